"""A linear time-invariant model with named states, inputs and outputs (issue 45: the record
:meth:`~tyrelab.vehicle.model.Assembly.linear` and :meth:`~tyrelab.vehicle.model.SeatSuspension.linear`
return)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["LinearModel"]


@dataclass(frozen=True)
class LinearModel:
    """``x' = A x + B w``, ``y = C x + D w`` with named states, inputs and outputs."""

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray
    states: tuple[str, ...]
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]

    def select(self, outputs) -> "LinearModel":
        """The same system with only the outputs ``outputs`` (names), in that order."""
        rows = [self.outputs.index(o) for o in outputs]
        return LinearModel(self.a, self.b, self.c[rows], self.d[rows], self.states, self.inputs, tuple(outputs))

    @property
    def abcd(self):
        """``(A, B, C, D)``."""
        return self.a, self.b, self.c, self.d
