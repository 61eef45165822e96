"""Tyre stiffness and damping, thesis chapters 4-5: size parsing, the stiffness
formula, run conditions, regressions on pressure/speed/load/size, the spoke
damping model and the formula's accuracy.

Every public name of its submodules (their ``__all__``) is importable from
here; a submodule is imported on first use (:mod:`tyrelab._lazy`).
"""

from .._lazy import attach

__getattr__, __dir__ = attach(__name__)
