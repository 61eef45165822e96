"""Numbers of the vehicle model stored before the parts refactor (issue 35, Deliver 7).

``compute(full)`` runs the thesis studies' tractor tables (XVII, XVIII, XX), both shipped
scenarios, the 3-D part kinds (pivot/suspended axles, suspended cab, hitch-spring implement,
ballast, Maxwell/Kelvin-Voigt longitudinal elements, lift-off across RK4), a seat suspension,
a sweep and the frequency-domain expectation, and returns ``{name: float array}``. Run as a
script on the code before a change to store them::

    .venv/bin/python tests/vehicle/golden_vehicle.py          # quick set (the default test)
    .venv/bin/python tests/vehicle/golden_vehicle.py --full   # everything (the slow test)
    .venv/bin/python -m tests.vehicle.golden_vehicle --bits   # which quantities today's code gives to the bit

``--bits`` stores nothing but ``golden_vehicle_quick_bits.json``: the quantities today's code gives
bit for bit on this platform (:func:`platform`: the locked numpy/scipy and the CPU kernels they
dispatch to), which the test then requires bit for bit wherever the platform is the same.

``tests/vehicle/test_parts_unchanged.py`` compares today's numbers to the stored ones.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).parent / "data"


def _frame(prefix: str, df: pd.DataFrame, out: dict) -> None:
    for c in df.columns:
        col = df[c]
        if pd.api.types.is_numeric_dtype(col) and not pd.api.types.is_bool_dtype(col):
            out[f"{prefix}/{c}"] = col.to_numpy(float)


def _ride(prefix: str, res, out: dict) -> None:
    _frame(f"{prefix}/speeds", res.speeds, out)
    for k, v in sorted(res.natural_frequencies_Hz.items()):
        out[f"{prefix}/f/{k}"] = np.array([v], float)
    for name in ("spectra", "transmissibility"):
        df = getattr(res, name, None)
        if isinstance(df, pd.DataFrame):
            _frame(f"{prefix}/{name}", df, out)


def _text_3d(extra: str, speeds: str = "[10]", surface: str | None = None, longitudinal: str = "") -> str:
    surface = surface or 'kind = "iso8608"\nclass = "D"\nlength_m = 60\ntracks = "isotropic"'
    return f"""
name = "golden 3-D"
[tractor]
mass_kg = 4700.0
pitch_inertia_kg_m2 = 5500.0
front_distance_m = 1.56
rear_distance_m = 0.95
cg_height_m = 0.95
roll_inertia_kg_m2 = 2400.0
front_track_m = 1.9
rear_track_m = 1.8
{longitudinal}
[seat]
ahead_of_cg_m = -0.4
left_of_cg_m = 0.35
height_above_cg_m = 1.0
gravity_tilt = true
suspension = "linear"
natural_frequency_Hz = 1.8
damping_ratio = 0.3
[tyres.front]
size = "380/85R28"
pressure_bar = 1.6
stiffness_kN_per_m = 500
damping_kN_s_per_m = 1.5
[tyres.rear]
size = "480/70R38"
pressure_bar = 1.2
stiffness_kN_per_m = 600
damping_kN_s_per_m = 2.0
[surface]
{surface}
[exposure]
speeds_km_h = {speeds}
hours_per_day = 8
{extra}
"""


PARTS = ('[front_axle]\nmount = "suspended"\nroll_inertia_kg_m2 = 160\nmass_kg = 400\nheight_m = 0.6\n'
         'suspension_stiffness_kN_per_m = 150\nsuspension_damping_kN_s_per_m = 8\n'
         '[cab]\nmount = "suspended"\nmass_kg = 800\npitch_inertia_kg_m2 = 600\nroll_inertia_kg_m2 = 500\n'
         'ahead_of_cg_m = -0.3\nheight_above_cg_m = 0.9\nfront_mount_ahead_of_cg_m = 0.5\n'
         'rear_mount_ahead_of_cg_m = -0.9\nmount_track_m = 1.2\nmount_stiffness_kN_per_m = 30\n'
         'mount_damping_kN_s_per_m = 2\n'
         '[implement]\nmass_kg = 800\npitch_inertia_kg_m2 = 300\nroll_inertia_kg_m2 = 300\n'
         'behind_rear_axle_m = 1.2\nheight_m = 0.8\nmount = "hitch_spring"\nhitch_behind_rear_axle_m = 0.5\n'
         'hitch_height_m = 0.6\nhitch_stiffness_kN_m_per_rad = 150\nhitch_damping_kN_m_s_per_rad = 15\n'
         '[ballast]\nmass_kg = 600\nahead_of_front_axle_m = 0.8\nheight_m = 0.7\n')
PIVOT = '[front_axle]\nmount = "pivot"\nroll_inertia_kg_m2 = 160\n'


def compute(full: bool = False) -> dict[str, np.ndarray]:
    from tyrelab.published import read_published
    from tyrelab.resources import scenarios_dir
    from tyrelab.scenario_io import load_scenario, parse_scenario
    from tyrelab.vehicle import bounce_pitch as bp
    from tyrelab.vehicle import published_layouts as layouts
    from tyrelab.vehicle import ride, studies
    from tyrelab.vehicle.scenario import with_overrides
    from tyrelab.vehicle.tractor import Tractor, simulate_tractor

    out: dict[str, np.ndarray] = {}
    # the pitch-plane tractor across lift-off, every longitudinal model, both methods
    t = Tractor(5120.0, 6210.0, 1.54, 0.896, 0.838, 8.5e5, 6.6e5, 3e3, 2e3, 9.1e5, 6e3,
                np.array(["none", "kelvin_voigt", "maxwell"], dtype=object))
    rng = np.random.default_rng(35)
    u = np.cumsum(rng.normal(0, 2e-3, (3, 4001)), axis=1) + np.r_[np.zeros(1001), np.full(3000, -0.06)]
    du = np.gradient(u, 5e-4, axis=1)
    for method in ("auto", "rk4"):
        sim = simulate_tractor(t, u, du, u, du, method=method)
        for k, v in sim.items():
            if k != "method_used":
                out[f"tractor/{method}/{k}"] = np.asarray(v, float)
    # Table XX
    xx = bp.table_xx(layouts.tractors(read_published("table_xix")), read_published("table_xx"))
    _frame("table_xx", xx, out)
    # Tables XVII and XVIII (quick: the three cases of tests/vehicle/test_studies_by_case.py)
    mass = layouts.tractor_mass(read_published("table_xv"))
    tyres = layouts.tractor_tyres(read_published("table_xvi"))
    if not full:
        rolling = tyres[tyres["characteristics"] == "rolling"]
        keep = rolling.index[[0, 5]].union(tyres.index[tyres["characteristics"] == "stationary"])
        tyres = tyres.loc[keep].reset_index(drop=True)
    st = studies.tractor_study(mass, tyres)
    for name in ("runs", "table_xvii", "table_xviii", "spectra"):
        if isinstance(st.get(name), pd.DataFrame):
            _frame(f"study/{name}", st[name], out)
    # shipped scenarios
    for name in ("modern_tractor", "mf698t"):
        sc = load_scenario(scenarios_dir() / f"{name}.toml")
        if not full:
            sc = with_overrides(sc, [16.0])
        _ride(f"shipped/{name}", ride.ride(sc, with_spectra=True), out)
    # 3-D: every part kind, seat suspension, lift-off on a rough track, Maxwell longitudinal
    lon = ('longitudinal_model = "maxwell"\nlongitudinal_stiffness_kN_per_m = 455\n'
           'longitudinal_damping_kN_s_per_m = 3\n')
    _ride("3d/parts", ride.ride(parse_scenario(_text_3d(PARTS, longitudinal=lon)), with_spectra=True), out)
    _ride("3d/pivot_kv", ride.ride(parse_scenario(_text_3d(PIVOT, longitudinal=lon.replace("maxwell", "kelvin_voigt"))),
                                   with_spectra=True), out)
    rough = 'kind = "iso8608"\nclass = "F"\nlength_m = 40\ntracks = "isotropic"'
    _ride("3d/lift_off", ride.ride(parse_scenario(_text_3d(PARTS, "[12]", rough, lon)), with_spectra=False), out)
    # sweeps: time domain and the frequency-domain expectation
    sc = parse_scenario(_text_3d(PIVOT, "[8, 12]"))
    # the variants ride_sweep ran (it refuses this sweep since issue 37: the tyres' K and C are given, so
    # the pressures change nothing; the batched run of four variants is what is recorded)
    variants = [ride.with_overrides(sc, None, f, r) for f in (1.2, 1.6) for r in (1.0, 1.4)]
    for i, r in enumerate(ride.ride_variants(variants, with_spectra=False)):
        _ride(f"sweep/{i}", r, out)
    ex = ride.expected_sweep(sc, [1.0, 1.3, 1.6], [0.9, 1.2, 1.5])
    if isinstance(ex, pd.DataFrame):
        _frame("expected_sweep", ex, out)
    else:
        for k, v in (ex.items() if isinstance(ex, dict) else []):
            if isinstance(v, pd.DataFrame):
                _frame(f"expected_sweep/{k}", v, out)
            else:
                out[f"expected_sweep/{k}"] = np.asarray(v, float)
    return out


def use_thesis_gravity(monkeypatch) -> None:
    """The vehicle model's default gravity set back to the thesis' 9.81 m/s², as before issue 45 made
    it the standard 9.80665: the numbers stored before then are compared under it."""
    from tyrelab.vehicle import ride
    from tyrelab.vehicle.carriage import THESIS_GRAVITY_M_S2
    from tyrelab.vehicle.model import assemble

    monkeypatch.setattr(sys.modules[assemble.__module__], "STANDARD_GRAVITY_M_S2", THESIS_GRAVITY_M_S2)
    monkeypatch.setattr(ride, "GRAVITY_M_S2", THESIS_GRAVITY_M_S2, raising=False)  # the footprints' loads


def path(full: bool) -> Path:
    return HERE / f"golden_vehicle_{'full' if full else 'quick'}.npz"


def bits_path(full: bool) -> Path:
    return HERE / f"golden_vehicle_{'full' if full else 'quick'}_bits.json"


def platform() -> dict:
    """What decides the last bits of these numbers besides the code: numpy's and scipy's versions,
    the CPU kernels numpy dispatches to (its SIMD targets found on this CPU, after any
    ``NPY_DISABLE_CPU_FEATURES``) and OpenBLAS's choice (``OPENBLAS_CORETYPE``, else from the
    same CPU flags)."""
    import os
    import platform as _platform

    import scipy

    try:
        from numpy._core import _multiarray_umath as um
    except ImportError:  # numpy 1.x
        from numpy.core import _multiarray_umath as um
    return {"numpy": np.__version__, "scipy": scipy.__version__, "machine": _platform.machine(),
            "simd": [f for f in um.__cpu_dispatch__ if um.__cpu_features__.get(f)],
            "openblas_coretype": os.environ.get("OPENBLAS_CORETYPE")}


def same_bits(full: bool, values: dict) -> list[str]:
    """The stored quantities ``values`` reproduce bit for bit."""
    stored = np.load(path(full))
    return [k for k in stored.files if k in values and np.array_equal(stored[k], values[k], equal_nan=True)]


if __name__ == "__main__":
    import json

    full = "--full" in sys.argv
    if "--bits" in sys.argv:
        from tests.vehicle.test_parts_unchanged import before_issue_33_parts

        with before_issue_33_parts():
            values = compute(full)
        bits = {"platform": platform(), "bit_identical": same_bits(full, values)}
        bits_path(full).write_text(json.dumps(bits, indent=1) + "\n")
        print(len(bits["bit_identical"]), "of", len(values), "bit for bit ->", bits_path(full))
        sys.exit(0)
    values = compute(full)
    HERE.mkdir(exist_ok=True)
    np.savez_compressed(path(full), **values)
    print(len(values), "arrays ->", path(full))
