"""Shared check of the thesis/ours/difference columns of comparison tables."""

from __future__ import annotations

import numpy as np
import pandas as pd

from tyrelab.report.tables import find_pairs


def assert_differences_are_ours_minus_thesis(t: pd.DataFrame, name: str) -> int:
    """Every thesis/ours/difference triple holds ours − thesis; returns the non-zero cases seen."""
    nonzero = 0
    pairs = [p for p in find_pairs(t.columns) if p.difference]
    assert pairs, f"{name}: no thesis/ours/difference columns"
    for p in pairs:
        both = t[[p.thesis, p.ours, p.difference]].apply(pd.to_numeric, errors="coerce").dropna()
        np.testing.assert_allclose(both[p.difference], both[p.ours] - both[p.thesis], atol=1e-9,
                                   err_msg=f"{name}.{p.difference} is not {p.ours} - {p.thesis}")
        nonzero += int((both[p.difference].abs() > 1e-9).sum())
    return nonzero
