"""Ride scenario files, parsed and checked: a tractor, its tyres, a track and speeds, in TOML (issue 13).

A scenario's text is parsed with the standard library's :mod:`tomllib` and checked
against ``schemas/scenario.json`` (every key, its type, unit and bounds are
documented there; :func:`key_table` prints them). Every problem is collected
and :class:`ScenarioError` lists them all at once, so a user fixes a file in
one pass. The result is a tree of small frozen dataclasses; nothing is
computed here (stiffness, profiles and the simulation live in
:mod:`tyrelab.vehicle.ride`), and no file is read: :mod:`tyrelab.scenario_io` reads scenario files
and track profiles and passes them in.

Example (``raw/scenarios/modern_tractor.toml`` is a complete one)::

    name = "my tractor"
    [tractor]
    mass_kg = 4700
    pitch_inertia_kg_m2 = 5500
    front_distance_m = 1.56
    rear_distance_m = 0.95
    cg_height_m = 0.95
    [tyres.front]
    size = "14.9R28"
    pressure_bar = 1.6
    [tyres.rear]
    size = "18.4R38"
    pressure_bar = 1.2
    [surface]
    kind = "iso8608"
    class = "C"
    [exposure]
    speeds_km_h = [4, 8, 12, 16]
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping
import unicodedata
from functools import cache
from pathlib import Path

import pandas as pd

from ... import _validate as _checks
from ...schema import load_schema
from ...tyre.sizes import TyreSizeError, parse_tyre_size
from ..model import cab_mount_problems, needs, pivot_problem, scenario_key
from .limits import LIMITS, long_integer_problems, scenario_problems
from .specs import (AxleSpec, BallastSpec, CabSpec, ExposureSpec, ImplementSpec, Scenario, ScenarioError, SeatSpec,
                    SimulationSpec, SurfaceSpec, SweepSpec, TractorSpec, TyreSpec)

__all__ = ["parse_scenario", "scenario_from_dict", "key_table", "numeric_key"]


@cache
def _sections() -> dict[str, dict]:
    """Section name -> {field name -> field dict} from ``schemas/scenario.json``."""
    schema = load_schema("scenario")["sections"]
    out = {}
    for name, sec in schema.items():
        src = schema[sec["same_as"]] if "same_as" in sec else sec
        out[name] = {"required": sec.get("required", False), "fields": {f["name"]: f for f in src["fields"]}}
    return out


def key_table() -> pd.DataFrame:
    """Every scenario key with its section, type, unit, default and description.

    See Also
    --------
    numeric_key : one key's field.
    parse_scenario : checks a scenario against it.

    Examples
    --------
    >>> t = key_table()
    >>> t.loc[t["key"] == "mass_kg", ["section", "unit"]].values.tolist()[:2]
    [['tractor', 'kg'], ['front_axle', 'kg']]
    """
    rows = []
    for sec, spec in _sections().items():
        for name, f in spec["fields"].items():
            c = f.get("constraints", {})
            rows.append({"section": sec, "key": name, "type": f["type"], "unit": f.get("unit", ""),
                         "required": bool(c.get("required", False)), "default": f.get("default"),
                         "description": f.get("description", "")})
    return pd.DataFrame(rows)


def _control_characters(text: str, allowed: str = "") -> str:
    r"""The control characters (Unicode category Cc: NUL, ESC, newline, DEL, C1) in ``text`` other than
    ``allowed``, as escapes (``"U+001B, U+000A"``); empty when there are none.

    Examples
    --------
    >>> _control_characters("tractor\x1b[2J\n"), _control_characters("a\tb", allowed="\t")
    ('U+001B, U+000A', '')
    """
    found = dict.fromkeys(c for c in text if unicodedata.category(c) == "Cc" and c not in allowed)
    return ", ".join(f"U+{ord(c):04X}" for c in found)


def _is_number(v) -> bool:
    """A finite real number: no bool, no NaN or infinity, no integer too large for a float (``1``
    and 400 zeros, which TOML holds exactly: False, never an OverflowError)."""
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return False
    try:
        return math.isfinite(v)
    except OverflowError:
        return False


def _check_value(where: str, f: dict, value, n_speeds: int | None) -> list[str]:
    """Problems of one value against its field definition."""
    t = f["type"]
    c = f.get("constraints", {})
    unit = f" {f['unit']}" if f.get("unit") and f["unit"] != "1" else ""
    if t == "string":
        if not isinstance(value, str):
            return [f"{where}: expected text, got {value!r}"]
        control = _control_characters(value, allowed="\t\n" if where == "description" else "")
        if control:  # they would reach the terminal, the page and the report as they are
            return [f"{where}: holds control characters ({control}): give printable text"]
        if "enum" in c and value not in c["enum"]:
            return [f"{where}: {value!r} is not one of {', '.join(c['enum'])}"]
        return []
    if t == "boolean":
        return [] if isinstance(value, bool) else [f"{where}: expected true or false, got {value!r}"]
    if t == "integer":
        return [] if isinstance(value, int) and not isinstance(value, bool) else [f"{where}: expected an integer, got {value!r}"]
    if t in ("numbers", "number_or_numbers"):
        if t == "number_or_numbers" and _is_number(value):
            values = [value]
        elif isinstance(value, list) and value and all(_is_number(v) for v in value):
            values = value
            if t == "number_or_numbers" and n_speeds is not None and len(value) != n_speeds:
                return [f"{where}: {len(value)} values but exposure.speeds_km_h has {n_speeds} (give one per speed)"]
        else:
            return [f"{where}: expected {'a number or ' if t == 'number_or_numbers' else ''}a list of numbers, got "
                    f"{_checks.shown(value)}"]
    elif t == "number":
        if not _is_number(value):
            return [f"{where}: expected a number, got {_checks.shown(value)}"]
        values = [value]
    else:  # pragma: no cover - schema typo
        raise ValueError(f"schema type {t!r}")
    problems = []
    for v in values:
        if "exclusiveMinimum" in c and not v > c["exclusiveMinimum"]:
            problems.append(f"{where}: {v}{unit} must be greater than {c['exclusiveMinimum']}")
        elif "minimum" in c and v < c["minimum"]:
            problems.append(f"{where}: {v}{unit} is negative" if c["minimum"] == 0 else f"{where}: {v}{unit} is below {c['minimum']}")
        elif "maximum" in c and v > c["maximum"]:
            problems.append(f"{where}: {v}{unit} is above {c['maximum']}")
    return problems[:1]


def _section_values(doc: dict, name: str) -> tuple[dict | None, list[str]]:
    """The table of section ``name`` (dotted) in ``doc``, or None, and type problems."""
    node = doc
    for part in name.split("."):
        if not isinstance(node, dict) or part not in node:
            return None, []
        node = node[part]
    if not isinstance(node, dict):
        return None, [f"[{name}] must be a table, got {node!r}"]
    return node, []


def _validate(doc: dict, base_dir: Path, confine: bool = True, read_profile=None,
              profiles: dict | None = None, read_crg=None) -> list[str]:
    """Every problem of a parsed TOML document (empty list when it is valid); a profile read with
    ``read_profile`` (a CRG road with ``read_crg``) goes to ``profiles``."""
    problems: list[str] = []
    profiles = {} if profiles is None else profiles
    sections = _sections()
    # unknown keys and tables at every level
    known_top = {k for k in sections[""]["fields"]} | {s.split(".")[0] for s in sections if s}
    if isinstance(doc.get("tyres"), dict):
        for k in doc["tyres"]:
            if k not in ("front", "rear"):
                problems.append(f"unknown table [tyres.{k}] (expected [tyres.front] and [tyres.rear])")
    speeds = doc.get("exposure", {}).get("speeds_km_h") if isinstance(doc.get("exposure"), dict) else None
    n_speeds = len(speeds) if isinstance(speeds, list) else None
    for sec, spec in sections.items():
        values, p = (doc, []) if sec == "" else _section_values(doc, sec)
        problems += p
        if values is None:
            if spec["required"] and not p:
                problems.append(f"missing table [{sec}]")
            continue
        label = (lambda k: k) if sec == "" else (lambda k, s=sec: f"{s}.{k}")
        for k, v in values.items():
            if sec == "" and k in known_top and k not in spec["fields"]:
                continue  # a table, checked as its own section
            if sec == "sweep" and "." in k:
                problems += _sweep_key_problems(k, v)
                continue
            if k not in spec["fields"]:
                known = sorted(known_top) if sec == "" else list(spec["fields"])
                problems.append(f"unknown key {label(k)!r} (known: {', '.join(known)})")
                continue
            problems += _check_value(label(k), spec["fields"][k], v, n_speeds)
        for k, f in spec["fields"].items():
            if f.get("constraints", {}).get("required") and k not in values:
                unit = f" ({f['unit']})" if f.get("unit") else ""
                problems.append(f"missing {label(k)}{unit}")
    # cross-field rules
    for axle in ("front", "rear"):
        t, _ = _section_values(doc, f"tyres.{axle}")
        if t and isinstance(t.get("size"), str):
            try:
                parse_tyre_size(t["size"])
            except TyreSizeError as exc:
                problems.append(f"tyres.{axle}.size: {exc}")
    seat, _ = _section_values(doc, "seat")
    if seat and seat.get("suspension") == "linear":
        for k in ("natural_frequency_Hz", "damping_ratio"):
            if k not in seat:
                problems.append(f"seat.{k} is required with suspension = \"linear\"")
    problems += _parts_problems(doc)
    ex, _ = _section_values(doc, "exposure")
    if ex and _is_number(ex.get("working_speed_km_h")) and isinstance(ex.get("speeds_km_h"), list) \
            and ex["working_speed_km_h"] not in ex["speeds_km_h"]:
        problems.append(f"exposure.working_speed_km_h: {ex['working_speed_km_h']:g} km/h is not one of "
                        f"exposure.speeds_km_h ({', '.join(f'{v:g}' for v in ex['speeds_km_h'] if _is_number(v))})")
    surf, _ = _section_values(doc, "surface")
    if surf:
        kind = surf.get("kind")
        if kind == "iso8608" and "class" not in surf:
            problems.append("surface.class (A-H) is required with kind = \"iso8608\"")
        if kind == "profile":
            if "profile" not in surf:
                problems.append("surface.profile (a CSV path) is required with kind = \"profile\"")
            elif isinstance(surf["profile"], str):
                problems += _profile_problems(base_dir, surf["profile"], confine, read_profile, profiles)
        if kind == "crg":
            problems += _crg_problems(doc, surf, base_dir, confine, read_crg, profiles)
    return problems


def _crg_problems(doc: dict, surf: dict, base_dir: Path, confine: bool, read_crg, profiles: dict) -> list[str]:
    """``kind = "crg"``: the file is there and readable (``read_crg``: path -> :class:`tyrelab.vehicle.crg.CrgData`),
    and every wheel's line lies on the road with heights from ``start_m`` for ``length_m``."""
    if "file" not in surf:
        return ["surface.file (an OpenCRG .crg path) is required with kind = \"crg\""]
    if not isinstance(surf["file"], str):
        return []  # the type problem is listed already
    full, problem = _resolve_inside(base_dir, surf["file"], confine, "surface.file")
    if problem:
        return [problem]
    if read_crg is None:
        return [f"surface.file {surf['file']!r}: no CRG reader given (tyrelab.scenario_io.parse_scenario and "
                "load_scenario read CRG files)"]
    try:
        data = read_crg(full)
    except ValueError as exc:  # the file named as the scenario names it (no path of this machine in a table)
        text = str(exc)
        return [f"surface.file: {surf['file']}: {text[len(str(full)) + 2:]}" if text.startswith(f"{full}: ")
                else f"surface.file: {text}"]
    profiles[full] = data
    gap_problem = []
    if data.u_inc_m > LIMITS["profile.gap_m"][1]:  # as a profile CSV's distances
        gap_problem = [f"surface.file: {data.name}'s cross sections are {data.u_inc_m:g} m apart, above "
                       f"{LIMITS['profile.gap_m'][1]:g} m"]
    tractor, _ = _section_values(doc, "tractor")
    tractor = tractor or {}
    numbers = {k: surf.get(k, d) for k, d in (("lateral_offset_m", 0.0), ("start_m", 0.0))}
    length = surf.get("length_m")
    if not all(_is_number(v) for v in numbers.values()) or (length is not None and not _is_number(length)):
        return gap_problem  # the rest listed as type problems
    three_d = "roll_inertia_kg_m2" in tractor
    tracks = [tractor.get(k) if three_d else None for k in ("front_track_m", "rear_track_m")]
    if any(t is not None and not _is_number(t) for t in tracks):
        return gap_problem
    from ..crg import crg_problems, wheel_positions

    return gap_problem + crg_problems(data, wheel_positions(numbers["lateral_offset_m"], *tracks), float(numbers["start_m"]),
                        None if length is None else float(length), bool(surf.get("fill_missing", False)))


def _given(table: dict | None, key: str) -> bool:
    return bool(table) and _is_number(table.get(key))


def _parts_problems(doc: dict) -> list[str]:
    """Problems between the keys of the tractor's parts (issue 23): what each mount needs, the
    3-D model's track widths, the seat inside a suspended cab."""
    problems: list[str] = []
    tractor, _ = _section_values(doc, "tractor")
    tractor = tractor or {}
    three_d = "roll_inertia_kg_m2" in tractor
    if three_d:
        for k in ("front_track_m", "rear_track_m"):
            if k not in tractor:
                problems.append(f"tractor.{k} is required with tractor.roll_inertia_kg_m2 (the 3-D model)")
    else:
        for k in ("front_track_m", "rear_track_m"):
            if k in tractor:
                problems.append(f"tractor.{k} needs tractor.roll_inertia_kg_m2 (the 3-D model); without it the "
                                "tracks are averaged")
        if tractor.get("lateral_model", "none") != "none" or "yaw_inertia_kg_m2" in tractor:
            key = "lateral_model" if tractor.get("lateral_model", "none") != "none" else "yaw_inertia_kg_m2"
            problems.append(f"tractor.{key} needs tractor.roll_inertia_kg_m2 (the 3-D model: lateral tyre "
                            "elements move the body sideways, in roll and in yaw)")
        if tractor.get("longitudinal_model") == "rolling":
            problems.append("tractor.longitudinal_model = \"rolling\" needs tractor.roll_inertia_kg_m2 (the 3-D "
                            "model; the pitch plane keeps the thesis' elements of §7.3 and §7.5)")
        for axle in ("front", "rear"):
            ty, _ = _section_values(doc, f"tyres.{axle}")
            for k in ("lateral_stiffness_kN_per_m", "lateral_damping_kN_s_per_m",
                      "lateral_series_damping_kN_s_per_m_km_h"):
                if ty and k in ty:
                    problems.append(f"tyres.{axle}.{k} needs the 3-D model (tractor.roll_inertia_kg_m2 and the "
                                    "track widths)")
    if three_d:  # issue 42: a series damper's a applies to the rolling element only
        lateral = tractor.get("lateral_model", "rolling")
        for axle in ("front", "rear"):
            ty, _ = _section_values(doc, f"tyres.{axle}")
            if ty and "lateral_series_damping_kN_s_per_m_km_h" in ty and lateral != "rolling":
                problems.append(f"tyres.{axle}.lateral_series_damping_kN_s_per_m_km_h applies to "
                                f"tractor.lateral_model = \"rolling\", not {lateral!r}")
    if "longitudinal_series_damping_kN_s_per_m_km_h" in tractor and tractor.get("longitudinal_model") != "rolling":
        problems.append("tractor.longitudinal_series_damping_kN_s_per_m_km_h applies to longitudinal_model = "
                        f"\"rolling\", not {tractor.get('longitudinal_model', 'none')!r}")
    for axle in ("front_axle", "rear_axle"):
        t, _ = _section_values(doc, axle)
        if not t:
            continue
        mount = t.get("mount", "rigid")
        if mount == "pivot" and not three_d:
            problems.append(pivot_problem(axle))
        problems += _missing(axle, t, needs("axle", mount, three_d), f" with mount = \"{mount}\"")
        if mount == "rigid":
            extra = sorted(k for k in t if k != "mount")
            if extra:
                problems.append(f"{axle}: {', '.join(extra)} apply to a pivot or suspended axle, not mount = \"rigid\"")
    mounts = {axle: (_section_values(doc, axle)[0] or {}).get("mount", "rigid") for axle in ("front_axle", "rear_axle")}
    if three_d and "rigid" not in mounts.values():
        problems.append(f"front_axle.mount = \"{mounts['front_axle']}\" and rear_axle.mount = \"{mounts['rear_axle']}\": "
                        "nothing holds the body in roll (a pivot or suspended axle passes no roll moment); make one "
                        "axle rigid")
    surf, _ = _section_values(doc, "surface")
    if surf and surf.get("tracks") == "isotropic" and not three_d:
        problems.append("surface.tracks = \"isotropic\" needs the track widths of the 3-D model "
                        "(tractor.roll_inertia_kg_m2, front_track_m, rear_track_m)")
    cab, _ = _section_values(doc, "cab")
    if cab and cab.get("mount", "rigid") == "suspended":
        problems += _missing("cab", cab, needs("cab", "suspended", three_d), " with mount = \"suspended\"")
        if _given(cab, "front_mount_ahead_of_cg_m") and _given(cab, "rear_mount_ahead_of_cg_m"):
            front, rear = cab["front_mount_ahead_of_cg_m"], cab["rear_mount_ahead_of_cg_m"]
            problems += cab_mount_problems(front, rear)
            seat, _ = _section_values(doc, "seat")
            seat = seat or {}
            x, y = seat.get("ahead_of_cg_m", 0.0), seat.get("left_of_cg_m", 0.0)
            if _is_number(x) and not rear <= x <= front:
                problems.append(f"seat.ahead_of_cg_m = {x} m lies outside the cab (its mounts are from {rear} to "
                                f"{front} m ahead of the CG)")
            half = cab.get("mount_track_m")
            if _is_number(y) and _is_number(half) and abs(y) > half / 2:
                problems.append(f"seat.left_of_cg_m = {y} m lies outside the cab (its mounts are {half} m apart)")
    imp, _ = _section_values(doc, "implement")
    if imp:
        problems += _missing("implement", imp, needs("implement"), "")
        if imp.get("mount") == "hitch_spring":
            problems += _missing("implement", imp, needs("implement", "hitch_spring")[len(needs("implement")):],
                                 " with mount = \"hitch_spring\"")
    ballast, _ = _section_values(doc, "ballast")
    if ballast:
        problems += _missing("ballast", ballast, needs("ballast"), "")
    return problems


def _missing(section: str, table: dict, fields, why: str) -> list[str]:
    """The part fields :func:`tyrelab.vehicle.model.needs` names that ``table`` lacks, as its keys."""
    return [f"{section}.{scenario_key(f)} is required{why}" for f in fields if scenario_key(f) not in table]


def _resolve_inside(base_dir: Path, relative: str, confine: bool = True,
                    key: str = "surface.profile") -> tuple[Path | None, str | None]:
    """``base_dir / relative`` if it stays inside ``base_dir``, else a problem naming ``key``; without
    ``confine`` (a scenario file the user names) any path, absolute or relative to ``base_dir``."""
    if "\0" in relative:
        return None, f"{key} {relative!r}: a path cannot hold a NUL character"
    rel = Path(relative)
    if not confine:
        return (base_dir / rel).resolve(), None
    if rel.is_absolute():
        return None, f"{key} {relative!r}: give a path relative to the scenario file"
    full = (base_dir / rel).resolve()
    if not full.is_relative_to(base_dir.resolve()):
        return None, f"{key} {relative!r} escapes the scenario's folder"
    return full, None


def _profile_problems(base_dir: Path, relative: str, confine: bool, read_profile, profiles: dict) -> list[str]:
    """Resolve ``surface.profile`` and read it with the caller's ``read_profile`` (path -> distance,
    left, right); the data go to ``profiles`` (full path -> data) for :func:`_build`."""
    full, problem = _resolve_inside(base_dir, relative, confine)
    if problem:
        return [problem]
    if read_profile is None:
        return [f"surface.profile {relative!r}: no profile reader given (tyrelab.scenario_io.parse_scenario "
                "and load_scenario read profiles)"]
    try:
        profiles[full] = read_profile(full)
    except ValueError as exc:
        return [f"surface.profile: {exc}"]
    return []


def _float_or_none(v):
    return None if v is None else float(v)


def _speed_values(v):
    return tuple(float(x) for x in v) if isinstance(v, list) else (None if v is None else float(v))


def _floats(table: dict) -> dict:
    """A table's values with numbers as floats (text and booleans as they are)."""
    return {k: (v if isinstance(v, (str, bool)) else float(v)) for k, v in table.items()}


def _build(doc: dict, path: Path | None, base_dir: Path, confine: bool = True, profiles: dict | None = None) -> Scenario:
    t, s, surf, ex = doc["tractor"], doc.get("seat", {}), doc["surface"], doc["exposure"]
    sim = doc.get("simulation", {})
    sweep = doc.get("sweep", {})

    def tyre(axle: str) -> TyreSpec:
        d = doc["tyres"][axle]
        return TyreSpec(
            size=d["size"], pressure_bar=float(d["pressure_bar"]), traction=bool(d.get("traction", axle == "rear")),
            stiffness_kN_per_m=_speed_values(d.get("stiffness_kN_per_m")),
            damping_kN_s_per_m=_speed_values(d.get("damping_kN_s_per_m")),
            measured_tyre_id=d.get("measured_tyre_id"), water_ballast=bool(d.get("water_ballast", False)),
            age_years=float(d.get("age_years", 1.0)), radius_m=d.get("radius_m"), footprint_m=d.get("footprint_m"),
            formula=str(d.get("formula", "thesis")),
            lateral_stiffness_kN_per_m=_float_or_none(d.get("lateral_stiffness_kN_per_m")),
            lateral_damping_kN_s_per_m=_float_or_none(d.get("lateral_damping_kN_s_per_m")),
            lateral_series_damping_kN_s_per_m_km_h=_float_or_none(d.get("lateral_series_damping_kN_s_per_m_km_h")),
        )

    t = dict(t)
    three_d = "roll_inertia_kg_m2" in t
    if three_d and "lateral_model" not in t:
        t["lateral_model"] = "rolling"  # issues 33, 42: a 3-D scenario's tyres have rolling lateral elements
    s = dict(s)
    s.setdefault("gravity_tilt", three_d)  # issue 42: ISO 2631-1's seat pad is body-fixed (3-D)

    profile = _resolve_inside(base_dir, surf["profile"], confine)[0] if "profile" in surf else None
    crg_file = _resolve_inside(base_dir, surf["file"], confine, "surface.file")[0] \
        if surf.get("kind") == "crg" and "file" in surf else None
    crg_data = (profiles or {}).get(crg_file) if crg_file is not None else None
    length_m = float(surf.get("length_m", 400.0))
    if crg_data is not None and "length_m" not in surf:  # the rest of the file
        length_m = crg_data.length_m - float(surf.get("start_m", 0.0))
    return Scenario(
        name=doc["name"],
        description=doc.get("description", ""),
        tractor=TractorSpec(**_floats(t)),
        seat=SeatSpec(**{k: (v if isinstance(v, (str, bool)) else float(v)) for k, v in s.items()}),
        front_axle=AxleSpec(**_floats(doc.get("front_axle", {}))),
        rear_axle=AxleSpec(**_floats(doc.get("rear_axle", {}))),
        cab=CabSpec(**_floats(doc.get("cab", {}))),
        implement=ImplementSpec(**_floats(doc["implement"])) if "implement" in doc else None,
        ballast=BallastSpec(**_floats(doc["ballast"])) if "ballast" in doc else None,
        front=tyre("front"),
        rear=tyre("rear"),
        surface=SurfaceSpec(
            kind=surf["kind"], road_class=surf.get("class"), length_m=length_m,
            seed=int(surf.get("seed", 1)), dx_m=float(surf.get("dx_m", 0.05)), profile=profile,
            spectrum_g0_m3=surf.get("spectrum_g0_m3"), spectrum_waviness=float(surf.get("spectrum_waviness", 2.0)),
            spectrum_correlated=surf.get("spectrum_correlated"), enveloping=surf.get("enveloping", "tapered"),
            lead_in_m=float(surf.get("lead_in_m", 5.0)), tracks=surf.get("tracks", "independent"),
            profile_data=(profiles or {}).get(profile),
            file=crg_file, lateral_offset_m=float(surf.get("lateral_offset_m", 0.0)),
            start_m=float(surf.get("start_m", 0.0)), fill_missing=bool(surf.get("fill_missing", False)),
            crg_data=crg_data,
        ),
        exposure=ExposureSpec(tuple(float(v) for v in ex["speeds_km_h"]), float(ex.get("hours_per_day", 8.0)),
                              working_speed_km_h=(float(ex["working_speed_km_h"]) if "working_speed_km_h" in ex
                                                  else None)),
        simulation=SimulationSpec(sim.get("duration_s"), bool(sim.get("lift_off", True)), str(sim.get("method", "auto"))),
        sweep=SweepSpec(tuple(float(v) for v in sweep.get("front_pressures_bar", ())),
                        tuple(float(v) for v in sweep.get("rear_pressures_bar", ())),
                        {k: tuple(float(x) for x in v) for k, v in sweep.items() if "." in k}),
        path=path,
        doc=doc,
        base_dir=base_dir,
    )


def parse_scenario(text: str, base_dir: str | Path = ".", path: str | Path | None = None, *,
                   confine: bool = True, read_profile=None, read_crg=None) -> Scenario:
    """Parse and check scenario TOML text.

    Parameters
    ----------
    text : str
        TOML text.
    base_dir : path
        Folder that relative paths (``surface.profile``) are resolved against and
        must stay inside.
    path : path, optional
        File name used in messages.
    confine : bool, optional
        ``surface.profile`` must be a relative path inside ``base_dir`` (default: campaign
        scenarios the pipeline walks). False for a file the user names (``tyrelab ride FILE``):
        an absolute path, or one relative to ``base_dir`` anywhere.
    read_profile : callable, optional
        ``path -> (distance_m, left_m, right_m)`` for ``kind = "profile"`` (this module reads no
        file: :func:`tyrelab.scenario_io.parse_scenario` and ``load_scenario`` pass
        :func:`tyrelab.scenario_io.read_profile_csv`); the data are kept in
        ``surface.profile_data``.
    read_crg : callable, optional
        ``path -> CrgData`` for ``kind = "crg"`` (:func:`tyrelab.scenario_io.read_crg`); the road is
        kept in ``surface.crg_data``.

    Raises
    ------
    ScenarioError
        With every problem found.

    See Also
    --------
    key_table : the keys it accepts.
    scenario_from_dict : the same from a dict.

    Examples
    --------
    >>> s = parse_scenario('''
    ... name = "demo"
    ... [tractor]
    ... mass_kg = 4700
    ... pitch_inertia_kg_m2 = 5500
    ... front_distance_m = 1.56
    ... rear_distance_m = 0.95
    ... cg_height_m = 0.95
    ... [tyres.front]
    ... size = "14.9R28"
    ... pressure_bar = 1.6
    ... [tyres.rear]
    ... size = "18.4R38"
    ... pressure_bar = 1.2
    ... [surface]
    ... kind = "iso8608"
    ... class = "C"
    ... [exposure]
    ... speeds_km_h = [4, 8]
    ... ''')
    >>> s.tractor.wheelbase_m, s.exposure.speeds_km_h, s.front.traction
    (2.51, (4.0, 8.0), False)
    """
    _checks.instance("text", text, str)
    where = str(path) if path is not None else "<scenario>"
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(where, [f"not valid TOML: {exc}"]) from None
    except RecursionError:  # arrays nested thousands deep
        raise ScenarioError(where, ["not valid TOML: nested too deeply"]) from None
    except ValueError:  # an integer of more digits than Python converts (4300): tomllib's own ValueError
        raise ScenarioError(where, long_integer_problems(text) or ["not valid TOML: a number too long to read"]) from None
    return _from_document(doc, where, base_dir, path, confine, read_profile, read_crg)


def _plain(value, depth: int = 0):
    """A mapping or sequence as the types :mod:`tomllib` gives (dict, list, str, bool, int, float)."""
    if depth > 32:
        raise RecursionError
    if isinstance(value, Mapping):
        return {str(k): _plain(v, depth + 1) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v, depth + 1) for v in value]
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):  # a numpy scalar
        return value.item()
    return value


def scenario_from_dict(doc, base_dir: str | Path = ".", path: str | Path | None = None, *,
                       confine: bool = True, read_profile=None, read_crg=None) -> Scenario:
    """A scenario from its document as a dict: the tables of the TOML file as nested dicts.

    The same checks as :func:`parse_scenario` (every problem at once, each naming its key); tuples
    are taken as arrays and numpy scalars as numbers.

    Parameters
    ----------
    doc : mapping
        ``{"name": ..., "tractor": {...}, "tyres": {"front": {...}, "rear": {...}}, "surface":
        {...}, "exposure": {...}}`` (every key, unit, default and bound: ``schemas/scenario.json``).
    base_dir, path, confine, read_profile, read_crg
        As :func:`parse_scenario`.

    Raises
    ------
    ScenarioError
        With every problem found.

    See Also
    --------
    parse_scenario : the same from TOML text.

    Examples
    --------
    >>> s = scenario_from_dict({"name": "demo", "tractor": {"mass_kg": 4700, "pitch_inertia_kg_m2": 5500, "front_distance_m": 1.56,
    ...                                                     "rear_distance_m": 0.95, "cg_height_m": 0.95},
    ...                         "tyres": {"front": {"size": "14.9R28", "pressure_bar": 1.6},
    ...                                   "rear": {"size": "18.4R38", "pressure_bar": 1.2}},
    ...                         "surface": {"kind": "iso8608", "class": "C"}, "exposure": {"speeds_km_h": (4, 8)}})
    >>> s.exposure.speeds_km_h
    (4.0, 8.0)
    >>> try:
    ...     scenario_from_dict({"tractor": {"mass_kg": -1}})
    ... except ScenarioError as exc:
    ...     print(exc.problems[:3])
    ['missing name', 'tractor.mass_kg: -1 kg must be greater than 0', 'missing tractor.pitch_inertia_kg_m2 (kg m^2)']
    """
    where = str(path) if path is not None else "<scenario>"
    if not isinstance(doc, Mapping):
        raise ScenarioError(where, [f"doc must be a table of sections (a dict), got {type(doc).__name__}"])
    try:
        doc = _plain(doc)
    except RecursionError:
        raise ScenarioError(where, ["nested too deeply"]) from None
    return _from_document(doc, where, base_dir, path, confine, read_profile, read_crg)


def _from_document(doc: dict, where: str, base_dir, path, confine: bool, read_profile, read_crg=None) -> Scenario:
    base = Path(base_dir)
    profiles: dict = {}
    problems = _validate(doc, base, confine, read_profile, profiles, read_crg)
    if problems:
        raise ScenarioError(where, problems)
    scenario = _build(doc, Path(path) if path is not None else None, base, confine, profiles)
    problems = scenario_problems(scenario)  # what the model can represent (limits.LIMITS)
    if problems:
        raise ScenarioError(where, problems)
    return scenario


def numeric_key(key: str) -> dict | None:
    """The schema field of a numeric scenario key ``"section.key"`` (``"tyres.front.pressure_bar"``),
    or None when it is not one.

    See Also
    --------
    key_table : every key.

    Examples
    --------
    >>> numeric_key("tyres.front.pressure_bar")["unit"], numeric_key("seat.dampingratio") is None
    ('bar', True)
    """
    _checks.instance("key", key, str)
    section, _, name = key.rpartition(".")
    f = _sections().get(section, {}).get("fields", {}).get(name)
    return f if f is not None and f["type"] in ("number", "number_or_numbers") else None


def _sweep_key_problems(key: str, values) -> list[str]:
    """Problems of a ``[sweep]`` entry ``"section.key" = [values]``."""
    f = numeric_key(key)
    if f is None:
        return [f"sweep.{key!r}: not a numeric scenario key (a quoted \"section.key\", e.g. \"implement.mass_kg\")"]
    if not isinstance(values, list) or not values or not all(_is_number(v) for v in values):
        return [f"sweep.{key!r}: expected a list of numbers, got {values!r}"]
    return [p for v in values for p in _check_value(f"sweep.{key!r}", {**f, "type": "number"}, v, None)][:1]
