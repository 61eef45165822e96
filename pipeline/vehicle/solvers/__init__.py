"""Solutions of an assembled model: the exact first-order-hold LTI step, the time domain (exact in contact, RK4 across lift-off), the undamped modes.

Each module's public names are importable from here too, on first use (:mod:`tyrelab._lazy`).
"""

from ..._lazy import attach

__getattr__, __dir__ = attach(__name__)
