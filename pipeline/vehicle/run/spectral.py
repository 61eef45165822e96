"""The ride's frequency-domain core (issues 13, 36, 45): the expected seat response of a linear
model to the track's spectrum.

For the model ``(A, B, C, D)`` of an assembly (:meth:`tyrelab.vehicle.model.Assembly.linear`,
inputs ``u, u'`` per tyre) each output's response to a tyre's ground displacement, with the
enveloping filter's spatial transfer function and the wheelbase delay, gives its spectrum
``h S h^H`` over the tyres' input (cross-)spectrum ``S`` and the expected ISO 2631-1 weighted
r.m.s. ``sqrt(∫ S_y |W|² df)`` (:func:`expected_weighted_rms`, batched over variants); the expected
seat PSD and the transmissibility of the figures come from the same responses.

(The solvers' layer of issue 45 holds this module's kind; it lives here until ``vehicle/solvers/``
is on main.)
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ... import _validate
from ..._validate import positive
from .. import enveloping as ev
from .. import iso2631
from ..scenario import Scenario
from .records import AXIS_WORDS, SpeedRun, VariantPlan
from .track import FS_HZ, Track

__all__ = ["frequency_response", "enveloping_response", "input_cross_spectra", "expected_weighted_rms", "AXIS_WEIGHTING"]

#: The ISO 2631-1 frequency weighting of each seat axis (W_k vertical, W_d horizontal; any other
#: output, e.g. a tyre force, unweighted): :data:`tyrelab.vehicle.comfort.iso2631.AXIS_WEIGHTING`, the one table.
AXIS_WEIGHTING = iso2631.AXIS_WEIGHTING


def frequency_response(a, b, c, d, frequency_Hz) -> np.ndarray:
    """Complex response ``C (jω I - A)⁻¹ B + D`` of every output to every input.

    Computed modally (``A = V Λ V⁻¹``), vectorised over frequencies.

    Returns
    -------
    ndarray, shape (p, m, n_f)

    See Also
    --------
    expected_weighted_rms : the expected r.m.s. from these responses.

    Examples
    --------
    >>> m, k, c = 1000.0, 250e3, 3000.0                        # a mass on a spring and damper
    >>> a = np.array([[0.0, 1.0], [-k / m, -c / m]]); b = np.array([[0.0], [1.0 / m]])
    >>> h = frequency_response(a, b, np.array([[1.0, 0.0]]), np.zeros((1, 1)), [0.0, 10.0])   # 1/k; ≈ 1/(m ω²) above
    >>> h.shape, round(float(abs(h[0, 0, 0]) * k), 9), round(float(abs(h[0, 0, 1]) * m * (2 * np.pi * 10) ** 2), 3)
    ((1, 1, 2), 1.0, 1.066)
    """
    _validate.non_negative_array("frequency_Hz", frequency_Hz)
    a, b, c, d = (np.atleast_2d(np.asarray(v, float)) for v in (a, b, c, d))
    lam, vecs = np.linalg.eig(a)
    cv = c @ vecs
    vb = np.linalg.solve(vecs, b)
    jw = 2j * math.pi * np.asarray(frequency_Hz, float)
    inv = 1.0 / (jw[None, :] - lam[:, None])  # (n, nf)
    return np.einsum("pk,km,kf->pmf", cv, vb, inv) + d[:, :, None]


def enveloping_response(kind: str, footprint_m: float, dx_m: float, n_cycles_per_m) -> np.ndarray:
    """Spatial transfer function of the linear enveloping filters (real, symmetric windows).

    ``none`` and ``rigid_band`` (nonlinear; no transfer function) give 1.

    See Also
    --------
    frequency_response : the vehicle's response it multiplies.
    tyrelab.vehicle.enveloping.fixed_footprint : the filter in space.

    Examples
    --------
    >>> np.round(enveloping_response("fixed", 0.2, 0.01, [0.0, 2.5, 5.0]), 3).tolist()   # 21 samples: 0.21 m
    [1.0, 0.605, -0.048]
    """
    _validate.choice("kind", kind, ("none", "fixed", "tapered", "rigid_band"))
    _validate.non_negative("footprint_m", footprint_m)
    positive("dx_m", dx_m)
    if kind not in ("fixed", "tapered"):
        return np.ones_like(np.asarray(n_cycles_per_m, float))
    return _envelope_table(kind, [footprint_m], dx_m, n_cycles_per_m)[0]


def _envelope_table(kind: str, footprints_m, dx_m: float, n_cycles_per_m) -> np.ndarray:
    """:func:`enveloping_response` of each footprint (rows), the cosines of each window length computed
    once (a sweep's footprints differ in their last bits more often than in their windows)."""
    n = np.asarray(n_cycles_per_m, float)
    if kind not in ("fixed", "tapered"):
        return np.ones((len(footprints_m), n.size))
    cosines: dict = {}
    rows = []
    for fp in footprints_m:
        taps = ev.window(kind, fp, dx_m)  # the filter's own taps (terrain/enveloping.py: one home)
        if taps.size not in cosines:
            k = np.arange(taps.size) - taps.size // 2
            cosines[taps.size] = np.cos(2 * math.pi * np.outer(n, k * dx_m))
        rows.append(cosines[taps.size] @ taps)
    return np.array(rows).reshape(len(rows), n.size)


def input_cross_spectra(tyres: list[str], side_spectrum, f_Hz, v: float, wheelbase_m: float) -> np.ndarray:
    """The tyres' input cross-spectral matrix (tyres, tyres, f), m²/Hz: per pair the two tracks'
    spectrum or cross-spectrum (``G_LL``, ``G_RR``, ``G_LR`` at ``n = f/v``, per Hz ``/v``) times
    ``exp(-jω (τ_i - τ_j))``, ``τ`` = 0 front, ``wheelbase/v`` rear (the front/rear delay).

    See Also
    --------
    expected_weighted_rms : the expectation it feeds.

    Examples
    --------
    Class C tracks (``G(n) = 256·10⁻⁶ (n/0.1)⁻²`` m³), the two tracks half coherent, at 2 m/s and 1 Hz
    (``n`` = 0.5 cycles/m: ``G/v`` = 5.12·10⁻⁶ m²/Hz); the rear wheel 1.25 s behind the front, a
    quarter turn of phase at 1 Hz:

    >>> n = np.geomspace(0.01, 3, 200); g = 256e-6 * (n / 0.1) ** -2
    >>> s = input_cross_spectra(["front_left", "front_right", "rear_left"], (n, g, g, 0.5 * g), [1.0], v=2.0, wheelbase_m=2.5)
    >>> np.round(s[:, :, 0] * 1e6, 2).tolist()[0]
    [(5.12+0j), (2.56+0j), 5.12j]
    """
    positive("v", v)
    _validate.non_negative("wheelbase_m", wheelbase_m)
    n_s, g_ll, g_rr, g_lr = side_spectrum
    n = np.asarray(f_Hz, float) / v
    g = {("left", "left"): np.interp(n, n_s, g_ll), ("right", "right"): np.interp(n, n_s, g_rr),
         ("left", "right"): np.interp(n, n_s, g_lr.real) + 1j * np.interp(n, n_s, np.imag(g_lr))}
    g[("right", "left")] = np.conj(g[("left", "right")])
    jw = 2j * math.pi * np.asarray(f_Hz, float)
    tau = {t: (wheelbase_m / v if t.startswith("rear") else 0.0) for t in tyres}
    out = np.empty((len(tyres), len(tyres), n.size), dtype=complex)
    for i, a in enumerate(tyres):
        for j, b in enumerate(tyres):
            out[i, j] = g[(a.split("_")[1], b.split("_")[1])] / v * np.exp(-jw * (tau[a] - tau[b]))
    return out


def _expected_batch(members: list, v: float, forces: bool = False) -> None:
    """Expected weighted r.m.s. per seat axis (``run.expected``) of the runs ``members``
    (``(variant, speed index)`` pairs sharing a track and speed ``v``, m/s) from the
    frequency-domain path: one batched :func:`expected_weighted_rms` per model structure; with
    ``forces`` also the r.m.s. of every tyre element's dynamic force (``run.force_sd_N``, N)."""
    batches: dict = {}
    for p, i in members:
        r, sc = p.runs[i], p.scenario
        seat = sc.seat
        key = (r.lm.a.shape, r.asm.tyres, tuple(p.axes), sc.surface.enveloping,
               (seat.natural_frequency_Hz, seat.damping_ratio) if p.seat_abcd is not None else None)
        batches.setdefault(key, []).append((p, i))
    for batch in batches.values():
        p0, i0 = batch[0]
        sc, track, axes = p0.scenario, p0.track, list(p0.axes)
        grid = _fd_grid(sc, track, v)
        runs = [p.runs[i] for p, i in batch]
        env = {}
        for j, axle in enumerate(("front", "rear")):
            fps = sorted({r.footprints_m[j] for r in runs})
            table = _envelope_table(sc.surface.enveloping, fps, track.profile.dx_m, grid["n"])
            env[axle] = (table, np.array([fps.index(r.footprints_m[j]) for r in runs]))
        seat_tf = _seat_tf(p0.seat_abcd, grid["f"]) if p0.seat_abcd is not None else None
        tyres = runs[0].asm.tyres
        rows = axes + [f"force:{t}" for t in tyres] if forces else axes  # the rows of lm: seat axes, tyre forces
        na = len(rows)
        lms = [r.lm for r in runs]
        out = expected_weighted_rms(np.array([m.a for m in lms]), np.array([m.b for m in lms]),
                                    np.array([m.c[:na] for m in lms]), np.array([m.d[:na] for m in lms]),
                                    tyres, grid, env, seat_tf, rows, chunk=4 if forces else 8)
        for k, r in enumerate(runs):
            r.expected = {ax: float(out[ax][k]) for ax in axes}
            if forces:
                r.force_sd_N = {t: float(out[f"force:{t}"][k]) for t in tyres}


def _fd_grid(scenario: Scenario, track: Track, v: float) -> dict:
    """The frequency-domain path's grid at speed ``v`` (m/s): frequencies ``f`` (Hz, up to the
    Nyquist frequency of the time path), wavenumbers ``n`` (cycles/m) for the enveloping filters,
    and the ground input: the pitch plane's axle-mean spectrum ``s_u`` (m²/Hz, as the ch. 7 study),
    in 3-D the tyres' full cross-spectral matrix (:func:`input_cross_spectra`)."""
    wb = scenario.tractor.wheelbase_m
    if not scenario.tractor.three_d:
        n_s, g_s = track.spectrum
        f_s = n_s * v
        keep = f_s <= FS_HZ / 2
        return {"f": f_s[keep], "n": n_s[keep], "s_u": g_s[keep] / v, "wb": wb, "v": v}
    f_s = track.side_spectrum[0] * v
    f_s = f_s[f_s <= FS_HZ / 2]
    return {"f": f_s, "n": f_s / v, "side_spectrum": track.side_spectrum, "wb": wb, "v": v}


def expected_weighted_rms(a, b, c, d, tyres, grid: dict, env: dict, seat_tf, axes, chunk: int = 8) -> dict:
    """Expected ISO 2631-1 weighted r.m.s. of outputs of many linear models on one frequency grid.

    For each model ``(A, B, C, D)`` (stacked, leading axis: the variants) with inputs ``u, u'`` per
    tyre (:meth:`tyrelab.vehicle.model.Assembly.linear`), the response of output ``p`` to tyre
    ``t``'s ground displacement is, modally (``A = V Λ V⁻¹``, ``c = C V``, ``b = V⁻¹ B``),
    ``h_pt(jω) = env_t [ Σ_k c_pk b_k,u' + D_p,u + jω D_p,u' + Σ_k c_pk (b_k,u + λ_k b_k,u') / (jω - λ_k) ]``
    (``(b_u + jω b_u') / (jω - λ) = b_u' + (b_u + λ b_u') / (jω - λ)``): one small matrix product
    per variant over the frequencies. The output spectrum is ``h S h^H`` (``S`` the tyres' input
    cross-spectral matrix; the pitch plane: ``|Σ_t h_t e^{-jωτ_t}|² S_u``, the rear tyre a wheelbase
    later) and the expected value ``sqrt(∫ S_y |W|² df)`` (W_k on ``z``, W_d on ``x``, ``y``; the seat
    suspension's transmissibility ``seat_tf`` on ``z``).

    Parameters
    ----------
    a, b, c, d : ndarray, shape (V, n, n), (V, n, 2T), (V, p, n), (V, p, 2T)
        The variants' linear models, rows of ``c``/``d`` in the order of ``axes``.
    tyres : sequence of str
        The tyre elements (``front``/``rear`` or ``front_left``, ...), the inputs' order.
    grid : dict
        :func:`_fd_grid`.
    env : dict
        Axle (``front``/``rear``) -> enveloping transfer function on the grid: shape (F,) for
        all variants, (V, F), or ``(table, index)``: row ``index[v]`` of ``table`` for variant ``v``.
    seat_tf : ndarray or None
        Seat suspension transmissibility on the grid (applied to ``z``).
    axes : sequence of str
        Names of the output rows: seat axes (``z``, ``x``, ``y``: weighted) or any other name (an
        output taken unweighted, e.g. a tyre force: its r.m.s. in its own unit).
    chunk : int
        Variants per vectorised step (memory).

    Returns
    -------
    dict
        Axis -> ndarray (V,), m/s².

    See Also
    --------
    frequency_response : the responses it weights.
    input_cross_spectra : the tyres' input spectra.

    Examples
    --------
    Two outputs without dynamics (one decoupled state), on a flat input spectrum ``S_u`` = 1 m²/Hz
    from 0 to 1 Hz, in the pitch plane (inputs ``u, u'`` per tyre, the rear 1 s behind): the front
    tyre's ground rate, whose r.m.s. is ``sqrt(∫ ω² df)`` = ``2π/√3``, and the sum of the front and
    rear displacements, ``sqrt(∫ |1 + e^(-jω)|² df)`` = ``√2``; both unweighted (their names are not
    seat axes):

    >>> f = np.linspace(0.0, 1.0, 1001)
    >>> grid = {"f": f, "s_u": np.ones(f.size), "wb": 2.5, "v": 2.5}
    >>> a, b, c = np.array([[[-1.0]]]), np.zeros((1, 1, 4)), np.zeros((1, 2, 1))
    >>> d = np.array([[[0.0, 1.0, 0.0, 0.0], [1.0, 0.0, 1.0, 0.0]]])       # rows: outputs; columns: u, u' per tyre
    >>> env = {"front": np.ones(f.size), "rear": np.ones(f.size)}
    >>> r = expected_weighted_rms(a, b, c, d, ["front", "rear"], grid, env, None, ["rate", "sum"])
    >>> round(float(r["rate"][0]), 4), round(float(2 * np.pi / np.sqrt(3)), 4), round(float(r["sum"][0]), 6)
    (3.6276, 3.6276, 1.414214)
    """
    _validate.positive_int("chunk", chunk)
    a, b, c, d = (np.asarray(x, float) for x in (a, b, c, d))
    if not (a.ndim == 3 and a.shape[1] == a.shape[2] and b.shape[:2] == a.shape[:2] and c.shape[0] == a.shape[0]
            and c.shape[2] == a.shape[1] and d.shape == (c.shape[0], c.shape[1], b.shape[2])
            and b.shape[2] == 2 * len(tyres) and c.shape[1] >= len(axes)):
        raise ValueError(f"a, b, c, d: shapes {a.shape}, {b.shape}, {c.shape}, {d.shape} are not (V, n, n), "
                         f"(V, n, 2T), (V, p, n), (V, p, 2T) with T = {len(tyres)} tyres and p >= {len(axes)} axes")
    f = np.asarray(grid["f"], float)
    omega = 2 * math.pi * f
    n_t, n_f = len(tyres), f.size
    axle = [t.split("_")[0] for t in tyres]
    # the integral sqrt(∫ S_y |W|² df) by the trapezoidal rule as one weighted sum over the grid:
    # per axis the weights (trapezoid × |W|² × the seat's |T|² on z × S_u in the pitch plane)
    trap = np.zeros(n_f)
    if n_f > 1:
        df = np.diff(f)
        trap[:-1] += 0.5 * df
        trap[1:] += 0.5 * df
    seat2 = np.abs(seat_tf) ** 2 if seat_tf is not None else None
    quad = {}
    for ax in axes:
        weighting = AXIS_WEIGHTING.get(ax)  # any other output (a force): unweighted
        q = trap * np.abs(iso2631.weighting_response(f, weighting)) ** 2 if weighting else trap
        if seat2 is not None and ax == "z":
            q = q * seat2
        quad[ax] = q * grid["s_u"] if "s_u" in grid else q
    if "s_u" in grid:  # the pitch plane: rear a wheelbase later, one spectrum
        delay = np.array([np.exp(-1j * omega * grid["wb"] / grid["v"]) if t.startswith("rear") else np.ones(n_f)
                          for t in tyres])
        s_in = None
    else:
        s_in = input_cross_spectra(list(tyres), grid["side_spectrum"], f, grid["v"], grid["wb"])
    out = {ax: np.empty(a.shape[0]) for ax in axes}
    n_p, n_s = len(axes), a.shape[1]
    n_h = n_p * n_t
    for lo in range(0, a.shape[0], chunk):
        sl = slice(lo, lo + chunk)
        lam, vecs = np.linalg.eig(a[sl])
        cv = c[sl][:, :n_p] @ vecs  # (V, p, n)
        vb = np.linalg.solve(vecs, b[sl].astype(complex))  # (V, n, 2T)
        vb_u, vb_du = vb[:, :, 0::2], vb[:, :, 1::2]
        nv = lam.shape[0]
        # h_pt(jw) = sum_k beta_ptk / (jw - lam_k) + alpha0_pt + jw alpha1_pt as one real matrix
        # product per variant: rows [Re h; Im h], columns over the basis [br_k; x_k; 1; w] with
        # 1/(jw - lam) = br - j x, br = a / (a² + x²), x = (w - Im lam) / (a² + x²), a = -Re lam
        beta = (cv[:, :, :, None] * (vb_u + lam[:, :, None] * vb_du)[:, None, :, :]).transpose(0, 1, 3, 2)
        beta = beta.reshape(nv, n_h, n_s)
        alpha0 = (cv @ vb_du + d[sl][:, :n_p, 0::2]).reshape(nv, n_h)  # (V, p T)
        alpha1 = d[sl][:, :n_p, 1::2].reshape(nv, n_h)
        big = np.zeros((nv, 2 * n_h, 2 * n_s + 2))
        big[:, :n_h, :n_s], big[:, :n_h, n_s:2 * n_s] = beta.real, beta.imag
        big[:, n_h:, :n_s], big[:, n_h:, n_s:2 * n_s] = beta.imag, -beta.real
        big[:, :n_h, 2 * n_s], big[:, n_h:, 2 * n_s], big[:, n_h:, 2 * n_s + 1] = alpha0.real, alpha0.imag, alpha1
        basis = np.empty((nv, 2 * n_s + 2, n_f))
        x = np.subtract(omega[None, None, :], lam.imag[:, :, None], out=basis[:, n_s:2 * n_s])
        inv = x * x
        inv += (lam.real**2)[:, :, None]
        np.reciprocal(inv, out=inv)
        np.multiply(inv, -lam.real[:, :, None], out=basis[:, :n_s])
        x *= inv
        basis[:, 2 * n_s] = 1.0
        basis[:, 2 * n_s + 1] = omega
        h = np.matmul(big, basis).reshape(nv, 2, n_p, n_t, n_f)  # [Re h, Im h] (V, 2, p, T, F)
        env_t = np.stack([_rows(env[x_], sl, nv, n_f) for x_ in axle], axis=1)  # (V, T, F)
        # a variant's numbers do not depend on the others in its chunk (how a sweep is cut into
        # executor tasks): elementwise operations, and per variant one sum over the grid
        h_re, h_im = h[:, 0], h[:, 1]  # (V, p, T, F)
        if s_in is None:  # |sum_t h_t env_t e^{-jw tau_t}|² S_u
            e_re, e_im = env_t * delay.real, env_t * delay.imag  # (V, T, F)
            r_re = np.zeros((nv, n_p, n_f))
            r_im = np.zeros((nv, n_p, n_f))
            for t in range(n_t):
                r_re += h_re[:, :, t] * e_re[:, None, t] - h_im[:, :, t] * e_im[:, None, t]
                r_im += h_re[:, :, t] * e_im[:, None, t] + h_im[:, :, t] * e_re[:, None, t]
            power = r_re * r_re
            power += r_im * r_im
        else:  # h S h^H, S Hermitian: sum_i |h_i|² S_ii + 2 sum_{i<j} Re(h_i conj(h_j) S_ij)
            h_re = h_re * env_t[:, None]
            h_im = h_im * env_t[:, None]
            power = np.zeros((nv, n_p, n_f))
            for i in range(n_t):
                power += (h_re[:, :, i] ** 2 + h_im[:, :, i] ** 2) * s_in[i, i].real
                for j in range(i + 1, n_t):
                    # Re(h_i conj(h_j) S_ij) with h_i conj(h_j) = (a_i a_j + b_i b_j) + j (b_i a_j - a_i b_j)
                    x_re = h_re[:, :, i] * h_re[:, :, j] + h_im[:, :, i] * h_im[:, :, j]
                    x_im = h_im[:, :, i] * h_re[:, :, j] - h_re[:, :, i] * h_im[:, :, j]
                    power += 2.0 * (x_re * s_in[i, j].real - x_im * s_in[i, j].imag)
        for k, ax in enumerate(axes):  # numpy's sum per row (BLAS' dot rounds with the memory alignment)
            out[ax][sl] = np.sqrt(np.maximum(np.sum(power[:, k] * quad[ax], axis=-1), 0.0))
    return out


def _rows(env, sl: slice, nv: int, n_f: int) -> np.ndarray:
    """An axle's enveloping transfer function for the variants ``sl``: one row for all, a row per
    variant, or ``(table, index)`` (a row of ``table`` per variant)."""
    if isinstance(env, tuple):
        table, index = env
        return np.asarray(table, float)[np.asarray(index)[sl]]
    env = np.asarray(env, float)
    return np.broadcast_to(env, (nv, n_f)) if env.ndim < 2 else env[sl]


def _wheel_responses(r: SpeedRun, f_Hz, v: float, env) -> tuple[np.ndarray, list[str]]:
    """Response of every output to each tyre's ground displacement (p, tyres, f), with the
    enveloping filter of its axle (``env[axle]``), without the wheelbase delay; and the tyres."""
    h = frequency_response(*r.lm.abcd, f_Hz)
    jw = 2j * math.pi * np.asarray(f_Hz, float)
    tyres = list(r.asm.tyres)
    out = np.stack([(h[:, 2 * j] + jw * h[:, 2 * j + 1]) * env[t.split("_")[0]] for j, t in enumerate(tyres)], axis=1)
    return out, tyres


def _transmissibility(r: SpeedRun, axes: dict, seat_ss, f_grid, v: float, wb: float, speed: float) -> pd.DataFrame:
    """|seat acceleration / ground acceleration| per axis on the figure grid (all wheels in phase
    on both sides, the rear a wheelbase later): ``seat_vertical``, ``seat_longitudinal_per_m``
    (fore-aft per unit ground acceleration, as before) and in 3-D ``seat_lateral_roll``: lateral
    seat acceleration per unit left/right anti-phase ground acceleration."""
    w2 = (2 * math.pi * f_grid) ** 2
    ones = {"front": 1.0, "rear": 1.0}
    h, tyres = _wheel_responses(r, f_grid, v, ones)
    delay = np.array([np.exp(-2j * math.pi * f_grid * wb / v) if t.startswith("rear") else np.ones_like(f_grid)
                      for t in tyres])
    in_phase = np.einsum("ptf,tf->pf", h, delay)
    out = {"speed_km_h": speed, "frequency_Hz": f_grid}
    k = list(axes)
    tz = in_phase[k.index("z")] * (_seat_tf(seat_ss, f_grid) if seat_ss is not None else 1.0)
    out["seat_vertical"] = np.abs(tz) / w2
    out["seat_longitudinal_per_m"] = np.abs(in_phase[k.index("x")]) / w2
    if "y" in axes:
        sign = np.array([1.0 if t.endswith("left") else -1.0 for t in tyres])[:, None]
        anti = np.einsum("ptf,tf->pf", h, 0.5 * sign * delay)
        out["seat_lateral_roll"] = np.abs(anti[k.index("y")]) / w2
    return pd.DataFrame(out)


def _seat_tf(seat_ss, f_Hz) -> np.ndarray:
    return frequency_response(*seat_ss, f_Hz)[0, 0]


def _expected_psd(p: VariantPlan, i: int, f_Hz: np.ndarray, speed: float) -> pd.DataFrame:
    """The expected seat acceleration PSD per axis (m²/s⁴/Hz, unweighted; the seat suspension on z) of
    run ``i`` of ``p`` at ``f_Hz``: ``h S h^H`` with the enveloping filters and the wheelbase delay."""
    r, sc, track, axes = p.runs[i], p.scenario, p.track, p.axes
    v = r.v_m_s
    n = f_Hz / v
    env = {axle: enveloping_response(sc.surface.enveloping, r.footprints_m[j], track.profile.dx_m, n)
           for j, axle in enumerate(("front", "rear"))}
    h, tyres = _wheel_responses(r, f_Hz, v, env)
    h = h[:len(axes)]
    if not sc.tractor.three_d:
        n_s, g_s = track.spectrum
        s_u = np.interp(n, n_s, g_s, left=0.0, right=0.0) / v
        delay = np.array([np.exp(-2j * math.pi * f_Hz * p.wheelbase_m / v) if t.startswith("rear") else np.ones_like(f_Hz)
                          for t in tyres])
        power = np.abs(np.einsum("ptf,tf->pf", h, delay)) ** 2 * s_u
    else:
        n_s = track.side_spectrum[0]
        inside = (n >= n_s[0]) & (n <= n_s[-1])
        s_in = input_cross_spectra(list(tyres), track.side_spectrum, f_Hz, v, p.wheelbase_m) * inside
        power = np.einsum("pif,ijf,pjf->pf", h, s_in, np.conj(h)).real
    out = {"speed_km_h": speed, "frequency_Hz": f_Hz}
    for k, ax in enumerate(axes):
        s = power[k]
        if ax == "z" and p.seat_abcd is not None:
            s = s * np.abs(_seat_tf(p.seat_abcd, f_Hz)) ** 2
        out[f"seat_{AXIS_WORDS[ax]}_psd_m2_s4_per_Hz"] = np.maximum(s, 0.0)
    return pd.DataFrame(out)
