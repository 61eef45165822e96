"""The virtual dynamic tyre test vehicle (thesis ch. 3): the truth model of the
tyres, the instrument, the campaigns it records and the alternative experiments.

Every public name of its submodules (their ``__all__``) is importable from
here; a submodule is imported on first use (:mod:`tyrelab._lazy`).
"""

from .._lazy import attach

__getattr__, __dir__ = attach(__name__)
