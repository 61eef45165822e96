"""The tyre catalogue: the old columns and the optional columns of a user's measured tyre (issue 12)."""

import pandas as pd
import pytest

from tyrelab.stages.analyse import wheel_interference_Hz
from tyrelab.stages.ingest import BUILTIN_TYRES, load_catalogue
from tyrelab.tyre.sizes import ROLLING_FACTOR, rolling_circumference_m

EXTENDED = (
    "tyre_id,size,position,source,outer_diameter_m,rolling_circumference_m,lugs_per_side,"
    "carcass_stiffness_kN_per_m,pressure_dependence_kN_per_m_bar,carcass_damping_kN_s_per_m,"
    "pressure_dependence_kN_s_per_m_bar,measured_speed_km_h,tested_load_kN,"
    "measured_pressure_min_bar,measured_pressure_max_bar\n"
    "MY1,IF 710/70R42 173D,rear_traction,our rig 2026,2.05,6.1,24,140,260,1.2,0.4,12,40,0.6,1.6\n"
    "MY2,480/70R38 145D,rear_traction,,1.64,,,,,,,,,,\n"
    "MY3,650/65R42,rear_traction,,,,,,,,,,,,\n"
)


def test_old_catalogue_still_loads_without_problems(tmp_path):
    cat, problems = load_catalogue(tmp_path, [])
    assert problems == []
    assert len(cat) == len(pd.read_csv(BUILTIN_TYRES)) and cat["size_ok"].all()


def test_extended_catalogue_loads_and_parses_metric_sizes(tmp_path):
    campaign = tmp_path / "c1"
    campaign.mkdir()
    (campaign / "tyres.csv").write_text(EXTENDED)
    cat, problems = load_catalogue(tmp_path, [campaign])
    assert problems == []
    my = cat.set_index("tyre_id").loc[["MY1", "MY2", "MY3"]]
    assert my["size_ok"].all()
    assert my.loc["MY1", "section_width_in"] == pytest.approx(710 / 25.4)
    assert my.loc["MY1", "rim_diameter_in"] == 42 and my.loc["MY1", "construction"] == "radial"
    assert float(my.loc["MY1", "carcass_stiffness_kN_per_m"]) == 140
    assert "T1" in set(cat["tyre_id"])  # the built-in tyres are still there


def test_bad_optional_value_is_one_line_naming_the_file(tmp_path):
    (tmp_path / "tyres.csv").write_text("tyre_id,size,lugs_per_side\nMY1,480/70R38,-3\n")
    cat, problems = load_catalogue(tmp_path, [])
    assert len(problems) == 1 and "tyres.csv" in problems[0] and "lugs_per_side" in problems[0]
    assert "MY1" in set(cat["tyre_id"])


def test_lug_passing_uses_measured_circumference_diameter_and_lugs(tmp_path):
    campaign = tmp_path / "c1"
    campaign.mkdir()
    (campaign / "tyres.csv").write_text(EXTENDED)
    cat = load_catalogue(tmp_path, [campaign])[0].set_index("tyre_id", drop=False)
    v = 10.0  # km/h
    # MY1: catalogue circumference 6.1 m and 24 lugs per side
    f = wheel_interference_Hz(v, cat.loc["MY1"])
    assert f[0] == pytest.approx(v / 3.6 / 6.1) and f[3] == pytest.approx(24 * v / 3.6 / 6.1)
    # MY2: only the outer diameter
    f = wheel_interference_Hz(v, cat.loc["MY2"])
    assert f[0] == pytest.approx(v / 3.6 / (3.141592653589793 * 1.64 * ROLLING_FACTOR))
    # MY3: from the size's stated aspect ratio
    f = wheel_interference_Hz(v, cat.loc["MY3"])
    assert f[0] == pytest.approx(v / 3.6 / rolling_circumference_m("650/65R42"))
    # thesis tyres unchanged: T1 4.66 m, F1 ribbed (no lugs)
    assert wheel_interference_Hz(v, cat.loc["T1"])[0] == pytest.approx(v / 3.6 / 4.66)
    assert len(wheel_interference_Hz(v, cat.loc["F1"])) == 3
