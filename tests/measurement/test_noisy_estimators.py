"""Issue 44: rig numbers a lab can trust — the broadband and transient estimators under real noise.

The runs come from tests/measurement/noisy_rig.py, a time-domain generator independent of
tyrelab's (the rig's 1866 kg suspended mass on a Kelvin–Voigt or rolling tyre, the linkage in
parallel, noise on the accelerometers or the load beams at a fraction of the signal in band). The
default run checks a few seeds each; the Monte Carlo of docs/rig_methods.md ("Estimators under
noise") is ``test_monte_carlo_bias_and_coverage`` (marked slow), and its table is printed by

    python -m tests.measurement.test_noisy_estimators 200

(200 seeded runs per case: method × direction × tyre model × noise; coverage with its binomial
standard error); the ground check's (lateral rolling runs over ISO 8608 roads) by

    python -m tests.measurement.test_noisy_estimators 20 --ground
"""

import math

import numpy as np
import pytest

from tests.measurement.noisy_rig import dwell_decay, rig_run

from tyrelab.measurement import broadband as bb
from tyrelab.measurement import rig_methods as rm
from tyrelab.measurement.recording import recording_arrays
from tyrelab.rawformat import MIN_DURATION_s, RunFileError, check_run

AXLE_KG = 600.0
#: The tyres of the Monte Carlo per direction: (K N/m, C N s/m); a rolling tyre adds the series damper
#: :data:`SERIES_C` at 5 km/h (the virtual rig's lateral T1 at 1.38 bar; the vertical one's K and C).
TYRES = {"vertical": (530e3, 3.0e3), "lateral": (261.5e3, 1.5e3)}
SERIES_C = 20e3
NOISES = {"accelerometer noise 0.3": {"accel_noise": 0.3}, "load-beam noise 0.3": {"beam_noise": 0.3},
          "no noise": {}}
#: The cases of the Monte Carlo, method × direction × tyre model × noise: name → (K N/m, C N s/m,
#: series c₂ N s/m or None, method, generator options, direction).
CASES = {
    f"{direction} {'rolling' if rolling else 'KV'}, {method.replace('_sine', '')}, {noise}": (
        *TYRES[direction], SERIES_C if rolling else None, method,
        {**options, **({"speed_km_h": 5.0} if rolling else {})}, direction)
    for method in ("random", "swept_sine") for direction in TYRES for rolling in (False, True)
    for noise, options in NOISES.items()
}


def _analyse(frame, method="random", *, rolling=False, band=(1.0, 8.0), direction="vertical"):
    accel, beams = recording_arrays(frame)
    row, _ = rm.analyse_method_run(method, direction, frame["time_s"].to_numpy(), accel, beams, AXLE_KG,
                                   band_Hz=band, rolling=rolling)
    return row


def _broadband(frame, pair=True, band=(1.0, 8.0), rolling=False):
    from tyrelab.measurement.apparent_mass import tyre_force

    accel, beams = recording_arrays(frame)
    force = tyre_force(accel[0], accel[1], beams, AXLE_KG)
    fs = 1 / float(np.median(np.diff(frame["time_s"].to_numpy())))
    return bb.analyse_broadband(force, accel.mean(axis=0), fs, band, rolling=rolling,
                                accel_pair_m_s2=accel if pair else None, axle_mass_kg=AXLE_KG if pair else None)


def test_the_segments_spectra_are_the_whole_records_welch_estimate():
    rng = np.random.default_rng(0)
    a = rng.standard_normal(256 * 30)
    f = 600 * a + rng.standard_normal(a.size)
    pair = (a + 0.1 * rng.standard_normal(a.size), a + 0.1 * rng.standard_normal(a.size), AXLE_KG)
    f_ref, x_ref, pair_ref = bb._references(f, a, 256.0, 0.5, pair)
    welch = bb._block_spectra(f_ref, x_ref, 256.0, 1, bb.RESOLUTION_Hz, True, pair_ref)
    seg = bb._segment_spectra(f_ref, x_ref, 256.0, bb.RESOLUTION_Hz, pair_ref)
    assert seg.segments == welch.segments == seg.s_aa.shape[0]
    for name in ("s_aa", "s_ff", "s_af", "s_12"):
        assert np.allclose(seg.mean(name), welch.mean(name), rtol=0, atol=1e-12 * np.abs(welch.mean(name)).max()), name


def test_without_noise_c_carries_no_window_bias():
    """The Hann window moves a bin's effective frequency where the reference's spectrum slopes (the
    rig's resonance): C was 0.33 % low on every noise-free run, against a scatter of 0.04 %, and its
    type A interval never covered it. The shift is measured and taken off (``broadband._window_shift``)."""
    K, C = 530e3, 3.0e3
    for seed in (1, 2):
        frame = rig_run(K, C, seed=seed)
        r = _broadband(frame)
        assert abs(r.fit.damping_N_s_per_m / C - 1) < 0.0005, r.fit.damping_N_s_per_m
        lo, hi = r.interval(r.fit.damping_N_s_per_m, r.damping_u_a_N_s_per_m)
        assert lo <= C <= hi
        f_ref, x_ref, _ = bb._references(*_force_accel(frame), 256.0, 0.5)
        shift = bb._window_shift(bb._segment_spectra(f_ref, x_ref, 256.0, bb.RESOLUTION_Hz))[r.in_fit]
        assert np.max(np.abs(shift.imag) / (2 * np.pi * r.frequency_Hz[r.in_fit])) > 0.005  # it is there to take off


def test_the_jackknife_replicates_are_not_bounded():
    """A replicate's C below zero stays below zero: bounding it at C = 0 truncated the scatter of a C
    that is barely in the data (a rolling tyre under load-beam noise: coverage 0.76)."""
    w = 2 * np.pi * np.linspace(1.5, 7.5, 20)
    z = np.stack([bb.maxwell_impedance(w, 2.6e5, c, 2e4) for c in (-400.0, 1500.0)])
    k, c, _ = bb._kv_given_series_blocks(w, z, np.ones(w.size), np.array([2e4, 2e4]))
    assert c == pytest.approx([-400.0, 1500.0], rel=1e-6) and k == pytest.approx([2.6e5, 2.6e5], rel=1e-9)


def test_the_overlap_factor_follows_its_derivation():
    """Segments whose neighbours correlate by ρ (a moving average of white noise), 20 000 records of 8
    groups of 3: the true variance of the record's mean over the groups' jackknife (its mean) is the
    factor squared."""
    rng = np.random.default_rng(5)
    m, g, rho = 3, 8, bb.HANN_SEGMENT_CORRELATION
    e = rng.standard_normal((20000, m * g + 1))
    # neighbours correlated by rho: x_i = (a e_i + b e_{i+1}), a² + b² = 1, a b = rho
    a = math.sqrt((1 + math.sqrt(1 - 4 * rho**2)) / 2)
    b = rho / a
    x = a * e[:, :-1] + b * e[:, 1:]
    groups = x.reshape(-1, g, m).mean(axis=2)
    jack = groups.var(axis=1, ddof=1) / g
    true = x.mean(axis=1).var()
    assert math.sqrt(true / jack.mean()) == pytest.approx(bb._overlap_factor(m, g), rel=0.02)


def _force_accel(frame):
    from tyrelab.measurement.apparent_mass import tyre_force

    accel, beams = recording_arrays(frame)
    return tyre_force(accel[0], accel[1], beams, AXLE_KG), accel.mean(axis=0)


def test_without_noise_the_cross_estimate_is_h1():
    frame = rig_run(530e3, 3.0e3, seed=1)
    cross, h1 = _broadband(frame), _broadband(frame, pair=False)
    assert cross.estimator == "accelerometer_cross" and h1.estimator == "h1"
    assert cross.fit.stiffness_N_per_m == pytest.approx(h1.fit.stiffness_N_per_m, rel=1e-6)
    assert cross.fit.stiffness_N_per_m == pytest.approx(530e3, rel=0.002)
    assert cross.fit.damping_N_s_per_m == pytest.approx(3.0e3, rel=0.01)


def test_accelerometer_noise_pulls_h1_towards_the_axle_mass_and_not_the_reported_estimate():
    """Noise n on the accelerometers is in both channels (the tyre force is M_a ā − Σ beams), so H1
    per bin is ``(Z S_xx + ω² M_a S_nn) / (S_xx + S_nn)``: pulled towards ω² M_a (K low below
    sqrt(K / M_a), high above); the two accelerometers' cross-spectrum takes S_nn out."""
    K, C = 530e3, 3.0e3
    r = _broadband(rig_run(K, C, seed=3, accel_noise=0.6))
    f, use = r.frequency_Hz, r.in_fit
    w2m = (2 * np.pi * f) ** 2 * AXLE_KG
    k_h1 = ((2 * np.pi * f) ** 2 * r.h1_kg).real
    low, high = use & (w2m < 0.5 * K), use & (w2m > 1.5 * K)
    assert np.mean(k_h1[low]) < np.mean(r.stiffness_N_per_m_f[low]) and np.mean(k_h1[high]) > np.mean(r.stiffness_N_per_m_f[high])
    assert r.stiffness_u_N_per_m == pytest.approx(math.hypot(r.stiffness_u_a_N_per_m, r.stiffness_u_b_N_per_m))
    assert np.isfinite(r.h1_h2_stiffness_spread) and r.h1_h2_expected_spread > 0


def test_a_rolling_run_with_too_few_bins_to_choose_its_model_is_flagged_never_kelvin_voigt():
    frame = rig_run(261.5e3, 1.5e3, 20e3, seed=2, speed_km_h=5.0, band_Hz=(3.0, 4.75))
    row = _analyse(frame, rolling=True, band=(3.0, 4.75), direction="lateral")
    assert row["fit_bins"] < bb.MIN_CHOICE_BINS
    assert row["model"] == "maxwell" and np.isfinite(row["stiffness_N_per_m"])
    assert any("too few to choose" in r for r in row["reasons"])  # reported, QC not passed
    # with the whole band the F test finds the series damper
    row = _analyse(rig_run(261.5e3, 1.5e3, 20e3, seed=2, speed_km_h=5.0), rolling=True, direction="lateral")
    assert row["model"] == "maxwell" and row["model_test_p"] < bb.MODEL_TEST_LEVEL and not row["reasons"]


def test_a_kelvin_voigt_tyre_rolling_is_mostly_reported_kelvin_voigt():
    models = [_analyse(rig_run(530e3, 3.0e3, seed=s, accel_noise=0.3), rolling=True)["model"] for s in range(6)]
    assert models.count("kelvin_voigt") >= 4


def test_a_rolling_run_over_a_rough_road_is_flagged_and_a_smooth_one_is_not():
    """The ground's height under a rolling tyre is a second input no channel records: ISO 8608 class
    C at 5 km/h takes C of this tyre −74 % and K −6 % (10 runs); its effect, estimated from the axle's
    motion outside the drive band, is significant and large against the type A interval. A smooth
    run's is bounded small: ``ok``."""
    K, C, c2 = 261.5e3, 1.5e3, 20e3
    smooth = _analyse(rig_run(K, C, c2, seed=4, speed_km_h=5.0), rolling=True, direction="lateral")
    rough = _analyse(rig_run(K, C, c2, seed=3, speed_km_h=5.0, road="C"), rolling=True, direction="lateral")
    assert smooth["qc_ground_input"] == "ok" and not smooth["reasons"]
    assert abs(smooth["ground_damping_effect_N_s_per_m"]) < 0.01 * C
    assert rough["qc_ground_input"] == "biased"
    assert any("ground's input under the tyre" in r for r in rough["reasons"])
    # the effect is what the ground took off: K and C both lowered, C most
    assert -0.10 < rough["ground_stiffness_effect_N_per_m"] / K < -0.01
    assert -1.0 < rough["ground_damping_effect_N_s_per_m"] / C < -0.2


def test_accelerometer_noise_alone_does_not_flag_a_rolling_run():
    """Noise 0.3 on the accelerometers and no ground: the ground's level outside the band is zero
    within its standard error (the two accelerometers' cross-spectrum, signed), so the run is not
    flagged (the old |ratio| check flagged every such run: 0.9–1.1 % against 0.01 %); the noise
    leaves the effect too uncertain to bound: ``undetermined``."""
    K, C, c2 = 261.5e3, 1.5e3, 20e3
    row = _analyse(rig_run(K, C, c2, seed=1, speed_km_h=5.0, accel_noise=0.3), rolling=True, direction="lateral")
    assert row["qc_ground_input"] == "undetermined" and not row["reasons"], row["reasons"]
    assert np.isfinite(row["ground_damping_effect_u_N_s_per_m"]) and row["ground_damping_effect_u_N_s_per_m"] > 0


def test_the_ground_state_is_only_for_rolling_broadband_runs():
    row = _analyse(rig_run(530e3, 3.0e3, seed=1))
    assert row.get("qc_ground_input") is None and math.isnan(row.get("ground_stiffness_effect_N_per_m", math.nan))


def test_free_vibration_finds_the_release_after_a_dwell_at_resonance():
    """A dwell at resonance before the release: the largest |a| is a dwell cycle; the decay is found
    from the envelope (C was −62 % with the largest |a| as the release)."""
    K, C = 560e3, 3.12e3
    rows = [_analyse(dwell_decay(K, C, seed=s), "free_vibration") for s in range(6)]
    c = np.array([r["damping_N_s_per_m"] for r in rows])
    assert np.all(np.abs(c / C - 1) < 0.03), c
    assert np.mean([r["damping_ci95_low_N_s_per_m"] <= C <= r["damping_ci95_high_N_s_per_m"] for r in rows]) >= 5 / 6


def test_an_eight_second_decay_is_not_held_to_the_stepped_sines_minimum():
    frame = dwell_decay(560e3, 3.12e3, dwell_s=2.0, decay_s=6.0)
    info = check_run(frame, 0.0, 256.0, method="free_vibration")
    assert info.duration_s == pytest.approx(8.0) and info.duration_s < MIN_DURATION_s
    with pytest.raises(RunFileError, match="truncated"):
        check_run(frame, 0.0, 256.0)


def _summary(K, C, c2, method, options, runs, direction=None, seeds=None):
    """Bias, scatter and type A 95 % coverage of K and C over ``runs`` seeded runs (through
    :func:`tyrelab.measurement.analyse_method_run`); every run counts, a refused one as not covered."""
    direction = direction or ("vertical" if c2 is None else "lateral")
    rows = [_analyse(rig_run(K, C, c2, method=method, seed=s, **options), method, rolling=c2 is not None,
                     direction=direction) for s in (seeds if seeds is not None else range(runs))]
    out = {"runs": len(rows), "flagged": sum(bool(r["reasons"]) for r in rows)}
    for name, unit, truth in (("stiffness", "N_per_m", K), ("damping", "N_s_per_m", C)):
        v = np.array([r[f"{name}_{unit}"] for r in rows])
        ua = np.array([r[f"{name}_u_a_{unit}"] * r["coverage_factor"] for r in rows])
        cov = float(np.mean(np.abs(v - truth) <= ua))
        out[name] = {"bias": float(np.nanmean(v / truth - 1)), "sd": float(np.nanstd(v / truth, ddof=1)),
                     "coverage_a": cov, "coverage_se": math.sqrt(cov * (1 - cov) / len(rows))}
    return out


@pytest.mark.parametrize("case", ["vertical KV, random, accelerometer noise 0.3",
                                  "lateral rolling, random, accelerometer noise 0.3"])
def test_a_few_noisy_runs_keep_k_within_one_percent(case):
    K, C, c2, method, options, direction = CASES[case]
    s = _summary(K, C, c2, method, options, runs=3, direction=direction)
    assert abs(s["stiffness"]["bias"]) < 0.01 + 2 * s["stiffness"]["sd"] / math.sqrt(3)


@pytest.mark.slow
@pytest.mark.parametrize("case", list(CASES))
def test_monte_carlo_bias_and_coverage(case):
    """40 seeded runs per case: K's bias within ±1 % and C's within 5 % (or its own scatter's
    standard error, twice), 95 % coverage of the type A interval alone ≥ 0.90 (issue 44, Deliver 1):
    failed where the 40 runs' coverage is below 0.90 by more than the one-sided 5 % binomial margin
    (1.645 × sqrt(0.9 × 0.1 / 40) = 0.078; docs/rig_methods.md has the 200-run table)."""
    K, C, c2, method, options, direction = CASES[case]
    n = 40
    s = _summary(K, C, c2, method, options, runs=n, direction=direction)
    assert abs(s["stiffness"]["bias"]) <= 0.01
    assert abs(s["damping"]["bias"]) <= max(0.05, 2 * s["damping"]["sd"] / math.sqrt(n))
    margin = 1.645 * math.sqrt(0.9 * 0.1 / n)
    assert s["stiffness"]["coverage_a"] >= 0.90 - margin and s["damping"]["coverage_a"] >= 0.90 - margin


def coverage_table(runs: int) -> str:
    """The Monte Carlo's table (markdown): every case of :data:`CASES`, ``runs`` seeded runs each."""
    lines = ["| case | runs (flagged) | K bias ± sd | C bias ± sd | type A coverage K | type A coverage C |",
             "|---|---|---|---|---|---|"]
    for case, (K, C, c2, method, options, direction) in CASES.items():
        s = _summary(K, C, c2, method, options, runs, direction)
        k, c = s["stiffness"], s["damping"]
        lines.append(f"| {case} | {s['runs']} ({s['flagged']}) | {100 * k['bias']:+.2f} ± {100 * k['sd']:.2f} % | "
                     f"{100 * c['bias']:+.2f} ± {100 * c['sd']:.2f} % | {k['coverage_a']:.3f} ± {k['coverage_se']:.3f} | "
                     f"{c['coverage_a']:.3f} ± {c['coverage_se']:.3f} |")
    return "\n".join(lines)


#: The ground-input cases (issue 44, Deliver 3): the lateral rolling tyre at 5 km/h over no road and ISO
#: 8608 classes A, B, C, without noise and under accelerometer noise 0.3: name → (method, options).
GROUND_CASES = {
    f"{method.replace('_sine', '')}, {road or 'no road'}, {noise}": (method, {**options, **({"road": road} if road else {})})
    for method in ("random", "swept_sine") for noise, options in list(NOISES.items())[::2]
    for road in (None, "A", "B", "C")
}


def ground_table(runs: int) -> str:
    """The ground check's table (markdown): per case of :data:`GROUND_CASES`, ``runs`` seeded runs of the
    lateral rolling tyre through :func:`tyrelab.measurement.analyse_method_run`: how many runs each
    ``qc_ground_input`` state got, the measured bias of K and C and the mean estimated effect."""
    K, C, c2, _, _, _ = CASES["lateral rolling, random, no noise"]
    lines = ["| case | runs | ok / undetermined / biased (refused) | K bias | K effect | C bias | C effect |",
             "|---|---|---|---|---|---|---|"]
    for case, (method, options) in GROUND_CASES.items():
        rows = [_analyse(rig_run(K, C, c2, method=method, seed=s, speed_km_h=5.0, **options), method, rolling=True,
                         direction="lateral") for s in range(runs)]
        fitted = [r for r in rows if np.isfinite(r.get("stiffness_N_per_m", math.nan))]
        states = [r.get("qc_ground_input") for r in fitted]
        mean = lambda key, truth: 100 * float(np.mean([r[key] for r in fitted])) / truth  # noqa: E731
        lines.append(f"| {case} | {len(rows)} | {states.count('ok')} / {states.count('undetermined')} / "
                     f"{states.count('biased')} ({len(rows) - len(fitted)}) | {mean('stiffness_N_per_m', K) - 100:+.2f} % | "
                     f"{mean('ground_stiffness_effect_N_per_m', K):+.2f} % | {mean('damping_N_s_per_m', C) - 100:+.1f} % | "
                     f"{mean('ground_damping_effect_N_s_per_m', C):+.1f} % |")
    return "\n".join(lines)


if __name__ == "__main__":
    import sys

    n = int(sys.argv[1]) if len(sys.argv) > 1 else 40
    print(ground_table(n) if "--ground" in sys.argv else coverage_table(n))
