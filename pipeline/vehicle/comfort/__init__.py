"""What the driver feels: ISO 2631-1 (weighting, a_w, VDV, A(8)) and ISO 2631-5, the Directive's day (daily exposure, hours to EAV/ELV), one streamed analysis of a recording, the accuracy measures of thesis §6.4/§7.4.

Each module's public names are importable from here too, on first use (:mod:`tyrelab._lazy`).
"""

from ..._lazy import attach

__getattr__, __dir__ = attach(__name__)
