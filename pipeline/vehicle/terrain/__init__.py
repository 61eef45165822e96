"""The ground under the tyres: profiles (the slatted track, ISO 8608 tracks, their spectra and coherence), measured roads (OpenCRG), the ISO 8608 class of a road, the tyre's enveloping filter.

Each module's public names are importable from here too, on first use (:mod:`tyrelab._lazy`).
"""

from ..._lazy import attach

__getattr__, __dir__ = attach(__name__)
