"""jinja2 templates of the report (installed as ``tyrelab.templates``; see :mod:`tyrelab.resources`)."""
