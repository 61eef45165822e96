"""Data shipped with tyrelab: the tyre catalogue (thesis Table II), the digitised thesis tables and
example ride scenarios (installed as ``tyrelab.data``; see :mod:`tyrelab.resources`).

Your own recordings do not go here: keep campaigns in a folder of your own and pass it as
``tyrelab run --raw DIR`` (``make all`` writes the demo campaign to ``raw/demo/``, which is not shipped).
"""
