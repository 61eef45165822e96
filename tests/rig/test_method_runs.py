"""Issue 34: the virtual test vehicle records every method and direction; Table I from those recordings."""

import numpy as np
import pandas as pd
import pytest

from tyrelab.measurement import rig_methods as rm
from tyrelab.measurement.methods import table_i_from_results
from tyrelab.measurement.recording import analyse_frame, recording_arrays
from tyrelab.published import read_published
from tyrelab.rig import truth
from tyrelab.rig.campaigns import campaign_plan, simulate_run
from tyrelab.rig.method_runs import directional_truth


def test_directional_truths_have_the_thesis_tendencies():
    L = truth.NOMINAL_LOAD_KN
    for d in ("lateral", "longitudinal"):
        k_lo, c_lo, _ = directional_truth("T1", d, 1.38, 0.0, 0.8 * L)
        k_hi, c_hi, _ = directional_truth("T1", d, 1.38, 0.0, 1.2 * L)
        assert k_lo == k_hi and c_hi > c_lo  # stiffness independent of load, damping rising with it
        assert directional_truth("T1", d, 1.8, 0.0, L)[0] > directional_truth("T1", d, 1.0, 0.0, L)[0]
        c2 = [directional_truth("T1", d, 1.38, v, L)[2] for v in (0.0, 2.5, 5.0, 10.0)]
        assert c2[0] == np.inf and c2[1] > c2[2] > c2[3]  # the series damper falls with speed (rolling only)
    with pytest.raises(ValueError, match="direction"):
        directional_truth("T1", "diagonal", 1.38, 0.0, L)


@pytest.fixture(scope="module")
def table_i_recordings():
    """The small plan's Table I runs (T1, 1.38 bar, stationary) recorded and analysed one by one."""
    plan = campaign_plan("small")
    p0 = plan.loc[plan["method"] == "free_vibration", "pressure_bar"].iloc[0]
    case = plan[(plan["tyre_id"] == "T1") & (plan["pressure_bar"] == p0) & (plan["speed_km_h"] == 0)
                & (plan["kind"] == "measurement") & (plan["direction"] == "vertical")
                & ((plan["method"] != "stepped_sine") | (plan["excitation_frequency_Hz"] == 4.0))]
    rows = []
    for r in case.to_dict("records"):
        run, info = simulate_run(r, 1991)
        fields = {k: r[k] for k in ("run_id", "tyre_id", "pressure_bar", "load_kN", "speed_km_h", "method",
                                    "direction", "excitation_frequency_Hz")}
        if r["method"] == "stepped_sine":
            res = analyse_frame(run, r["axle_mass_kg"])
            fields.update(stiffness_N_per_m=res.stiffness_N_per_m, damping_N_s_per_m=res.damping_N_s_per_m,
                          qc_ok=res.qc_ok)
        else:
            accel, beams = recording_arrays(run)
            out, _ = rm.analyse_method_run(r["method"], "vertical", run["time_s"].to_numpy(), accel, beams,
                                           r["axle_mass_kg"], band_Hz=(r["band_low_Hz"], r["band_high_Hz"])
                                           if r["method"] in rm.BROADBAND else None,
                                           deflection_m=run.get("deflection_m"))
            fields.update({k: v for k, v in out.items() if k not in ("reasons",)}, qc_ok=not out["reasons"])
        fields["truth_stiffness_N_per_m"] = info["stiffness_N_per_m"]
        rows.append(fields)
    return pd.DataFrame(rows)


def test_table_i_ordering_from_virtual_recordings(table_i_recordings):
    r = table_i_recordings
    assert set(r["method"]) == {"stepped_sine", "random", "swept_sine", "free_vibration", "load_deflection"}
    assert r["qc_ok"].all()
    t = table_i_from_results(r, read_published("table_i")).set_index("method")
    assert t["source"].str.startswith("recordings: T1 at 1.38 bar").all()
    k, c = t["stiffness_kN_per_m"], t["damping_kN_s_per_m"]
    # thesis Table I: the apparent-mass damping lowest, free vibration the stiffest, load deflection the softest
    assert c["apparent_mass"] < c["free_vibration"] and c["apparent_mass"] < c["forced_vibration"]
    assert k["free_vibration"] == k.max() and k["load_deflection"] == k.min()
    assert np.isnan(c["load_deflection"])


def test_table_i_falls_back_without_recordings_of_several_methods(table_i_recordings):
    only_stepped = table_i_recordings[table_i_recordings["method"] == "stepped_sine"]
    assert table_i_from_results(only_stepped, read_published("table_i")) is None
