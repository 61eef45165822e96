"""Predictions checked against recordings (thesis §6.4, §7.4).

Each module's public names are importable from here too, on first use (:mod:`tyrelab._lazy`).
"""

from ..._lazy import attach

__getattr__, __dir__ = attach(__name__)
