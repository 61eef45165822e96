"""The apparent-mass method of thesis chapter 3: tyre force, apparent mass, K and C,
QC, the daily force-plate check, the alternative methods of Table I, and
:func:`analyze_recording` for one recording.

Every public name of its submodules (their ``__all__``) is importable from
here; a submodule is imported on first use (:mod:`tyrelab._lazy`).
"""

from .._lazy import attach

__getattr__, __dir__ = attach(__name__)
