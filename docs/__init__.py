"""The project's documents (installed as ``tyrelab.docs``): the report renders the ones its pages link to
(:mod:`tyrelab.report.docs`; see :mod:`tyrelab.resources`)."""
