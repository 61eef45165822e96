"""Ride scenario files for tests: one template (the ride tests' tractor), each part a keyword.

``tests.vehicle.test_ride`` and ``tests.hostile.test_hostile_scenarios`` write their scenarios
from it; :func:`write` puts one in a folder.
"""

from __future__ import annotations

from pathlib import Path

#: The tractor of the template (a ~4.7 t two-axle tractor; keys of ``[tractor]``).
TRACTOR = dict(mass_kg=4700.0, pitch_inertia_kg_m2=5500.0, front_distance_m=1.56, rear_distance_m=0.95, cg_height_m=0.95)
#: The default surface: a 60 m generated ISO 8608 class C track.
ISO_C = 'kind = "iso8608"\nclass = "C"\nlength_m = 60'


def scenario_text(surface: str = ISO_C, speeds: str = "[8]", tractor_extra: str = "", seat: str = "", front: str = "",
                  extra: str = "", *, tractor: dict | None = None, name: str = "test tractor",
                  hours_per_day: float | None = 6, rear: str = "", rear_size: str = "18.4R38") -> str:
    """TOML of a scenario: ``[tractor]`` (:data:`TRACTOR` updated by ``tractor``, then the lines
    ``tractor_extra`` and ``seat``), ``[tyres.front]`` 14.9R28 at 1.6 bar (plus ``front``),
    ``[tyres.rear]`` ``rear_size`` (18.4R38) at 1.2 bar (plus ``rear``), ``[surface]`` and ``[exposure]`` (``speeds``, ``hours_per_day``
    unless None), then ``extra``."""
    body = "\n".join(f"{k} = {v}" for k, v in {**TRACTOR, **(tractor or {})}.items())
    hours = "" if hours_per_day is None else f"hours_per_day = {hours_per_day:g}"
    return f"""
name = "{name}"
[tractor]
{body}
{tractor_extra}
{seat}
[tyres.front]
size = "14.9R28"
pressure_bar = 1.6
{front}
[tyres.rear]
size = "{rear_size}"
pressure_bar = 1.2
{rear}
[surface]
{surface}
[exposure]
speeds_km_h = {speeds}
{hours}
{extra}
"""


def write(folder: Path, text: str, name: str = "s.toml") -> Path:
    """Write ``text`` to ``folder/name``; return the path."""
    p = folder / name
    p.write_text(text)
    return p
