"""Measured roads in OpenCRG files (issue 33): the wheels' tracks on a CRG road.

An OpenCRG file (ASAM; ``.crg``) holds a road as a grid of heights ``z(u, v)`` along and across
a reference line (``u`` m along it, ``v`` m to its left). It is read with the PyPI package
``pyopencrg`` (:func:`tyrelab.scenario_io.read_crg`; tyrelab has no CRG parser of its own);
this module takes the road and places the wheels on it:

* each wheel runs along its own line ``v = lateral_offset_m ± track / 2`` (left ``+``), with the
  front and rear track widths of the 3-D model, so front and rear wheels of different track
  widths take the heights the road has under each of them; the pitch-plane model (no track
  widths) runs all wheels along ``v = lateral_offset_m``;
* from ``start_m`` past the file's first cross section, for ``length_m`` (default: the rest of
  the file), sampled at the file's own spacing ``u_inc``;
* the height is the grid's (bilinear between grid points, as ``pyopencrg``'s ``uv_to_z``) plus
  the banking times ``v``; the reference line's own elevation (its longitudinal slope, a
  climb of the whole tractor at wavelengths far above its modes) is left out, as a CSV profile
  leaves it out. The file's modifiers (``$ROAD_CRG_MODS``) are not applied: the road as stored;
* a missing cell (NaN) under a wheel is refused (:func:`crg_problems` names the wheel and where),
  unless the scenario says ``fill_missing = true``: then the grid's NaN are filled as OpenCRG's
  own default does (``pyopencrg``'s ``fill_nan(mode=2)``: linear across a cross section between
  valid values, the last valid value of the cross section towards its edges).

Examples
--------
>>> import numpy as np, pyopencrg
>>> u, v = np.arange(0, 20.01, 0.05), np.arange(-1.5, 1.51, 0.1)
>>> road = pyopencrg.CrgRoad(np.outer(np.sin(u), np.ones(v.size)) * 0.01, u_inc=0.05, v=v)
>>> d = CrgData.of(road)
>>> x, tracks = wheel_tracks(d, {"front_left": 0.95, "front_right": -0.95}, start_m=0.0, length_m=10.0)
>>> float(x[-1]), bool(abs(tracks["front_left"][20] - 0.01 * np.sin(1.0)) < 1e-12)
(10.0, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ... import _validate
from .profiles import ROAD_HEIGHT_BOUNDS_M

__all__ = ["CrgData", "MAX_GRID_VALUES", "wheel_positions", "crg_problems", "wheel_tracks"]

#: Most grid values a CRG road may hold (20 million float64: 160 MB), a bound set before reading.
MAX_GRID_VALUES = 20_000_000


@dataclass(frozen=True, eq=False)
class CrgData:
    """A CRG road as read: the ``pyopencrg.CrgRoad`` and the numbers the checks need.

    Attributes
    ----------
    road : pyopencrg.CrgRoad
    name : str
        The file's name (for messages).
    u_start_m, u_inc_m, length_m : float
        First cross section, spacing and length of the road, m.
    v_min_m, v_max_m : float
        The road's width: lowest and highest ``v`` (m, left positive).
    """

    road: object
    name: str
    u_start_m: float
    u_inc_m: float
    length_m: float
    v_min_m: float
    v_max_m: float

    @classmethod
    def of(cls, road, name: str = "road.crg") -> "CrgData":
        """Describe a ``pyopencrg.CrgRoad``."""
        v = np.asarray(road.v, float)
        return cls(road, name, float(road.u_start), float(road.u_inc), float(road.length), float(v.min()),
                   float(v.max()))


def wheel_positions(lateral_offset_m: float, front_track_m: float | None, rear_track_m: float | None) -> dict:
    """``v`` (m, left positive) of each wheel's line: ``front_left``, ``front_right``, ``rear_left``,
    ``rear_right``; all on ``lateral_offset_m`` without track widths (the pitch-plane model).

    See Also
    --------
    wheel_tracks : the heights along those lines.

    Examples
    --------
    >>> wheel_positions(0.1, 1.8, 2.0)
    {'front_left': 1.0, 'front_right': -0.8, 'rear_left': 1.1, 'rear_right': -0.9}
    """
    offset = float(_validate.finite_array("lateral_offset_m", [lateral_offset_m])[0])
    out = {}
    for axle, name, t in (("front", "front_track_m", front_track_m), ("rear", "rear_track_m", rear_track_m)):
        half = 0.0 if t is None else 0.5 * _validate.positive(name, t)
        out[f"{axle}_left"] = offset + half
        out[f"{axle}_right"] = offset - half
    return out


def _window(data: CrgData, start_m: float, length_m: float | None) -> tuple[int, int]:
    """First and one-past-last cross section of the window ``start_m`` .. ``start_m + length_m``."""
    i0 = int(round(start_m / data.u_inc_m))
    n = data.road.nu - i0 if length_m is None else int(math.floor(length_m / data.u_inc_m + 1e-6)) + 1
    return i0, i0 + n


def crg_problems(data: CrgData, positions: dict, start_m: float, length_m: float | None,
                 fill_missing: bool = False) -> list[str]:
    """Every problem of driving the wheels ``positions`` (:func:`wheel_positions`) over ``data`` from
    ``start_m`` for ``length_m`` (None: to the end), one line each naming the key.

    See Also
    --------
    wheel_tracks : reads the road when there is none.

    Examples
    --------
    >>> import pyopencrg
    >>> u, v = np.arange(0, 20.01, 0.05), np.arange(-1.5, 1.51, 0.1)
    >>> d = CrgData.of(pyopencrg.CrgRoad(np.outer(np.sin(u), np.ones(v.size)) * 0.01, u_inc=0.05, v=v))
    >>> crg_problems(d, wheel_positions(0.0, 1.9, 1.9), 0.0, 10.0)
    []
    >>> [p.split(":")[0] for p in crg_problems(d, wheel_positions(0.0, 4.0, 4.0), 0.0, 30.0)][3:]  # off it, past its end
    ['surface.lateral_offset_m', 'surface.length_m']
    """
    _validate.instance("data", data, CrgData)
    _validate.instance("positions", positions, dict)
    problems = []
    for wheel, v in positions.items():
        if not data.v_min_m - 1e-9 <= v <= data.v_max_m + 1e-9:
            problems.append(f"surface.lateral_offset_m: the {wheel.replace('_', ' ')} wheel's line v = {v:g} m lies "
                            f"outside {data.name}'s width (v from {data.v_min_m:g} to {data.v_max_m:g} m; the track "
                            "widths and the offset place the wheels)")
    if start_m < 0 or start_m > data.length_m:
        problems.append(f"surface.start_m: {start_m:g} m is outside {data.name} (0 to {data.length_m:g} m)")
    elif length_m is not None and start_m + length_m > data.length_m + 1e-6 * max(1.0, data.length_m):
        problems.append(f"surface.length_m: {length_m:g} m from start_m = {start_m:g} m runs past the end of "
                        f"{data.name} ({data.length_m:g} m long)")
    if problems:
        return problems
    i0, i1 = _window(data, start_m, length_m)
    if i1 - i0 < 16:
        return [f"surface.length_m: {data.name} gives {i1 - i0} cross sections from start_m (need at least 16)"]
    z = np.asarray(data.road.z)[i0:i1]
    v_grid = np.asarray(data.road.v, float)
    banking = np.asarray(data.road.banking, float)[i0:i1]
    low, high = ROAD_HEIGHT_BOUNDS_M
    for wheel, v in positions.items():
        j = int(np.clip(np.searchsorted(v_grid, v), 1, v_grid.size - 1))
        cols = z[:, [j - 1, j]] if v_grid[j] != v else z[:, [j]]
        bad = np.flatnonzero(~np.isfinite(cols).all(axis=1))
        if bad.size and not fill_missing:
            u = data.u_start_m + (i0 + bad[0]) * data.u_inc_m
            problems.append(f"surface.file: {data.name} has {bad.size} missing heights (NaN) under the "
                            f"{wheel.replace('_', ' ')} wheel (v = {v:g} m), the first at u = {u:g} m; "
                            "fill_missing = true fills them as OpenCRG does")
        # the heights along the wheel's line (bilinear across v at the grid's u, plus the banking): the
        # same plausibility bound as a profile CSV's heights, before any track is built
        w = (v - v_grid[j - 1]) / (v_grid[j] - v_grid[j - 1]) if cols.shape[1] == 2 else 1.0
        h = (cols[:, 0] * (1.0 - w) + cols[:, -1] * w if cols.shape[1] == 2 else cols[:, 0]) + banking * v
        h = h[np.isfinite(h)]
        if h.size and (h.min() < low or h.max() > high):
            problems.append(f"surface.file: {data.name}'s heights under the {wheel.replace('_', ' ')} wheel (v = {v:g} m) "
                            f"must be within {low:g} to {high:g} m, as a profile's (found {h.min():g} to {h.max():g} m: "
                            "millimetres stored as metres?)")
    return problems


def wheel_tracks(data: CrgData, positions: dict, start_m: float = 0.0, length_m: float | None = None,
                 fill_missing: bool = False) -> tuple[np.ndarray, dict]:
    """Distance from ``start_m`` (m, the file's spacing) and each wheel's heights (m) along its line.

    Parameters
    ----------
    data : CrgData
    positions : dict
        Wheel -> ``v`` of its line, m (:func:`wheel_positions`).
    start_m, length_m : float
        The window along the road from its first cross section, m (``length_m`` None: to the end).
    fill_missing : bool
        Fill the grid's NaN as OpenCRG does (module docstring); otherwise a NaN under a wheel is
        a ValueError (:func:`crg_problems` says where).

    Returns
    -------
    x_m : ndarray
        0, ``u_inc``, ... along the window.
    heights : dict
        Wheel -> heights, m (grid plus banking times ``v``; no reference-line elevation).

    See Also
    --------
    wheel_positions : the lines' lateral positions.
    crg_problems : what stops the wheels from driving the road.

    Examples
    --------
    >>> import pyopencrg
    >>> u, v = np.arange(0, 20.01, 0.05), np.arange(-1.5, 1.51, 0.1)
    >>> d = CrgData.of(pyopencrg.CrgRoad(np.outer(np.sin(u), np.ones(v.size)) * 0.01, u_inc=0.05, v=v))
    >>> x, tracks = wheel_tracks(d, wheel_positions(0.0, 1.9, 1.9), start_m=2.0, length_m=10.0)
    >>> float(x[-1]), sorted(tracks), round(float(tracks["rear_right"][0]), 6) == round(float(0.01 * np.sin(2.0)), 6)
    (10.0, ['front_left', 'front_right', 'rear_left', 'rear_right'], True)
    """
    _validate.instance("data", data, CrgData)
    problems = crg_problems(data, positions, start_m, length_m, fill_missing)
    if problems:
        raise ValueError("; ".join(problems))
    road = data.road
    i0, i1 = _window(data, start_m, length_m)
    if fill_missing and not np.isfinite(np.asarray(road.z)).all():
        road = road.fill_nan(mode=2)
    u = np.asarray(road.u, float)[i0:i1]
    banking = np.asarray(road.banking, float)[i0:i1]
    heights = {}
    for wheel, v in positions.items():
        h = np.asarray(road.uv_to_z(u, np.full(u.size, v), grid_only=True), float) + banking * v
        heights[wheel] = h
    return (np.arange(i1 - i0) * data.u_inc_m), heights
