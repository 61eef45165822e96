"""Table Schemas shipped with tyrelab (installed as ``tyrelab.schemas``; see :mod:`tyrelab.resources`)."""
