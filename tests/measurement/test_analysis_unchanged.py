"""The analyse stage's ``results`` are unchanged by the speed-up of issue 15 §3 (analysis near the read floor).

A few seeded recordings, cheap: four closed-form spring-damper runs (20 s; different
frequencies, amplitudes and noise, one without excitation) in one batch and two 20 s
virtual-rig runs (a rough track at 5 km/h, a sweep run at 15 km/h), through ingest and
analyse. Every ``results`` column is compared with the values the code computed *before*
the FFT-sharing rewrite of :mod:`tyrelab.measurement.apparent_mass` (commit d0feb5f, stored
below as literals): floats to 1e-12 relative (the rewrite is in fact bit-identical), the
rest exactly. ``campaign`` (a temporary path) and ``input_hash`` (which hashes the
stage's code fingerprint by design, :func:`tyrelab.stages.analyse.input_hash`) are left out.
"""

import math

import pytest

from tests.synthetic import manifest_row, spring_damper_recording, write_campaign
from tyrelab.rig.campaigns import campaign_plan, simulate_run
from tyrelab.stages import Context, run_stage

NAN = math.nan
SPRING_DAMPERS = [
    dict(stiffness_N_per_m=250e3, damping_N_s_per_m=2000.0, frequency_Hz=4.0, force_noise_N=80,
         accel_noise_m_s2=0.05, seed=1),
    dict(stiffness_N_per_m=180e3, damping_N_s_per_m=1200.0, frequency_Hz=2.7, amplitude_mm_pp=6.0,
         force_noise_N=200, accel_noise_m_s2=0.1, seed=2),
    dict(stiffness_N_per_m=420e3, damping_N_s_per_m=3500.0, frequency_Hz=5.6, force_noise_N=20, seed=3),
    dict(amplitude_mm_pp=0.0, seed=4),  # no excitation: quarantined, NaN results
]


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("unchanged")
    runs = [(manifest_row(f"sd{i}", f"sd{i}.parquet", excitation_frequency_Hz=s.get("frequency_Hz", 4.0)),
             spring_damper_recording(duration_s=20.0, **s)) for i, s in enumerate(SPRING_DAMPERS)]
    plan = campaign_plan("small")
    meas = plan[plan["kind"] == "measurement"]
    for chosen in (meas[(meas["plan_set"] == "surface") & (meas["surface"] == "artificial_rough_track")],
                   meas[(meas["plan_set"] == "sweep") & (meas["speed_km_h"] == 15.0)]):
        r = {**chosen.iloc[0].to_dict(), "plan_duration_s": 20.0}
        run, _ = simulate_run(r, 1991)
        runs.append(({**{k: v for k, v in r.items() if not k.startswith("plan_")}, "file": f"{r['run_id']}.parquet"},
                     run))
    ctx = Context(raw=write_campaign(tmp / "raw", runs), build=tmp / "build", jobs=1)
    run_stage("ingest", ctx)
    run_stage("analyse", ctx)
    return ctx.read_table("stages/analysed")  # analyse's table (calibrate completes it into results)


def test_same_runs_and_columns(results):
    from tyrelab.measurement.rig_methods import METHOD_COLUMNS
    from tyrelab.stages.analyse import METHOD_CONDITION_COLUMNS

    assert sorted(results["run_id"]) == sorted(EXPECTED)
    cols = [c for c in results.columns if c not in ("campaign", "input_hash", "run_id")]
    # the old columns unmoved; issue 34 added its columns after them (add, never rename)
    assert cols == list(EXPECTED["sd0"]) + METHOD_CONDITION_COLUMNS + list(METHOD_COLUMNS)
    assert set(results["direction"]) == {"vertical"} and set(results["method"]) == {"stepped_sine"}


@pytest.mark.parametrize("run_id", ["sd0", "sd1", "sd2", "sd3", "T5_surface_003", "T2_sweep_003"])
def test_results_unchanged(results, run_id):
    row = results.set_index("run_id").loc[run_id]
    for col, want in EXPECTED[run_id].items():
        got = row[col]
        if isinstance(want, float):
            if math.isnan(want):
                assert math.isnan(got), col
            else:
                assert got == pytest.approx(want, rel=1e-12, abs=0.0), col
        else:
            assert (bool(got) if isinstance(want, bool) else got) == want, col


def test_empty_batch_gives_the_results_columns(results):
    """A batch of no runs (the empty ``results`` view) still yields every column."""
    from tyrelab.stages.analyse import empty_results

    empty = empty_results()
    assert len(empty) == 0 and sorted(empty.columns) == sorted(results.columns)


# Generated with the code of commit d0feb5f (before the change), 17 significant digits.
EXPECTED = {
    'T2_sweep_003': {
        'tyre_id': 'T2',
        'kind': 'measurement',
        'speed_km_h': 15.0,
        'pressure_bar': 0.83,
        'load_kN': 18.3,
        'excitation_frequency_Hz': 4.0,
        'amplitude_mm_pp': 14.0,
        'torque_kNm': 0.0,
        'surface': 'concrete',
        'axle_mass_kg': 600.0,
        'recorded_on': '1989-04-03',
        'excitation_frequency_measured_Hz': 4.015346723903908,
        'apparent_mass_real_kg': -527.8623872211723,
        'apparent_mass_imag_kg': -69.85268052998731,
        'stiffness_N_per_m': 335990.1603707932,
        'damping_N_s_per_m': 1762.3249801298434,
        'welch_stiffness_N_per_m': 334495.4208896071,
        'welch_damping_N_s_per_m': 1749.716840352163,
        'welch_frequency_Hz': 4.0,
        'coherence': 0.9999250280778976,
        'amplitude_measured_mm_pp': 14.156582937909109,
        'amplitude_measured_rms_mm': 5.005107896912654,
        'acceleration_amplitude_m_s2': 4.505136495583271,
        'stiffness_u_N_per_m': 6142.634473332816,
        'damping_u_N_s_per_m': 137.72727474106702,
        'stiffness_u_stat_N_per_m': 134.5261646850485,
        'damping_u_stat_N_s_per_m': 5.332168192938403,
        'uncertainty_dof_stat': 30.31578947368421,
        'uncertainty_dof': 131783346.12586753,
        'coverage_factor': 1.9599640025413516,
        'stiffness_ci95_low_N_per_m': 323950.81792229135,
        'stiffness_ci95_high_N_per_m': 348029.50281929504,
        'damping_ci95_low_N_s_per_m': 1492.3844577353655,
        'damping_ci95_high_N_s_per_m': 2032.2655025243214,
        'stiffness_kN_per_m': 335.9901603707932,
        'damping_kN_s_per_m': 1.7623249801298435,
        'welch_stiffness_kN_per_m': 334.4954208896071,
        'welch_damping_kN_s_per_m': 1.749716840352163,
        'qc_ok': True,
        'qc_reasons': '',
        'uncertainty_source': '§3.2.9 limits',
        'rolling': True,
    },
    'T5_surface_003': {
        'tyre_id': 'T5',
        'kind': 'measurement',
        'speed_km_h': 5.0,
        'pressure_bar': 1.38,
        'load_kN': 18.3,
        'excitation_frequency_Hz': 4.0,
        'amplitude_mm_pp': 14.0,
        'torque_kNm': 0.0,
        'surface': 'artificial_rough_track',
        'axle_mass_kg': 600.0,
        'recorded_on': '1989-05-02',
        'excitation_frequency_measured_Hz': 4.010994247715968,
        'apparent_mass_real_kg': -494.114279434316,
        'apparent_mass_imag_kg': -43.75314761316275,
        'stiffness_N_per_m': 313827.6608622651,
        'damping_N_s_per_m': 1102.6589560245968,
        'welch_stiffness_N_per_m': 311021.60042612464,
        'welch_damping_N_s_per_m': 1259.5546425655625,
        'welch_frequency_Hz': 4.0,
        'coherence': 0.9987896839413515,
        'amplitude_measured_mm_pp': 13.878731143737925,
        'amplitude_measured_rms_mm': 4.906872453001007,
        'acceleration_amplitude_m_s2': 4.405967887235166,
        'stiffness_u_N_per_m': 10048.524210217058,
        'damping_u_N_s_per_m': 350.3281327924818,
        'stiffness_u_stat_N_per_m': 8229.067758775069,
        'damping_u_stat_N_s_per_m': 326.52672378999154,
        'uncertainty_dof_stat': 30.31578947368421,
        'uncertainty_dof': 67.40241569607417,
        'coverage_factor': 1.995789323224953,
        'stiffness_ci95_low_N_per_m': 293772.9235293464,
        'stiffness_ci95_high_N_per_m': 333882.3981951838,
        'damping_ci95_low_N_s_per_m': 394.7123213241898,
        'damping_ci95_high_N_s_per_m': 1810.6055907250038,
        'stiffness_kN_per_m': 313.8276608622651,
        'damping_kN_s_per_m': 1.1026589560245967,
        'welch_stiffness_kN_per_m': 311.0216004261246,
        'welch_damping_kN_s_per_m': 1.2595546425655626,
        'qc_ok': True,
        'qc_reasons': '',
        'uncertainty_source': '§3.2.9 limits',
        'rolling': True,
    },
    'sd0': {
        'tyre_id': 'T1',
        'kind': 'measurement',
        'speed_km_h': 10.0,
        'pressure_bar': 1.38,
        'load_kN': 18.3,
        'excitation_frequency_Hz': 4.0,
        'amplitude_mm_pp': 14.0,
        'torque_kNm': 0.0,
        'surface': 'concrete',
        'axle_mass_kg': 600.0,
        'recorded_on': '1990-06-01',
        'excitation_frequency_measured_Hz': 3.9999912571562377,
        'apparent_mass_real_kg': -396.1172582857132,
        'apparent_mass_imag_kg': -78.56055681378164,
        'stiffness_N_per_m': 250208.22691704,
        'damping_N_s_per_m': 1974.4378296250015,
        'welch_stiffness_N_per_m': 250268.08945372194,
        'welch_damping_N_s_per_m': 1976.03804572802,
        'welch_frequency_Hz': 4.0,
        'coherence': 0.9999985640293229,
        'amplitude_measured_mm_pp': 14.00269322220029,
        'amplitude_measured_rms_mm': 4.950699666146366,
        'acceleration_amplitude_m_s2': 4.422414286900558,
        'stiffness_u_N_per_m': 4766.219462963193,
        'damping_u_N_s_per_m': 106.69202556478125,
        'stiffness_u_stat_N_per_m': 307.7500131388176,
        'damping_u_stat_N_s_per_m': 12.245010720963542,
        'uncertainty_dof_stat': 30.31578947368421,
        'uncertainty_dof': 1744105.3127480967,
        'coverage_factor': 1.9599653447061123,
        'stiffness_ci95_low_N_per_m': 240866.60194436836,
        'stiffness_ci95_high_N_per_m': 259549.85188971166,
        'damping_ci95_low_N_s_per_m': 1765.3238535113112,
        'damping_ci95_high_N_s_per_m': 2183.5518057386917,
        'stiffness_kN_per_m': 250.20822691704,
        'damping_kN_s_per_m': 1.9744378296250016,
        'welch_stiffness_kN_per_m': 250.26808945372196,
        'welch_damping_kN_s_per_m': 1.97603804572802,
        'qc_ok': True,
        'qc_reasons': '',
        'uncertainty_source': '§3.2.9 limits',
        'rolling': True,
    },
    'sd1': {
        'tyre_id': 'T1',
        'kind': 'measurement',
        'speed_km_h': 10.0,
        'pressure_bar': 1.38,
        'load_kN': 18.3,
        'excitation_frequency_Hz': 2.7,
        'amplitude_mm_pp': 14.0,
        'torque_kNm': 0.0,
        'surface': 'concrete',
        'axle_mass_kg': 600.0,
        'recorded_on': '1990-06-01',
        'excitation_frequency_measured_Hz': 2.7000111762972,
        'apparent_mass_real_kg': -627.1643269174741,
        'apparent_mass_imag_kg': -72.57121381429515,
        'stiffness_N_per_m': 180497.92272741566,
        'damping_N_s_per_m': 1231.1467339277926,
        'welch_stiffness_N_per_m': 186554.31527188548,
        'welch_damping_N_s_per_m': 1260.8388907745432,
        'welch_frequency_Hz': 2.75,
        'coherence': 0.9994419595747411,
        'amplitude_measured_mm_pp': 5.976810299433888,
        'amplitude_measured_rms_mm': 2.1131215462976507,
        'acceleration_amplitude_m_s2': 0.8600636659998216,
        'stiffness_u_N_per_m': 3580.3845789563475,
        'damping_u_N_s_per_m': 140.66395430840538,
        'stiffness_u_stat_N_per_m': 1501.848857841336,
        'damping_u_stat_N_s_per_m': 88.52802966177623,
        'uncertainty_dof_stat': 30.31578947368421,
        'uncertainty_dof': 979.225421795933,
        'coverage_factor': 1.9623895305107686,
        'stiffness_ci95_low_N_per_m': 173471.8135144695,
        'stiffness_ci95_high_N_per_m': 187524.0319403618,
        'damping_ci95_low_N_s_per_m': 953.7128544847213,
        'damping_ci95_high_N_s_per_m': 1508.5806133708638,
        'stiffness_kN_per_m': 180.49792272741567,
        'damping_kN_s_per_m': 1.2311467339277926,
        'welch_stiffness_kN_per_m': 186.55431527188549,
        'welch_damping_kN_s_per_m': 1.2608388907745431,
        'qc_ok': True,
        'qc_reasons': '',
        'uncertainty_source': '§3.2.9 limits',
        'rolling': True,
    },
    'sd2': {
        'tyre_id': 'T1',
        'kind': 'measurement',
        'speed_km_h': 10.0,
        'pressure_bar': 1.38,
        'load_kN': 18.3,
        'excitation_frequency_Hz': 5.6,
        'amplitude_mm_pp': 14.0,
        'torque_kNm': 0.0,
        'surface': 'concrete',
        'axle_mass_kg': 600.0,
        'recorded_on': '1990-06-01',
        'excitation_frequency_measured_Hz': 5.599994014037719,
        'apparent_mass_real_kg': -339.23768426153225,
        'apparent_mass_imag_kg': -99.40376701620842,
        'stiffness_N_per_m': 419990.00219226984,
        'damping_N_s_per_m': 3497.6010763432837,
        'welch_stiffness_N_per_m': 423766.02368790726,
        'welch_damping_N_s_per_m': 3513.944866450378,
        'welch_frequency_Hz': 5.625,
        'coherence': 0.9999999124955543,
        'amplitude_measured_mm_pp': 14.000029054515796,
        'amplitude_measured_rms_mm': 4.949757740628404,
        'acceleration_amplitude_m_s2': 8.666301816941031,
        'stiffness_u_N_per_m': 8261.602113864796,
        'damping_u_N_s_per_m': 134.68547170610512,
        'stiffness_u_stat_N_per_m': 63.70043950850406,
        'damping_u_stat_N_s_per_m': 1.8104019039111066,
        'uncertainty_dof_stat': 30.31578947368421,
        'uncertainty_dof': 8577411934.049052,
        'coverage_factor': 1.9599639848166257,
        'stiffness_ci95_low_N_per_m': 403797.55959220993,
        'stiffness_ci95_high_N_per_m': 436182.44479232974,
        'damping_ci95_low_N_s_per_m': 3233.62240221447,
        'damping_ci95_high_N_s_per_m': 3761.579750472097,
        'stiffness_kN_per_m': 419.99000219226986,
        'damping_kN_s_per_m': 3.4976010763432837,
        'welch_stiffness_kN_per_m': 423.76602368790725,
        'welch_damping_kN_s_per_m': 3.513944866450378,
        'qc_ok': True,
        'qc_reasons': '',
        'uncertainty_source': '§3.2.9 limits',
        'rolling': True,
    },
    'sd3': {
        'tyre_id': 'T1',
        'kind': 'measurement',
        'speed_km_h': 10.0,
        'pressure_bar': 1.38,
        'load_kN': 18.3,
        'excitation_frequency_Hz': 4.0,
        'amplitude_mm_pp': 14.0,
        'torque_kNm': 0.0,
        'surface': 'concrete',
        'axle_mass_kg': 600.0,
        'recorded_on': '1990-06-01',
        'excitation_frequency_measured_Hz': NAN,
        'apparent_mass_real_kg': NAN,
        'apparent_mass_imag_kg': NAN,
        'stiffness_N_per_m': NAN,
        'damping_N_s_per_m': NAN,
        'welch_stiffness_N_per_m': NAN,
        'welch_damping_N_s_per_m': NAN,
        'welch_frequency_Hz': NAN,
        'coherence': NAN,
        'amplitude_measured_mm_pp': NAN,
        'amplitude_measured_rms_mm': NAN,
        'acceleration_amplitude_m_s2': NAN,
        'stiffness_u_N_per_m': NAN,
        'damping_u_N_s_per_m': NAN,
        'stiffness_u_stat_N_per_m': NAN,
        'damping_u_stat_N_s_per_m': NAN,
        'uncertainty_dof_stat': NAN,
        'uncertainty_dof': NAN,
        'coverage_factor': NAN,
        'stiffness_ci95_low_N_per_m': NAN,
        'stiffness_ci95_high_N_per_m': NAN,
        'damping_ci95_low_N_s_per_m': NAN,
        'damping_ci95_high_N_s_per_m': NAN,
        'stiffness_kN_per_m': NAN,
        'damping_kN_s_per_m': NAN,
        'welch_stiffness_kN_per_m': NAN,
        'welch_damping_kN_s_per_m': NAN,
        'qc_ok': False,
        'qc_reasons': 'clipping in accel_left_m_s2; clipping in accel_right_m_s2; clipping in load_beam_1_N; clipping in load_beam_2_N; clipping in load_beam_3_N; clipping in load_beam_4_N; excitation not found',
        'uncertainty_source': '',
        'rolling': True,
    },
}

