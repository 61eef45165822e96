"""HTML report rendering: jinja2 templates in ``reports/``, output in ``build/reports/``."""
