"""A scenario's variants: other values of its keys, its speeds and pressures, and a sweep's
combinations (issues 13, 37, 45).

:func:`with_overrides` (speeds, pressures: the command line's overrides) and :func:`with_values`
(any numeric key, checked as the file is) make one variant; :func:`parse_sets` reads ``--set``;
:func:`sweep_variants` expands a sweep into its variants (pressure pairs front-major, then the swept
keys' combinations, the last varying fastest), after :func:`pressure_axes` and
:func:`unused_key_problems` (what a sweep may ask: every swept key reaches the model, or the sweep is
refused naming it, before any work).

A sweep (``tyrelab ride --set KEY=V1,V2``, a quoted key of ``[sweep]``) replaces a numeric
scenario key in each variant (:func:`tyrelab.vehicle.scenario.with_values`). Some keys take no
part in some scenarios' models: a rigid seat has no natural frequency, a pitch-plane tractor no
lateral seat offset, a tyre whose stiffness and damping are given does not use its pressure. A
sweep of such a key would run identical variants under different labels, so
:func:`unused_key_problems` names each with the reason (one line per key, all at once).

The tyre pressures are the model's pressure axes: ``tyres.front.pressure_bar`` and
``tyres.rear.pressure_bar`` swept as keys are the same sweep as ``--front-pressure`` /
``--rear-pressure`` (:func:`pressure_axes`), so both give the same numbers and the same table.

The reasons follow :func:`tyrelab.vehicle.ride.build_parts` and
:func:`tyrelab.vehicle.model.assemble`; ``tests/hostile/test_hostile_sweeps.py`` sweeps every
numeric key of two scenarios (the plainest and the richest) and checks that each one either
changes the results or is refused naming it. A new key or a new use of one (lateral tyre
elements, issue 33) is added here.

Examples
--------
>>> from tyrelab.resources import scenarios_dir
>>> from tyrelab.scenario_io import load_scenario
>>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
>>> unused_key_problems(s, ["seat.natural_frequency_Hz", "seat.left_of_cg_m"])
['seat.left_of_cg_m: the pitch-plane model has no lateral seat offset (give tractor.roll_inertia_kg_m2, front_track_m and rear_track_m for the 3-D model)']
>>> pressure_axes(s, None, [1.0], {"tyres.front.pressure_bar": (1.4, 1.8), "tractor.mass_kg": (5e3,)})
([1.4, 1.8], [1.0], {'tractor.mass_kg': (5000.0,)}, ['tyres.front.pressure_bar', 'tyres.rear.pressure_bar'])
"""

from __future__ import annotations

import itertools
import math
from dataclasses import replace
from pathlib import Path

from ..units import km_h_to_m_s
from ... import _validate
from .limits import override_problems, scenario_problems, uses_spectral, work_problems, MAX_SAMPLES
from .parse import _build, _check_value, _validate as _check_doc, numeric_key
from .specs import Scenario, ScenarioError

__all__ = ["PRESSURE_KEYS", "MAX_SET_COMBINATIONS", "parse_sets", "with_values", "with_overrides", "pressure_axes",
           "unused_key_problems", "sweep_variants"]

#: Most combinations ``--set`` may ask for (its keys' values multiplied; the work bounds of a whole sweep
#: are :data:`tyrelab.vehicle.scenario.limits.MAX_VARIANTS` and ``MAX_SPECTRAL_VARIANTS``).
MAX_SET_COMBINATIONS = 10_000


def parse_sets(items) -> dict:
    """``["KEY=V1,V2", ...]`` (``tyrelab ride --set``) -> ``{"KEY": (V1, V2)}``, every problem at once.

    See Also
    --------
    with_values : a scenario with one combination of them.
    sweep_variants : every combination.

    Examples
    --------
    >>> parse_sets(["implement.mass_kg=500,1000", "tyres.rear.pressure_bar=1.2"])
    {'implement.mass_kg': (500.0, 1000.0), 'tyres.rear.pressure_bar': (1.2,)}
    """
    _validate.instances("items", items, str)
    out, problems = {}, []
    for item in items:
        key, sep, text = str(item).partition("=")
        key = key.strip()
        try:
            values = tuple(float(v) for v in text.split(",")) if sep and text.strip() else ()
        except ValueError:
            values = ()
        if numeric_key(key) is None:
            problems.append(f"--set {item!r}: {key!r} is not a numeric scenario key (e.g. implement.mass_kg)")
        elif not values or not all(math.isfinite(v) for v in values):
            problems.append(f"--set {item!r}: expected KEY=V1,V2,... with numbers")
        else:
            bad = [p for v in values for p in _check_value(f"--set {key}", {**numeric_key(key), "type": "number"}, v, None)]
            problems += bad[:1]
            out[key] = values
    n = math.prod(len(v) for v in out.values()) if out else 1
    if n > MAX_SET_COMBINATIONS:
        problems.append(f"--set: {n} combinations (at most {MAX_SET_COMBINATIONS})")
    if problems:
        raise ValueError("; ".join(problems))
    return out


def with_values(scenario: Scenario, values: dict) -> Scenario:
    """A copy of ``scenario`` with numeric keys replaced, ``{"section.key": value}``, checked as the
    file is (every problem at once, :class:`ScenarioError`); the ``[sweep]`` table is dropped.

    See Also
    --------
    with_overrides : speeds and pressures only.
    parse_sets : the values of ``--set``.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> with_values(s, {"tractor.mass_kg": 5000, "tyres.rear.pressure_bar": 1.4}).tractor.mass_kg
    5000.0
    """
    _validate.instance("scenario", scenario, Scenario)
    if not scenario.doc:
        raise ValueError("scenario: built in memory, not from TOML (with_values needs the parsed file)")
    doc = {k: (dict(v) if isinstance(v, dict) else v) for k, v in scenario.doc.items()}
    doc["tyres"] = {k: dict(v) for k, v in doc.get("tyres", {}).items()}
    doc.pop("sweep", None)
    for key, value in values.items():
        if numeric_key(key) is None:
            raise ScenarioError(scenario.path or "<scenario>", [f"{key!r}: not a numeric scenario key"])
        parts = key.split(".")
        node = doc
        for part in parts[:-1]:
            node = node.setdefault(part, {})
        node[parts[-1]] = float(value)
    where = str(scenario.path) if scenario.path is not None else "<scenario>"
    base = scenario.base_dir or Path(".")
    data = scenario.surface.profile_data  # the profile cannot be swept: its data as read
    road = scenario.surface.crg_data  # nor the CRG road (its window and the wheels' lines can)
    profiles: dict = {}
    # the profile path was checked when the scenario was read
    problems = _check_doc(doc, base, False, (lambda _path: data) if data is not None else None, profiles,
                         (lambda _path: road) if road is not None else None)
    if problems:
        raise ScenarioError(where, problems)
    out = _build(doc, scenario.path, base, False, profiles)
    problems = scenario_problems(out)  # what the model can represent (limits.LIMITS)
    if problems:
        raise ScenarioError(where, problems)
    return replace(out, exposure=replace(out.exposure, speeds_km_h=scenario.exposure.speeds_km_h,
                                         list_speeds_km_h=scenario.exposure.list_speeds_km_h))


def with_overrides(
    scenario: Scenario,
    speeds_km_h: list[float] | None = None,
    front_pressure_bar: float | None = None,
    rear_pressure_bar: float | None = None,
) -> Scenario:
    """A copy with other speeds and/or pressures (command-line overrides).

    Per-speed stiffness/damping lists keep applying to the scenario's own speeds
    (:func:`tyrelab.vehicle.ride.per_speed` interpolates them); pressures replace
    the tyre's pressure only.

    See Also
    --------
    with_values : any numeric key.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> o = with_overrides(s, speeds_km_h=[8.0], rear_pressure_bar=0.8)
    >>> o.exposure.speeds_km_h, o.rear.pressure_bar, o.front.pressure_bar == s.front.pressure_bar
    ((8.0,), 0.8, True)
    """
    s = scenario
    if speeds_km_h:
        if any(not (v > 0) for v in speeds_km_h):
            raise ValueError("speeds_km_h must be positive")
        s = replace(s, exposure=replace(s.exposure, speeds_km_h=tuple(float(v) for v in speeds_km_h)))
    if front_pressure_bar is not None:
        if not front_pressure_bar > 0:
            raise ValueError("front_pressure_bar must be positive")
        s = replace(s, front=replace(s.front, pressure_bar=float(front_pressure_bar)))
    if rear_pressure_bar is not None:
        if not rear_pressure_bar > 0:
            raise ValueError("rear_pressure_bar must be positive")
        s = replace(s, rear=replace(s.rear, pressure_bar=float(rear_pressure_bar)))
    return s


#: The scenario keys of the two pressure axes of a sweep.
PRESSURE_KEYS = {"front": "tyres.front.pressure_bar", "rear": "tyres.rear.pressure_bar"}
_THREE_D = "give tractor.roll_inertia_kg_m2, front_track_m and rear_track_m for the 3-D model"


def pressure_axes(scenario: Scenario, front_pressures_bar, rear_pressures_bar, keys: dict) -> tuple[list, list, dict]:
    """The front and rear pressures of a sweep and its other swept keys.

    Each axle's pressures come from the option (``--front-pressure``), else the swept key
    (:data:`PRESSURE_KEYS`, from ``--set`` or ``[sweep]``), else ``[sweep] *_pressures_bar``,
    else the tyre's own. An axle given both by an option and by a key is refused (ValueError naming
    both): one of them would be dropped.

    Returns
    -------
    fronts, rears : list of float
    others : dict
        ``keys`` without the pressure keys.
    asked : list of str
        The pressure keys given a value (by any of these), not left at the tyre's own.

    See Also
    --------
    sweep_variants : the sweep these axes span.
    parse_sets : the swept keys.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> pressure_axes(s, [1.2, 1.6], None, {"seat.damping_ratio": (0.2, 0.4)})[:3]
    ([1.2, 1.6], [1.2], {'seat.damping_ratio': (0.2, 0.4)})
    """
    _validate.instance("scenario", scenario, Scenario)
    others = dict(keys)
    out, asked = [], []
    for axle, given in (("front", front_pressures_bar), ("rear", rear_pressures_bar)):
        key = PRESSURE_KEYS[axle]
        swept = others.pop(key, None)
        if given and swept:
            raise ValueError(f"{key}: swept and given by --{axle}-pressure; give the {axle} pressures once")
        values = given or swept or getattr(scenario.sweep, f"{axle}_pressures_bar")
        if values:
            asked.append(key)
        out.append([float(v) for v in values or [getattr(scenario, axle).pressure_bar]])
    return out[0], out[1], others, asked


def _tyre_reason(scenario: Scenario, axle: str, name: str) -> str | None:
    spec = getattr(scenario, axle)
    k_given, c_given = spec.stiffness_kN_per_m is not None, spec.damping_kN_s_per_m is not None
    measured = bool(spec.measured_tyre_id)
    envelope = scenario.surface.enveloping
    if name == "pressure_bar" and k_given and c_given:
        return (f"tyres.{axle}.stiffness_kN_per_m and damping_kN_s_per_m are given, so the pressure changes no "
                "tyre value (remove them to take the pressure's stiffness and damping)")
    if name == "age_years" and (k_given or measured) and (c_given or measured):
        return ("the age enters only the stiffness formula and the damping model, and this tyre's stiffness and "
                "damping are " + ("measured" if measured and not (k_given and c_given) else "given"))
    if name == "footprint_m" and envelope not in ("tapered", "fixed"):
        return f"surface.enveloping = \"{envelope}\" uses no footprint (\"tapered\" and \"fixed\" do)"
    if name == "radius_m" and envelope != "rigid_band" and (envelope not in ("tapered", "fixed")
                                                          or spec.footprint_m is not None):
        return ("the radius gives the footprint (not given) of \"tapered\"/\"fixed\" enveloping and the tread "
                f"band of \"rigid_band\"; this scenario has surface.enveloping = \"{envelope}\""
                + (f" and tyres.{axle}.footprint_m" if spec.footprint_m is not None else ""))
    return None


def _reason(scenario: Scenario, key: str, values, spectral: bool = False) -> str | None:
    """Why ``key`` takes no part in ``scenario``'s results (None: it does; ``spectral``: the rows are
    the frequency-domain expectation, :mod:`tyrelab.vehicle.spectral_ride`)."""
    section, _, name = key.rpartition(".")
    t = scenario.tractor
    three_d, lateral = t.three_d, t.lateral_model != "none"
    if section in ("implement", "ballast") and getattr(scenario, section) is None:
        return f"the scenario has no [{section}] (add the table with its required keys to sweep it)"
    if section.startswith("tyres."):
        if name.startswith("lateral_") and not (three_d and lateral):
            return f"the tyres have no lateral element here (tractor.lateral_model, the 3-D model: {_THREE_D})"
        return _tyre_reason(scenario, section.split(".")[1], name)
    if section == "tractor":
        if name == "yaw_inertia_kg_m2" and not (three_d and lateral):
            return "the body yaws only with lateral tyre elements (tractor.lateral_model, the 3-D model)"
        if name.startswith("longitudinal_") and t.longitudinal_model == "none":
            return "tractor.longitudinal_model is \"none\" (no fore-aft tyre element)"
        if name == "cg_height_m" and t.longitudinal_model == "none" and not lateral and \
                scenario.implement is None and scenario.ballast is None:
            return ("the CG height enters through the fore-aft tyre element (tractor.longitudinal_model), an "
                    "[implement] or a [ballast]; this scenario has none (the seat's place is given from the CG)")
        return None
    if section == "seat":
        if name in ("natural_frequency_Hz", "damping_ratio") and scenario.seat.suspension != "linear":
            return f"seat.suspension is \"{scenario.seat.suspension}\" (a linear suspension seat has these)"
        if name == "left_of_cg_m" and not three_d:
            return f"the pitch-plane model has no lateral seat offset ({_THREE_D})"
        return None
    if section in ("front_axle", "rear_axle"):
        mount = getattr(scenario, section).mount
        if mount == "rigid" or (mount == "pivot" and name != "roll_inertia_kg_m2"):
            return (f"{section}.mount is \"{mount}\": the key applies to a "
                    f"{'suspended' if name != 'roll_inertia_kg_m2' else 'pivot or suspended'} axle")
        if name == "roll_inertia_kg_m2" and not three_d:
            return f"the pitch-plane model has no axle roll ({_THREE_D})"
        if name == "height_m" and not lateral:
            return ("the axle moves with the body fore-aft and sideways, and the tractor's mass and inertias hold "
                    "it already: its height enters no term of this model")
        return None
    if section == "cab":
        if scenario.cab.mount != "suspended":
            return "cab.mount is \"rigid\" (the cab is part of the body): the key applies to a suspended cab"
        if name == "roll_inertia_kg_m2" and not three_d:
            return f"the pitch-plane model has no cab roll ({_THREE_D})"
        return None
    if section == "implement":
        if name.startswith("hitch_") and scenario.implement.mount != "hitch_spring":
            return f"implement.mount is \"{scenario.implement.mount}\": the key applies to mount = \"hitch_spring\""
        if name == "roll_inertia_kg_m2" and not three_d:
            return f"the pitch-plane model has no roll ({_THREE_D})"
        return None
    if section == "ballast":
        if name == "roll_inertia_kg_m2" and not three_d:
            return f"the pitch-plane model has no roll ({_THREE_D})"
        return None
    if section == "surface":
        kind = scenario.surface.kind
        if name == "lead_in_m":
            return ("the level approach before the track changes no result: the tractor starts at rest and the "
                    "record starts as the front axle reaches the track")
        if name in ("spectrum_g0_m3", "spectrum_waviness") and kind != "profile":
            return f"surface.kind is \"{kind}\": a declared spectrum applies to kind = \"profile\""
        if name == "spectrum_waviness" and scenario.surface.spectrum_g0_m3 is None:
            return "the waviness applies to a declared spectrum (surface.spectrum_g0_m3)"
        if name in ("seed", "length_m", "dx_m") and kind == "profile":
            return "surface.kind is \"profile\": the track is the profile file's (its length and points)"
        if name in ("lateral_offset_m", "start_m", "file") and kind != "crg":
            return f"surface.kind is \"{kind}\": the key applies to kind = \"crg\""
        if name == "seed" and kind not in ("iso8608", "slatted"):
            return f"surface.kind is \"{kind}\": a seed draws a generated track (\"iso8608\", \"slatted\")"
        duration = scenario.simulation.duration_s
        if name == "length_m" and spectral and duration is not None and kind == "iso8608" and values and all(
                duration <= v / km_h_to_m_s(speed) for v in values for speed in scenario.exposure.speeds_km_h):
            return (f"spectral rows of a record of simulation.duration_s = {duration:g} s, shorter than the track at "
                    "every speed: the length changes no number (sweep it with --method time)")
        if name == "dx_m" and kind == "slatted":
            return "surface.kind is \"slatted\": the slats set the track's points"
        if name == "dx_m" and kind == "crg":
            return "surface.kind is \"crg\": the road file's grid sets the track's points"
        return None
    if key == "simulation.duration_s":
        longest = max(scenario.surface.length_m / km_h_to_m_s(v) for v in scenario.exposure.speeds_km_h)
        if values and all(v >= longest for v in values) and scenario.surface.kind != "profile":
            return (f"every value is at least the {longest:.3g} s the slowest speed takes over the track: each "
                    "record is the whole track")
        return None
    return None


def unused_key_problems(scenario: Scenario, keys, spectral: bool = False) -> list[str]:
    """One line per swept key that would change no result of ``scenario`` (``"KEY: why"``).

    Parameters
    ----------
    scenario : Scenario
    keys : dict or iterable of str
        The swept keys (``{"section.key": values}`` or the keys alone).
    spectral : bool
        The sweep's rows are spectral (:func:`tyrelab.vehicle.scenario.limits.uses_spectral`).

    See Also
    --------
    sweep_variants : refuses a sweep of such keys.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> unused_key_problems(s, ["seat.natural_frequency_Hz"])      # it changes the ride: no problem
    []
    """
    _validate.instance("scenario", scenario, Scenario)
    items = keys.items() if isinstance(keys, dict) else ((k, ()) for k in keys)
    problems = []
    for key, values in items:
        why = _reason(scenario, key, tuple(values), spectral)
        if why:
            problems.append(f"{key}: {why}")
    return problems


def sweep_variants(scenario: Scenario, front_pressures_bar=None, rear_pressures_bar=None, speeds_km_h=None,
                   sets: dict | None = None, method: str = "auto", max_variants: int | None = None,
                   max_samples: int | None = None, *, max_rows: int | None = None,
                   with_spectra: bool | str = False) -> list[tuple[Scenario, dict]]:
    """A sweep's variants, ``(scenario, swept values)``: each front × rear pressure pair (the
    :func:`pressure_axes`, however given) and every combination of the swept keys (``[sweep]`` and
    ``sets``), pressure pairs front-major, the last key varying fastest; checked before any is built.

    Raises
    ------
    ScenarioError
        A swept key (or a swept pressure) that the scenario's model does not use, each with the
        reason (:func:`unused_key_problems`).
    ValueError
        A pressure given by option and swept key both, values out of range, too much work
        (:func:`tyrelab.vehicle.scenario.limits.work_problems`: ``max_variants``, ``max_samples``,
        and ``max_rows`` spectral rows, ``with_spectra`` saying which have figure data).

    See Also
    --------
    tyrelab.vehicle.ride.ride_sweep : runs them.

    Examples
    --------
    >>> from tyrelab.resources import scenarios_dir
    >>> from tyrelab.scenario_io import load_scenario
    >>> s = load_scenario(scenarios_dir() / "modern_tractor.toml")
    >>> [(v.front.pressure_bar, v.rear.pressure_bar, combo) for v, combo in sweep_variants(s, [1.2, 1.6], [1.0])]
    [(1.2, 1.0, {}), (1.6, 1.0, {})]
    """
    _validate.instance("scenario", scenario, Scenario)
    fronts, rears, swept, pressures = pressure_axes(scenario, front_pressures_bar, rear_pressures_bar,
                                                    {**scenario.sweep.keys, **(sets or {})})
    combos = [dict(zip(swept, values)) for values in itertools.product(*swept.values())] if swept else [{}]
    bad = override_problems(speeds_km_h, fronts, rears)
    if bad:
        raise ValueError("; ".join(bad))
    n = len(fronts) * len(rears) * len(combos)
    spectral = uses_spectral(scenario, method, n)
    bad = unused_key_problems(scenario, pressures) + unused_key_problems(scenario, swept, spectral)
    if bad:  # a key that changes nothing would run identical variants under different labels
        raise ScenarioError(scenario.path or "<scenario>", bad)
    too_much = work_problems(scenario, n, speeds_km_h, max_variants=max_variants,
                             max_samples=max_samples or MAX_SAMPLES, method=method, max_rows=max_rows,
                             with_spectra=with_spectra)
    if too_much:  # before any work (the variants are not even built)
        raise ValueError("; ".join(too_much))
    out = []
    for pf in fronts:
        for pr_ in rears:
            for combo in combos:
                base = with_values(scenario, combo) if combo else scenario
                out.append((with_overrides(base, speeds_km_h, pf, pr_), combo))
    return out
