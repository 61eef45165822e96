"""Vehicle simulators and ride metrics, thesis chapters 6-8: road profiles, tyre
enveloping, the carriage and tractor simulators, the bounce/pitch predictor,
ISO 2631 and spectral metrics.

Every public name of its submodules (their ``__all__``) is importable from
here; a submodule is imported on first use (:mod:`tyrelab._lazy`).
"""

from .._lazy import attach

__getattr__, __dir__ = attach(__name__)
