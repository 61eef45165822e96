"""Simulate stage speed (issue 15): the ch. 7 tractor batch by three paths, the studies, the stage.

In one process, BLAS threads pinned to 1, CPU seconds (``time.process_time``; the machine is
shared, wall times are not comparable between runs):

* the ch. 7 study's batch of tractor runs (95 runs + the Table XVIII sweep, 31.8 s each at
  1 ms), captured from :func:`tyrelab.vehicle.studies.tractor_study`, solved by
  - ``switched``: :func:`~tyrelab.vehicle.tractor.simulate_tractor` (``method="auto"``): exact
    while both axles are in contact, RK4 across the lift-off intervals, one batch;
  - ``old``: the path before issue 15's switching, one batch per longitudinal model, each run
    solved exactly first (:func:`linear_response`, the library's until issue 45) and the runs that
    lift a tyre off integrated again with RK4 over the whole record;
  - ``rk4``: RK4 over every run, one batch (the accuracy reference: largest difference of the
    switched runs' accelerations, relative to each run's r.m.s.);
* the two studies themselves (:func:`~tyrelab.vehicle.studies.tractor_study`,
  :func:`~tyrelab.vehicle.studies.carriage_study`);
* the ch. 6 reference batch (the virtual carriage's nonlinear runs, which make the demo's
  recordings: :func:`tyrelab.vehicle.study_recordings.carriage_recordings`) by
  :func:`~tyrelab.vehicle.carriage.simulate_nonlinear` (state as one array, buffers, about half
  the numpy calls a step) and by the plain RK4 loop it replaced (``textbook_carriage``, the
  baseline): CPU of each, ratio, and whether the outputs are bit-identical;
* with ``--stage``: the simulate stage on an empty build (shipped tables and scenarios),
  ``--jobs 1`` and ``--jobs 2``, CPU of this process and of its worker processes.

Prints one JSON object.

    .venv/bin/python bench/bench_simulate.py [--stage]
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import resource  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from tyrelab import published  # noqa: E402
from tyrelab.vehicle import carriage, studies, tractor  # noqa: E402
from tyrelab.vehicle import published_layouts as layouts  # noqa: E402
from tyrelab.vehicle.model import assemble  # noqa: E402
from tyrelab.vehicle.solvers import lti  # noqa: E402

_TRACTOR_ARRAYS = tractor.PARAMETERS


def _cpu(fn, *args, **kw):
    """(result, CPU seconds of this process)."""
    c0 = time.process_time()
    out = fn(*args, **kw)
    return out, time.process_time() - c0


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def _capture_batch(mass, tyres) -> tuple:
    """The (tractor, inputs) the ch. 7 study hands :func:`simulate_tractor` (and the study's CPU s)."""
    seen = []
    study = studies.chapter7  # the module of tractor_study (issue 45: the studies' package)
    real = study.simulate_tractor

    def recorder(tr, *args, **kw):
        seen.append((tr, args))
        return real(tr, *args, **kw)

    study.simulate_tractor = recorder
    try:
        _, cpu = _cpu(studies.tractor_study, mass, tyres, seed=5007)
    finally:
        study.simulate_tractor = real
    (tr, args), = seen
    return tr, args[:4], cpu


def _subset(tr: tractor.Tractor, idx) -> tractor.Tractor:
    models = np.broadcast_to(np.asarray(tr.longitudinal_model, dtype=object), (np.size(tr.mass_kg),))
    return tractor.Tractor(**{k: np.asarray(getattr(tr, k))[idx] for k in _TRACTOR_ARRAYS},
                           longitudinal_model=str(models[idx][0]))


def _capture_carriage(xii, stationary) -> tuple:
    """The (carriage, inputs, kwargs) the ch. 6 study hands :func:`carriage.simulate_nonlinear`."""
    seen = []
    real = carriage.simulate_nonlinear

    def recorder(*args, **kw):
        seen.append((args, kw))
        return real(*args, **kw)

    carriage.simulate_nonlinear = recorder
    try:  # the virtual carriage's runs (issue 24: they make the recordings, not the study)
        from tyrelab.vehicle.study_recordings import carriage_recordings

        carriage_recordings(xii, stationary, seed=5007)
    finally:
        carriage.simulate_nonlinear = real
    (args, kw), = seen
    return args, kw


def textbook_carriage(car: carriage.Carriage, u, ud, dt_s: float = 1e-3, lift_off: bool = True, vs: float = 0.005) -> dict:
    """The RK4 loop of :func:`carriage.simulate_nonlinear` before issue 15 (whole-array steps, one
    numpy call per operation): the baseline of its ratio."""
    runs = u.shape[0]
    m, k, c, cp, fc = (np.broadcast_to(np.asarray(getattr(car, f), float), (runs,)) for f in
                       ("mass_kg", "stiffness_N_per_m", "damping_N_s_per_m", "parasitic_damping_N_s_per_m",
                        "coulomb_friction_N"))
    floor = -m * carriage.GRAVITY_M_S2 if lift_off else np.full(runs, -np.inf)
    inv_m = 1.0 / m

    def accel(z, v, uu, uud):
        ft = np.maximum(k * (uu - z) + c * (uud - v), floor)
        return (ft - cp * v - fc * np.tanh(v / vs)) * inv_m, ft

    n = (u.shape[1] + 1) // 2
    z_out, v_out, a_out = np.empty((runs, n)), np.empty((runs, n)), np.empty((runs, n))
    off, z, v, h = np.zeros(runs), np.zeros(runs), np.zeros(runs), dt_s
    for i in range(n):
        j = 2 * i
        a1, ft = accel(z, v, u[:, j], ud[:, j])
        z_out[:, i], v_out[:, i], a_out[:, i] = z, v, a1
        off += ft <= floor
        if i == n - 1:
            break
        zb, vb = z + 0.5 * h * v, v + 0.5 * h * a1
        a2, _ = accel(zb, vb, u[:, j + 1], ud[:, j + 1])
        zc, vc = z + 0.5 * h * vb, v + 0.5 * h * a2
        a3, _ = accel(zc, vc, u[:, j + 1], ud[:, j + 1])
        zd, vd = z + h * vc, v + h * a3
        a4, _ = accel(zd, vd, u[:, j + 2], ud[:, j + 2])
        z = z + h / 6.0 * (v + 2 * vb + 2 * vc + vd)
        v = v + h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4)
    return {"z_m": z_out, "v_m_s": v_out, "a_m_s2": a_out, "lift_off_fraction": off / n}


def linear_response(tr: tractor.Tractor, inputs: np.ndarray, dt_s: float) -> dict[str, np.ndarray]:
    """Exact response of one run (scalar ``tr``) in permanent contact, from rest: the outputs of
    :data:`~tyrelab.vehicle.tractor.TRACTOR_OUTPUTS` and the dynamic axle forces per sample, for
    ``inputs`` ``u_f, u_f', u_r, u_r'`` (shape (4, n), step ``dt_s``, linear in between). The old
    path's exact solution (``tyrelab.vehicle.tractor.linear_response`` until issue 45 took it out
    of the library: only this baseline used it)."""
    names = tractor.TRACTOR_OUTPUTS + ("front_force_N", "rear_force_N")
    lm = assemble(tractor.tractor_parts(tr)).linear(names)
    y = lti.discretise(*lm.abcd, dt_s).run(inputs)
    y[3:5, 0] = 0.0  # at rest at the first sample exactly (the modal transform leaves ~1e-22)
    return dict(zip(names, y))


def old_path(tr: tractor.Tractor, inputs, dt_s: float) -> dict:
    """Before the switching: per longitudinal model, exact for every run, RK4 again for the lifting ones."""
    uf, udf, ur, udr = inputs
    runs, n = uf.shape[0], (uf.shape[1] + 1) // 2
    models = np.broadcast_to(np.asarray(tr.longitudinal_model, dtype=object), (runs,))
    out = {k: np.empty((runs, n)) for k in ("vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2")}
    for model in ("none", "kelvin_voigt", "maxwell"):
        group = np.flatnonzero(models == model)
        lifting = []
        for i in group:
            one = _subset(tr, [i])
            one = tractor.Tractor(**{k: float(np.asarray(getattr(one, k))[0]) for k in _TRACTOR_ARRAYS},
                                  longitudinal_model=model)
            lin = linear_response(one, np.stack([uf[i], udf[i], ur[i], udr[i]]), dt_s / 2)
            w, wb = tractor.GRAVITY_M_S2 * one.mass_kg, float(one.wheelbase_m)
            if lin["front_force_N"].min() <= -w * one.rear_distance_m / wb or \
                    lin["rear_force_N"].min() <= -w * one.front_distance_m / wb:
                lifting.append(i)
            else:
                for k in out:
                    out[k][i] = lin[k][::2]
        if lifting:
            sim = tractor.simulate_tractor(_subset(tr, lifting), *(x[lifting] for x in inputs), dt_s, method="rk4")
            for k in out:
                out[k][lifting] = sim[k]
    return out


def _differences(a: dict, b: dict, rows) -> dict:
    res = {}
    for k in ("vertical_m_s2", "pitch_rad_s2", "longitudinal_m_s2"):
        rms = np.sqrt(np.mean(b[k][rows] ** 2, axis=1))
        keep = rms > 0
        peak = np.abs(a[k][rows] - b[k][rows]).max(axis=1)[keep] / rms[keep]
        rms_rel = np.abs(np.sqrt(np.mean(a[k][rows] ** 2, axis=1))[keep] / rms[keep] - 1)
        res[k] = {"max_abs_diff_over_rms_max": float(f"{peak.max():.3g}"),
                  "max_abs_diff_over_rms_median": float(f"{np.median(peak):.3g}"),
                  "rms_relative_diff_max": float(f"{rms_rel.max():.3g}")}
    return res


def _stage(jobs: int) -> dict:
    from tyrelab.stages import simulate
    from tyrelab.stages.base import Context

    with tempfile.TemporaryDirectory() as tmp:
        ctx = Context(raw=Path(tmp) / "raw", build=Path(tmp) / "build", jobs=jobs)
        ctx.raw.mkdir()
        c0, k0, t0 = time.process_time(), _children_cpu(), time.perf_counter()
        simulate.run(ctx)
        return {"jobs": jobs, "wall_s": round(time.perf_counter() - t0, 2),
                "cpu_s": round(time.process_time() - c0, 2), "worker_cpu_s": round(_children_cpu() - k0, 2)}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--stage", action="store_true", help="also time the simulate stage (--jobs 1 and 2)")
    args = p.parse_args(argv)
    pub = {s: published.read_published(s, None) for s in ("table_xii", "table_xv", "table_xvi")}
    mass, tyres = layouts.tractor_mass(pub["table_xv"]), layouts.tractor_tyres(pub["table_xvi"])
    tr, inputs, cpu_study = _capture_batch(mass, tyres)
    dt = studies.DT_S
    switched, cpu_sw = _cpu(tractor.simulate_tractor, tr, *inputs, dt)
    old, cpu_old = _cpu(old_path, tr, inputs, dt)
    rk4, cpu_rk4 = _cpu(tractor.simulate_tractor, tr, *inputs, dt, method="rk4")
    sw_rows = np.flatnonzero(switched["method_used"] == "exact+rk4")
    _, cpu_car = _cpu(studies.carriage_study, layouts.carriage_rolling(pub["table_xii"]),
                      layouts.carriage_stationary(pub["table_xii"]), seed=5007)
    (car, u, ud, *rest), car_kw = _capture_carriage(layouts.carriage_rolling(pub["table_xii"]),
                                                    layouts.carriage_stationary(pub["table_xii"]))
    buffered, cpu_buffered = _cpu(carriage.simulate_nonlinear, car, u, ud, *rest, **car_kw)
    plain, cpu_plain = _cpu(textbook_carriage, car, u, ud, *rest, **car_kw)
    out = {
        "load_average_1min": round(os.getloadavg()[0], 1),
        "carriage_batch": {"runs": int(u.shape[0]), "steps": int((u.shape[1] + 1) // 2),
                           "cpu_s": {"buffered": round(cpu_buffered, 2), "textbook": round(cpu_plain, 2)},
                           "ratio_textbook_over_buffered": round(cpu_plain / cpu_buffered, 2),
                           "bit_identical": all(np.array_equal(buffered[k], plain[k]) for k in plain)},
        "tractor_batch": {"runs": int(inputs[0].shape[0]), "samples_per_run": int((inputs[0].shape[1] + 1) // 2),
                          "switched_runs": int(sw_rows.size),
                          "exact_runs": int(np.sum(switched["method_used"] == "exact"))},
        "tractor_batch_cpu_s": {"switched": round(cpu_sw, 2), "old": round(cpu_old, 2), "rk4_one_batch": round(cpu_rk4, 2)},
        "ratio_old_over_switched": round(cpu_old / cpu_sw, 2),
        "ratio_rk4_over_switched": round(cpu_rk4 / cpu_sw, 2),
        "switched_vs_rk4_on_switched_runs": _differences(switched, rk4, sw_rows),
        "old_vs_rk4_on_switched_runs": _differences(old, rk4, sw_rows),
        "tractor_study_cpu_s": round(cpu_study, 2),
        "carriage_study_cpu_s": round(cpu_car, 2),
    }
    if args.stage:
        out["stage"] = [_stage(1), _stage(2)]
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
