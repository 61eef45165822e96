"""The truth model gives back the thesis tables it is calibrated on."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tyrelab.rig import truth
from tyrelab.rig.campaigns import pressures

PUBLISHED = Path(__file__).resolve().parents[2] / "raw" / "published"


def _fit(xs, ys):
    slope, intercept = np.polyfit(xs, ys, 1)
    return intercept, slope


@pytest.mark.parametrize("tid", list(truth.TYRES))
def test_table_iii_regressions(tid):
    p = truth.TYRES[tid]
    ps = pressures(tid, 5)
    k0 = [truth.stiffness(tid, P, 0.0) / 1e3 for P in ps]
    assert _fit(ps, k0) == pytest.approx(p.k_stationary, abs=0.5)
    pooled = [(P, truth.stiffness(tid, P, v) / 1e3) for P in ps for v in (10.0, 12.5, 15.0)]
    kc, dk = _fit(*zip(*pooled))
    assert (kc, dk) == pytest.approx(p.k_rolling, abs=0.5)


@pytest.mark.parametrize("tid", list(truth.TYRES))
def test_table_vii_regressions(tid):
    ps = pressures(tid, 5)
    for v, cc, dc in truth.TYRES[tid].damping_nodes:
        if v == 0 and tid != "F1":
            continue
        c = [truth.damping(tid, P, v) / 1e3 for P in ps]
        assert _fit(ps, c) == pytest.approx((cc, dc), abs=0.005)


def test_onset_of_rolling_drop_is_25_percent():
    for tid in ("T1", "T2", "T4", "T5"):  # §4.5.1 (T3's stationary/rolling span is too small: clipped)
        kc0, _ = truth.carcass_stiffness_kN_per_m(truth.TYRES[tid], 0.0)
        kc1, _ = truth.carcass_stiffness_kN_per_m(truth.TYRES[tid], 1.0)
        assert kc1 / kc0 == pytest.approx(0.75, abs=0.01)


def test_plateau_drift_table_vi():
    for tid in ("T1", "AS10"):
        k10, k15 = (truth.stiffness(tid, 1.38, v) for v in (10, 15))
        assert (k15 - k10) / 1e3 == pytest.approx(-8.0, abs=0.1)


@pytest.mark.parametrize("tid,v_peak", [("T1", 0.67), ("F1", 0.38)])
def test_damping_maximum_at_0_04_rev_per_s(tid, v_peak):
    vs = np.linspace(0, 3, 301)
    c = [truth.damping(tid, 1.38, v) for v in vs]
    assert vs[int(np.argmax(c))] == pytest.approx(v_peak, abs=0.02)
    assert truth.damping(tid, 1.38, 2 * v_peak) > truth.damping(tid, 1.38, 0)  # rise up to 10 % (§5.3.2)


def test_table_i_stationary_damping_and_surfaces():
    assert truth.damping("T1", 1.38, 0) == pytest.approx(3000, rel=1e-6)  # Table I anchor
    k = truth.stiffness("T5", 1.38, 10)
    assert truth.stiffness("T5", 1.38, 10, surface="artificial_rough_track") == pytest.approx(0.9 * k)
    c = truth.damping("T5", 1.38, 10)
    assert truth.damping("T5", 1.38, 10, surface="dry_cultivated_land") == pytest.approx(2.9 * c)
    with pytest.raises(ValueError):
        truth.stiffness("T5", 1.38, 10, surface="Concrete")


def test_secondary_effects_vanish_at_nominal():
    for tid in ("T2", "F1", "AS7"):
        assert truth.stiffness(tid, 1.5, 5, 18.3, 14.0, 4.0, 0.0, "concrete") == truth.stiffness(tid, 1.5, 5)
    # Table IV: T2 stationary -9.8 kN/m per mm
    d = truth.stiffness("T2", 1.38, 0, amplitude_mm_pp=24) - truth.stiffness("T2", 1.38, 0)
    assert d / 1e3 == pytest.approx(-98, abs=0.1)
    # §4.3.5: +10 %/octave stationary
    assert truth.stiffness("T1", 1.38, 0, frequency_Hz=2) == pytest.approx(truth.stiffness("T1", 1.38, 0) / 1.10)


def test_age_and_buffing():
    t = truth.TYRES["AS2"]
    b = truth.buffed(t)
    assert b.k_rolling == (t.k_rolling[0] / 2, t.k_rolling[1])
    assert truth.damping(b, 1.38, 15) == pytest.approx(0.7 * truth.damping(t, 1.38, 15))
    older = truth.aged(truth.TYRES["T5"], 10)
    assert truth.stiffness(older, 1.38, 12.5) - truth.stiffness("T5", 1.38, 12.5) == pytest.approx(56e3)


@pytest.mark.skipif(not (PUBLISHED / "table_iii.csv").exists(), reason="raw/published/table_iii.csv not digitised")
def test_constants_match_published_table_iii():
    tab = pd.read_csv(PUBLISHED / "table_iii.csv").dropna(subset=["carcass_stiffness_kN_per_m"])
    assert len(tab) >= 30
    for r in tab.itertuples():
        p = truth.TYRES[r.tyre_id]
        ours = p.k_stationary if r.condition == "stationary" else p.k_rolling
        assert ours == pytest.approx((r.carcass_stiffness_kN_per_m, r.pressure_dependence_kN_per_m_bar)), r.tyre_id


@pytest.mark.skipif(not (PUBLISHED / "table_vii.csv").exists(), reason="raw/published/table_vii.csv not digitised")
def test_constants_match_published_table_vii():
    tab = pd.read_csv(PUBLISHED / "table_vii.csv")
    for r in tab.itertuples():
        nodes = {v: (c, d) for v, c, d in truth.TYRES[r.tyre_id].damping_nodes}
        assert nodes[float(r.speed_km_h)] == pytest.approx(
            (r.carcass_damping_kN_s_per_m, r.pressure_dependence_kN_s_per_m_bar)), r.tyre_id
