"""Ride prediction speed (issue 13): one scenario, a 5 x 5 pressure sweep, and the RK4 baseline.

The shipped ``modern_tractor.toml`` (4 speeds 4-16 km/h x 400 m of an ISO 8608
class C track, 750 s of simulated driving at 1 ms) is run with
:func:`tyrelab.vehicle.ride.ride` in this process on one core (BLAS threads
pinned to 1), then a 5 front x 5 rear pressure sweep of it (100 runs). The
baseline, in the same process, is the nonlinear RK4 tractor of the ch. 7 study
(:func:`tyrelab.vehicle.tractor.simulate_tractor`) on the scenario's 16 km/h run,
the shortest one, against the linear path of ``ride`` on the same run (inputs
built once for both). Prints wall times, ratios and the largest relative
difference of the seat vertical acceleration between the two paths.

    .venv/bin/python bench/bench_ride.py [--skip-sweep] [--targets] [--lateral] [--rolling] [--methods]
                                         [--rolling-grid] [--sensitivities]

``--targets`` also measures issue 23's sweep targets as ratios to u = one 4-speed scenario
(``one_scenario_cpu_s``) in this process, all in CPU seconds: the whole 10 x 10 pressure grid x 8
speeds (4-18 km/h) in the time domain (``ride_sweep``, ``grid_800_over_u``, target <= 25) and the
frequency-domain expectation alone for 50 x 50 pressure pairs x 4 speeds = 10,000 variant-speeds
(``expected_sweep``, ``fd_10000_over_u``, target <= 5); and the 3-D model's cost
(``three_d_over_u``: the same scenario with roll, isotropic tracks and a pivoting front axle); and
the floor of the grid's exact computation, the ISO 2631-1 weighting alone of its 1,600 seat records
(``grid_weighting_alone_over_u``: one variant's records at the grid's lengths, x 100). u is the
median of three runs.

``--lateral`` (issue 33): a 3-D scenario with the tyres' lateral elements (the 3-D default: since
issue 42 the rolling element) against the same with ``lateral_model = "none"`` in this process
(``lateral_over_none``, target <= 1.5).

``--rolling`` (issue 42): the same 3-D scenario with the rolling tyre (``lateral_model = "rolling"``,
the default: each speed its own series damper c2 = a / v, the contact points' states, the damped modes
per speed and their intervals across the stand-ins) against ``lateral_model = "kelvin_voigt"`` in this
process (``rolling_over_kelvin_voigt``, target <= 1.5).

``--rolling-grid`` (issue 42, Deliver 7): the 10 x 10 pressure grid x 8 speeds (4-18 km/h) of the same
3-D scenario with the rolling tyre, whose every variant has damped modes per speed (the complex roots of
each speed's assembly, its own series dampers) and their intervals (the modes of the tyre-stiffness
and stand-in perturbations), under ``--method auto`` against ``--method time`` (``rolling_grid_time_over_auto``,
target >= 30), in CPU seconds of this process; and what the damped modes cost a variant
(``damped_modes_cpu_ms_per_variant``: the per-speed roots and their intervals, timed inside the grid's
auto run, and their share of it). Both methods compute the same damped modes for every variant (the
mode table and ``ride.json`` report them per variant and speed): ``rolling_grid_ratio_without_modes`` is
the ratio of the two grids less that common work, what the rows alone would give. The A(8) interval
across the stand-in lateral stiffness is the first variant's alone in a sweep (the one ``ride.json``
reports).

``--sensitivities`` (issue 42, third session): how far the damped modes' ±1 % tyre-stiffness derivatives by
first-order root perturbation (``modes.root_sensitivities``) lie from the ±1 % models' modes solved in full
(central differences), over the 3-D bench tractor and ``modern_3d_tractor.toml`` at 4 pressure pairs x 3
speeds each, every oscillating mode (the ride solves an axle in full where any mode is overdamped; here its
oscillating modes are compared as well): the relative differences of df/dk and dζ/dk (median, 95th
percentile, largest), the axles the perturbation refuses, and the overdamped modes the full solve cannot
follow through ±1 % (an interval the ride then leaves out, with a note).

``--methods`` measures issue 36 in this process, in CPU seconds: the 10 x 10 pressure grid x 8
speeds (4-18 km/h) of ``ride_sweep`` under ``--method auto`` (spectral rows for every variant, the
first variant simulated beside them: the scenario's own pressures are not on the grid) against
``--method time`` (``grid_time_over_auto``, target >= 30); the whole command a user runs,
``tyrelab ride modern_tractor.toml --front-pressure x10 --rear-pressure x10 --speeds x8 --out DIR``
(page and JSON; ``tyrelab.cli.main`` in this process, auto first so that it pays the imports)
against the same with ``--method time`` (``command_time_over_auto``, target >= 10); and how far
each time-domain a_w of the grid lies from its spectral row (one realisation's sampling scatter:
median, 95th percentile and largest relative difference per axis, and the largest difference
between a spectral a_w and the time row's own expectation, which should be rounding).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from tyrelab.resources import scenarios_dir  # noqa: E402
from tyrelab.vehicle import iso2631, ride  # noqa: E402
from tyrelab.scenario_io import load_scenario, parse_scenario  # noqa: E402
from tyrelab.vehicle.scenario import with_overrides  # noqa: E402
from tyrelab.vehicle.solvers import lti  # noqa: E402
from tyrelab.vehicle.tractor import Tractor, simulate_tractor  # noqa: E402


CPU: dict[str, float] = {}


def simulate_state_space(a, b, c, d, w, outputs=(0,)):
    """The linear path's run of the outputs ``outputs`` from rest (the library's until issue 45 took it out)."""
    return lti.discretise(a, b, c[list(outputs)], d[list(outputs)], ride.DT_S).run(w)


def _timed(fn, *args, **kw):
    """(result, wall seconds); the process CPU seconds go to ``CPU[fn name]`` (less load-sensitive)."""
    c0, t0 = time.process_time(), time.perf_counter()
    out = fn(*args, **kw)
    CPU[fn.__name__] = CPU.get(fn.__name__, 0.0) + time.process_time() - c0
    return out, time.perf_counter() - t0


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--skip-sweep", action="store_true", help="only the single scenario and the baseline")
    p.add_argument("--targets", action="store_true", help="also the issue-23 sweep targets (minutes of CPU)")
    p.add_argument("--lateral", action="store_true",
                   help="also issue 33's cost: a 3-D scenario with lateral tyre elements against lateral_model = none")
    p.add_argument("--rolling", action="store_true",
                   help="also issue 42's cost: the 3-D scenario with the rolling tyre against kelvin_voigt")
    p.add_argument("--methods", action="store_true", help="only issue 36: the grid and the command, auto against time")
    p.add_argument("--sensitivities", action="store_true",
                   help="only issue 42: first-order root sensitivities against the full solves")
    p.add_argument("--rolling-grid", action="store_true",
                   help="only issue 42: the 3-D rolling-tyre grid, auto against time, and the damped modes' cost")
    args = p.parse_args(argv)
    if args.methods:
        print(json.dumps(_methods(), indent=2))
        return 0
    if args.rolling_grid:
        print(json.dumps(_rolling_grid(), indent=2))
        return 0
    if args.sensitivities:
        print(json.dumps(_sensitivities(), indent=2))
        return 0
    sc = load_scenario(scenarios_dir() / "modern_tractor.toml")
    ride.ride(with_overrides(sc, [16.0]), with_spectra=False)  # warm-up: imports, caches
    # u: the median of three runs (one run alone varied by +-25 % on the shared machine)
    ones = []
    for _ in range(3):
        res, t_one = _timed(ride.ride, sc, with_spectra=False)
        ones.append((CPU.pop("ride"), t_one))
    cpu_one, t_one = sorted(ones)[1]
    _, t_one_fig = _timed(ride.ride, sc, with_spectra=True)
    cpu_one_fig = CPU.pop("ride")
    out = {"scenario": sc.name, "speeds_km_h": list(sc.exposure.speeds_km_h),
           "simulated_s": float(res.speeds["duration_s"].sum()),
           "load_average_1min": round(os.getloadavg()[0], 1),
           "one_scenario_s": round(t_one, 3), "one_scenario_cpu_s": round(cpu_one, 3),
           "one_scenario_cpu_s_runs": [round(c, 3) for c, _ in ones],
           "one_scenario_with_figure_data_s": round(t_one_fig, 3), "with_figure_data_cpu_s": round(cpu_one_fig, 3),
           "methods": sorted(set(res.speeds["simulation"]))}

    # baseline: RK4 nonlinear model vs the linear path on the 16 km/h run
    tyres = ride.resolve_tyres(sc)
    track = ride.build_profile(sc)
    i = list(sc.exposure.speeds_km_h).index(16.0)
    tr = Tractor.of_parts(ride.build_parts(sc, tyres, i))
    v = 16.0 / 3.6
    wb = sc.tractor.wheelbase_m
    start, stop = ride._record_window(track, wb, v, None)
    fp = (float(tyres["front"].footprint_m[i]), float(tyres["rear"].footprint_m[i]))
    inputs = ride.axle_inputs(track.profile, sc.surface.enveloping, fp, (tyres["front"].radius_m, tyres["rear"].radius_m),
                              v, wb, stop)
    ss = ride.state_space(tr, sc.seat.ahead_of_cg_m, sc.seat.height_above_cg_m)
    lin, t_lin = _timed(simulate_state_space, *ss, np.vstack([u[::2] for u in inputs]), outputs=(0,))
    rk4, t_rk4 = _timed(simulate_tractor, tr, *inputs, lift_off=True, method="rk4")
    seat = rk4["vertical_m_s2"] + sc.seat.ahead_of_cg_m * rk4["pitch_rad_s2"]
    diff = float(np.max(np.abs(lin[0] - seat)) / np.sqrt(np.mean(seat**2)))
    out.update(baseline_run_s=round(stop / 1000, 1), linear_path_s=round(t_lin, 3), rk4_s=round(t_rk4, 3),
               linear_path_cpu_s=round(CPU["simulate_state_space"], 3), rk4_cpu_s=round(CPU["simulate_tractor"], 3),
               rk4_over_linear=round(t_rk4 / t_lin, 1), max_relative_difference=float(f"{diff:.2e}"))

    if not args.skip_sweep:
        pressures_f = [1.0, 1.3, 1.6, 1.9, 2.2]
        pressures_r = [0.8, 1.0, 1.2, 1.4, 1.6]
        sweep, t_sweep = _timed(ride.ride_sweep, sc, pressures_f, pressures_r, with_spectra=False)
        table = ride.results_table(sweep)
        out.update(sweep_runs=len(table), sweep_s=round(t_sweep, 2), sweep_cpu_s=round(CPU["ride_sweep"], 2),
                   sweep_nonlinear_runs=int((table["simulation"] != "linear").sum()))
    if args.targets:
        out.update(_targets(sc, cpu_one))
    if args.lateral:
        out.update(_lateral())
    if args.rolling:
        out.update(_rolling())
    print(json.dumps(out, indent=2))
    return 0


def _three_d_text() -> str:
    """The shipped modern tractor made 3-D: roll, isotropic tracks, a pivoting front axle."""
    text = (scenarios_dir() / "modern_tractor.toml").read_text()
    text = text.replace("[tractor]\n", "[tractor]\nroll_inertia_kg_m2 = 2400\nfront_track_m = 1.9\nrear_track_m = 1.8\n")
    text = text.replace("[surface]\n", "[surface]\ntracks = \"isotropic\"\n")
    return text + "\n[front_axle]\nmount = \"pivot\"\nroll_inertia_kg_m2 = 160\n"


def _against(first: tuple, second: tuple) -> tuple[float, float]:
    """Median CPU seconds of three ``ride`` runs of each ``(name, scenario)``, interleaved, after a warm-up."""
    ride.ride(with_overrides(first[1], [16.0]), with_spectra=False)  # warm-up
    cpu: dict = {}
    for name, s in (first, second) * 3:
        CPU.pop("ride", None)
        _timed(ride.ride, s, with_spectra=False)
        cpu.setdefault(name, []).append(CPU.pop("ride"))
    return sorted(cpu[first[0]])[1], sorted(cpu[second[0]])[1]


def _lateral() -> dict:
    """Issue 33: the shipped modern tractor made 3-D with the tyres' lateral elements (the default: the
    rolling element since issue 42; lateral and yaw freedoms, the static loads' moment) against the same
    scenario with ``lateral_model = "none"``, in this process, CPU seconds, the median of three runs each
    (target <= 1.5x)."""
    text = _three_d_text()
    lateral = parse_scenario(text, scenarios_dir())
    none = parse_scenario(text.replace("[tractor]\n", "[tractor]\nlateral_model = \"none\"\n"), scenarios_dir())
    lat, non = _against(("lateral", lateral), ("none", none))
    return {"lateral_cpu_s": round(lat, 3), "lateral_none_cpu_s": round(non, 3),
            "lateral_over_none": round(lat / non, 2)}


def _rolling() -> dict:
    """Issue 42: the 3-D modern tractor with the rolling tyre (the default) against ``kelvin_voigt``, in this
    process, CPU seconds, the median of three runs each (target <= 1.5x)."""
    text = _three_d_text()
    rolling = parse_scenario(text, scenarios_dir())
    kv = parse_scenario(text.replace("[tractor]\n", "[tractor]\nlateral_model = \"kelvin_voigt\"\n"), scenarios_dir())
    assert rolling.tractor.lateral_model == "rolling"
    rol, kel = _against(("rolling", rolling), ("kelvin_voigt", kv))
    return {"rolling_cpu_s": round(rol, 3), "kelvin_voigt_cpu_s": round(kel, 3),
            "rolling_over_kelvin_voigt": round(rol / kel, 2)}


def _rolling_grid() -> dict:
    """Issue 42: the 10 x 10 x 8 grid of the 3-D rolling-tyre scenario under auto and time, and the damped
    modes' CPU per variant inside the auto run (module docstring)."""
    from tyrelab.vehicle.run import plan

    sc = parse_scenario(_three_d_text(), scenarios_dir())
    assert sc.tractor.lateral_model == "rolling"
    speeds8 = [2.0 * k for k in range(2, 10)]
    fronts = [round(0.8 + 0.15 * i, 4) for i in range(10)]
    rears = [round(0.6 + 0.12 * i, 4) for i in range(10)]
    _warm_up(sc, fronts, rears, speeds8)
    spent = {"by_speed": 0.0, "intervals": 0.0, "variants": 0}
    originals = {"by_speed": plan._damped_by_speed, "intervals": plan._damped_intervals}

    def timed(key):
        def run(*a, **kw):
            c0 = time.process_time()
            try:
                return originals[key](*a, **kw)
            finally:
                spent[key] += time.process_time() - c0
                spent["variants"] += key == "by_speed"
        return run

    out: dict = {"scenario": sc.name, "load_average_1min_start": round(os.getloadavg()[0], 1)}
    tables = {}
    for method in ("auto", "time"):
        plan._damped_by_speed, plan._damped_intervals = timed("by_speed"), timed("intervals")
        try:
            spent.update(by_speed=0.0, intervals=0.0, variants=0)
            c0 = _cpu()
            res = ride.ride_sweep(sc, fronts, rears, speeds8, with_spectra=False, method=method, max_samples=10**9)
            out[f"rolling_grid_{method}_cpu_s"] = round(_cpu() - c0, 2)
        finally:
            plan._damped_by_speed, plan._damped_intervals = originals["by_speed"], originals["intervals"]
        tables[method] = ride.results_table(res)
        n = max(spent["variants"], 1)
        out[f"damped_modes_{method}"] = {
            "variants": spent["variants"], "per_speed_roots_cpu_ms_per_variant": round(1e3 * spent["by_speed"] / n, 1),
            "intervals_cpu_ms_per_variant": round(1e3 * spent["intervals"] / n, 1),
            "share_of_grid": round((spent["by_speed"] + spent["intervals"]) / out[f"rolling_grid_{method}_cpu_s"], 3)}
    out["rolling_grid_time_over_auto"] = round(out["rolling_grid_time_cpu_s"] / out["rolling_grid_auto_cpu_s"], 1)
    common = {m: out[f"rolling_grid_{m}_cpu_s"] * out[f"damped_modes_{m}"]["share_of_grid"] for m in ("auto", "time")}
    out["rolling_grid_ratio_without_modes"] = round(
        (out["rolling_grid_time_cpu_s"] - common["time"]) / (out["rolling_grid_auto_cpu_s"] - common["auto"]), 1)
    out["damped_modes_cpu_ms_per_variant"] = round(
        out["damped_modes_auto"]["per_speed_roots_cpu_ms_per_variant"] + out["damped_modes_auto"]["intervals_cpu_ms_per_variant"], 1)
    out["rolling_grid_rows"] = {m: t["method"].value_counts().to_dict() for m, t in tables.items()}
    out["load_average_1min_end"] = round(os.getloadavg()[0], 1)
    return out


def _sensitivities() -> dict:
    """Issue 42: first-order root sensitivities against central differences of full solves (module docstring)."""
    import dataclasses

    from tyrelab.vehicle.model import assemble
    from tyrelab.vehicle.solvers import modes

    def scaled(parts, axle, f):
        part = getattr(parts, axle)
        return dataclasses.replace(parts, **{axle: dataclasses.replace(part, tyre_stiffness_N_per_m=f * part.tyre_stiffness_N_per_m)})

    err_f, err_z, lost, refused = [], [], 0, 0
    for sc0 in (parse_scenario(_three_d_text(), scenarios_dir()), load_scenario(scenarios_dir() / "modern_3d_tractor.toml")):
        for pf, pr in ((0.8, 0.6), (1.2, 1.0), (1.6, 1.4), (2.15, 1.68)):
            for speed in (4.0, 10.0, 18.0):
                sc = with_overrides(sc0, [speed], pf, pr)
                base = ride.build_parts(sc, ride.resolve_tyres(sc), 0)
                asm = assemble(base)
                shapes = modes.mode_set(modes._released(asm, 0.0))
                nominal = {n: d for n, d in modes.damped_modes(asm, reference=shapes).items() if d is not None}
                oscillating = {n: d for n, d in nominal.items() if not d.overdamped}
                a = asm.linear(list(asm.kinematic_outputs)[:1]).a
                for axle in ("front", "rear"):
                    k = getattr(base, axle).tyre_stiffness_N_per_m
                    models = {f: assemble(scaled(base, axle, f)) for f in (1.01, 0.99)}
                    da = (models[1.01].linear(list(asm.kinematic_outputs)[:1]).a
                          - models[0.99].linear(list(asm.kinematic_outputs)[:1]).a) / (0.02 * k)
                    slopes = modes.root_sensitivities(a, oscillating, da, 0.01 * k)
                    if slopes is None:
                        refused += 1
                        continue
                    full = {f: modes.follow_damped(nominal, modes.damped_modes(m, reference=shapes)) for f, m in models.items()}
                    for n, (df, dz) in slopes.items():
                        up, down = full[1.01][n], full[0.99][n]
                        if up is None or down is None:
                            lost += 1
                            continue
                        df_full = (up.undamped_Hz - down.undamped_Hz) / (0.02 * k)
                        dz_full = (up.damping_ratio - down.damping_ratio) / (0.02 * k)
                        err_f.append(abs(df / df_full - 1) if df_full else 0.0)
                        err_z.append(abs(dz / dz_full - 1) if dz_full else 0.0)
                    lost += sum(1 for n in nominal if n not in oscillating and (full[1.01][n] is None or full[0.99][n] is None))

    def stats(x):
        return {"median": float(f"{np.median(x):.2e}"), "p95": float(f"{np.quantile(x, 0.95):.2e}"),
                "max": float(f"{max(x):.2e}"), "modes": len(x)}

    return {"df_dk_relative_difference": stats(err_f), "dzeta_dk_relative_difference": stats(err_z),
            "axles_refused": refused, "overdamped_modes_the_full_solve_cannot_follow": lost,
            "shape_share_limit": modes.SENSITIVITY_SHAPE_SHARE}


def _targets(sc, u_s: float) -> dict:
    """Issue 23's targets as ratios to ``u_s`` (one 4-speed scenario), all in CPU seconds of this process."""
    text = (scenarios_dir() / "modern_tractor.toml").read_text()
    text = text.replace("[tractor]\n", "[tractor]\nroll_inertia_kg_m2 = 2400\nfront_track_m = 1.9\nrear_track_m = 1.8\n")
    text = text.replace("[surface]\n", "[surface]\ntracks = \"isotropic\"\n")
    text += "\n[front_axle]\nmount = \"pivot\"\nroll_inertia_kg_m2 = 160\n"
    three = parse_scenario(text, scenarios_dir())
    CPU.pop("ride", None)
    _timed(ride.ride, three, with_spectra=False)
    t_3d = CPU.pop("ride")
    speeds8 = [2.0 * k for k in range(2, 10)]
    grid = ([0.8 + 0.15 * i for i in range(10)], [0.6 + 0.12 * i for i in range(10)])
    # the whole 10 x 10 x 8 grid in the time domain (ride_sweep in this process, batched)
    CPU.pop("ride_sweep", None)
    sweep, _ = _timed(ride.ride_sweep, sc, grid[0], grid[1], speeds8, with_spectra=False, max_samples=10**9)
    t_grid = CPU.pop("ride_sweep")
    runs = sum(len(r.speeds) for r in sweep)
    # frequency domain alone: 50 x 50 pressure pairs x the scenario's 4 speeds = 10,000 variant-speeds
    fronts = [round(0.8 + 1.6 * i / 49, 4) for i in range(50)]
    rears = [round(0.6 + 1.4 * i / 49, 4) for i in range(50)]
    table, _ = _timed(ride.expected_sweep, sc, fronts, rears)
    t_fd = CPU.pop("expected_sweep")
    # the floor of the grid's exact computation: the ISO 2631-1 weighting alone (iso2631.weighted_signal,
    # W_k on z and W_d on x) of one variant's seat records at the grid's record lengths, x 100 variants
    # (the records of the grid are these lengths; the weighting does not depend on their values)
    rng = np.random.default_rng(0)
    track = ride.build_profile(sc)
    lengths = [stop - start for start, stop in
               (ride._record_window(track, sc.tractor.wheelbase_m, s / 3.6, sc.simulation.duration_s) for s in speeds8)]
    records = [rng.standard_normal(n) for n in lengths]
    floor = []
    for _ in range(3):
        c0 = time.process_time()
        for x in records:
            iso2631.weighted_signal(x, ride.FS_HZ, "Wk")
            iso2631.weighted_signal(x, ride.FS_HZ, "Wd")
        floor.append(100 * (time.process_time() - c0))
    t_floor = sorted(floor)[1]
    return {"three_d_cpu_s": round(t_3d, 3), "three_d_over_u": round(t_3d / u_s, 2),
            "grid_weighting_alone_cpu_s": round(t_floor, 1), "grid_weighting_alone_over_u": round(t_floor / u_s, 1),
            "grid_runs": runs, "grid_cpu_s": round(t_grid, 1), "grid_800_over_u": round(t_grid / u_s, 1),
            "fd_variant_speeds": len(table), "fd_cpu_s": round(t_fd, 2), "fd_10000_over_u": round(t_fd / u_s, 1)}


def _warm_up(sc, fronts, rears, speeds) -> None:
    """Imports and the process' caches that the first run of either method fills and the other then
    finds (the ISO 2631-1 weightings on each record length's FFT grid, the tyre models): one variant
    simulated and four spectral at the grid's speeds, at pressures off the grid (nothing of the grid's
    own variants is kept). Both methods are then timed warm (until issue 42's third session the warm-up
    ran one speed, so the first method timed, auto, paid the caches the time grid then found)."""
    off_f, off_r = [f + 0.05 for f in fronts[:2]], [r + 0.05 for r in rears[:2]]
    ride.ride_sweep(sc, off_f[:1], off_r[:1], speeds, with_spectra=False, method="time", max_samples=10**9)
    ride.ride_sweep(sc, off_f, off_r, speeds, with_spectra=False, method="spectral")


def _cpu() -> float:
    """CPU seconds of this process and its finished children."""
    import resource

    return time.process_time() + resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime + \
        resource.getrusage(resource.RUSAGE_CHILDREN).ru_stime


def _methods() -> dict:
    """Issue 36: the 10 x 10 x 8 grid and the user's command under auto and time (module docstring)."""
    import contextlib
    import io
    import tempfile

    from tyrelab.cli import main as cli_main
    from tyrelab.vehicle import scenario_limits as limits

    path = scenarios_dir() / "modern_tractor.toml"
    sc = load_scenario(path)
    speeds8 = [2.0 * k for k in range(2, 10)]
    fronts = [round(0.8 + 0.15 * i, 4) for i in range(10)]
    rears = [round(0.6 + 0.12 * i, 4) for i in range(10)]
    _warm_up(sc, fronts, rears, speeds8)
    out: dict = {"load_average_1min_start": round(os.getloadavg()[0], 1)}
    tables = {}
    for method in ("auto", "time"):
        c0 = _cpu()
        res = ride.ride_sweep(sc, fronts, rears, speeds8, with_spectra=False, method=method, max_samples=10**9)
        out[f"grid_{method}_cpu_s"] = round(_cpu() - c0, 2)
        tables[method] = ride.results_table(res)
    out["grid_time_over_auto"] = round(out["grid_time_cpu_s"] / out["grid_auto_cpu_s"], 1)
    auto, timed = tables["auto"], tables["time"]
    spectral = auto[auto["method"] == "spectral"]
    out["grid_rows"] = {"auto": auto["method"].value_counts().to_dict(), "time": len(timed)}
    keys = ["front_pressure_bar", "rear_pressure_bar", "speed_km_h"]
    both = spectral.merge(timed, on=keys, suffixes=("_spectral", "_time"))
    for ax in ("z", "x"):
        rel = (both[f"a_w{ax}_m_s2_time"] / both[f"a_w{ax}_m_s2_spectral"] - 1).abs()
        out[f"a_w{ax}_time_vs_spectral_percent"] = {
            "median": round(100 * float(rel.median()), 2), "p95": round(100 * float(rel.quantile(0.95)), 2),
            "max": round(100 * float(rel.max()), 2), "rows": len(rel)}
        own = (both[f"a_w{ax}_m_s2_spectral"] / both[f"expected_a_w{ax}_m_s2_time"] - 1).abs()
        out[f"a_w{ax}_spectral_vs_time_rows_expectation_max"] = float(f"{float(own.max()):.1e}")
    # the bounds: 100 x 100 x 8 spectral is allowed, the same in the time domain refused before it starts
    out["bounds_100x100x8"] = {m: limits.work_problems(sc, 100 * 100, speeds8, method=m) == []
                               for m in ("spectral", "auto", "time")}
    # the whole command, page and JSON included
    args = ["ride", str(path), "--front-pressure", *map(str, fronts), "--rear-pressure", *map(str, rears),
            "--speeds", *(f"{v:g}" for v in speeds8), "--max-samples", str(10**9)]
    for method in ("auto", "time"):
        with tempfile.TemporaryDirectory() as tmp:
            sink = io.StringIO()
            c0 = _cpu()
            with contextlib.redirect_stdout(sink):
                code = cli_main([*args, "--method", method, "--out", tmp])
            out[f"command_{method}_cpu_s"] = round(_cpu() - c0, 2)
            out[f"command_{method}_exit"] = code
            out[f"command_{method}_json_MB"] = round(len(sink.getvalue()) / 1e6, 2)
    out["command_time_over_auto"] = round(out["command_time_cpu_s"] / out["command_auto_cpu_s"], 1)
    out["load_average_1min_end"] = round(os.getloadavg()[0], 1)
    return out


if __name__ == "__main__":
    raise SystemExit(main())
