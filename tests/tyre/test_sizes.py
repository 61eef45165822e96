import math

import pytest

from tyrelab.tyre.sizes import TyreSizeError, parse_tyre_size


@pytest.mark.parametrize(
    "text,w,r,construction",
    [
        ("13.6R38", 13.6, 38, "radial"),
        ("13.6-38", 13.6, 38, "cross-ply"),
        ("16.9/14R30", 16.9, 30, "radial"),
        ("11.2/10-24", 11.2, 24, "cross-ply"),
        ("7.50-18", 7.5, 18, "cross-ply"),
        ("9.5R44", 9.5, 44, "radial"),
        ("13.6 R 38", 13.6, 38, "radial"),
        ("12-38", 12, 38, "cross-ply"),
        ("13.6/12-36", 13.6, 36, "cross-ply"),
    ],
)
def test_parses_table_ii_and_xix_sizes(text, w, r, construction):
    s = parse_tyre_size(text)
    assert (s.section_width_in, s.rim_diameter_in, s.construction) == (w, r, construction)


def test_dual_designation_keeps_alternative_width():
    assert parse_tyre_size("16.9/14R30").alternative_width_in == 14
    assert parse_tyre_size("13.6R38").width_times_rim_in2 == pytest.approx(516.8)


@pytest.mark.parametrize("bad", ["", "13.6", "R38", "13,6R38", "abc", "13.6X38", "0.1R38", "13.6R3", None, 13.6])
def test_unparseable_size_is_a_clear_error(bad):
    with pytest.raises(TyreSizeError, match="tyre size"):
        parse_tyre_size(bad)


# --- metric (ETRTO/ISO) sizes, markings and service descriptions (issue 12) -----------------

from tyrelab.tyre.sizes import (  # noqa: E402
    DEFAULT_ASPECT_RATIO,
    LOAD_INDEX_kg,
    SPEED_SYMBOL_km_h,
    load_index_kg,
    rolling_circumference_m,
    speed_symbol_km_h,
)


@pytest.mark.parametrize(
    "text,width_mm,aspect,rim",
    [
        ("480/70R38", 480, 0.70, 38),
        ("650/65R42", 650, 0.65, 42),
        ("380/85R28", 380, 0.85, 28),
        ("540/65R28", 540, 0.65, 28),
        ("480/70 R38", 480, 0.70, 38),
    ],
)
def test_metric_sizes(text, width_mm, aspect, rim):
    s = parse_tyre_size(text)
    assert s.metric and s.aspect_ratio_stated
    assert s.section_width_mm == pytest.approx(width_mm)
    assert s.section_width_in == pytest.approx(width_mm / 25.4)
    assert s.aspect_ratio == pytest.approx(aspect)
    assert s.rim_diameter_in == rim
    assert s.construction == "radial"
    assert s.section_height_mm == pytest.approx(aspect * width_mm)
    assert s.outer_diameter_m == pytest.approx(rim * 0.0254 + 2 * aspect * width_mm / 1000)
    assert s.flexion_class is None and s.service is None


def test_480_70R38_numbers_of_the_issue():
    s = parse_tyre_size("480/70R38")
    assert s.section_width_in == pytest.approx(18.898, abs=1e-3)
    assert s.section_height_mm == pytest.approx(336)


@pytest.mark.parametrize(
    "text,flex,markings,factor",
    [
        ("IF 710/70R42", "IF", ("IF",), 1.2),
        ("IF710/70R42", "IF", ("IF",), 1.2),
        ("VF 600/70R30", "VF", ("VF",), 1.4),
        ("CFO 800/70R32", None, ("CFO",), 1.0),
        ("VF 900/60R32 CFO", "VF", ("VF", "CFO"), 1.4),
        ("PFO 650/65R38", None, ("PFO",), 1.0),
    ],
)
def test_flexion_and_service_markings(text, flex, markings, factor):
    s = parse_tyre_size(text)
    assert (s.flexion_class, s.markings, s.flexion_load_factor) == (flex, markings, factor)
    assert s.metric


def test_load_index_and_speed_symbol():
    s = parse_tyre_size("480/70R38 145D")
    assert (s.load_index, s.load_kg, s.speed_symbol, s.speed_km_h) == (145, 2900, "D", 65)
    s = parse_tyre_size("520/85R42 157A8/154B")
    assert (s.load_index, s.load_kg, s.speed_symbol, s.speed_km_h) == (157, 4125, "A8", 40)
    assert (s.alternative_service.load_index, s.alternative_service.load_kg) == (154, 3750)
    assert (s.alternative_service.speed_symbol, s.alternative_service.speed_km_h) == ("B", 50)
    assert str(s.service) == "157A8"
    # Table II prints the Silsoe T5's service description as 146/A8
    s = parse_tyre_size("13.6R38 146/A8")
    assert (s.load_index, s.load_kg, s.speed_km_h) == (146, 3000, 40)
    s = parse_tyre_size("IF 710/70R42 173D")
    assert (s.flexion_class, s.load_kg) == ("IF", 6500)


def test_tread_code_ply_rating_and_tubeless():
    s = parse_tyre_size("18.4R38 146A8 R-1W 8PR TL")
    assert (s.tread_code, s.ply_rating, s.tubeless) == ("R-1W", 8, True)
    assert (s.section_width_in, s.rim_diameter_in, s.load_kg) == (18.4, 38, 3000)
    assert parse_tyre_size("7.50-18 F-2 TT").tread_code == "F-2"
    assert parse_tyre_size("7.50-18 F-2 TT").tubeless is False


def test_inch_sizes_take_the_85_series_default_aspect_ratio():
    for text in ("13.6R38", "13.6-38", "16.9/14R30", "7.50-18", "18.4R38"):
        s = parse_tyre_size(text)
        assert s.aspect_ratio == DEFAULT_ASPECT_RATIO == 0.85
        assert not s.aspect_ratio_stated and not s.metric
    # inch-width low-section implement size: the second number is an aspect ratio
    s = parse_tyre_size("10.0/75-15.3")
    assert (s.section_width_in, s.aspect_ratio, s.rim_diameter_in, s.alternative_width_in) == (10.0, 0.75, 15.3, None)


def test_rolling_circumference_from_the_aspect_ratio():
    # 13.6R38: the thesis' 4.66 m (§4.5.1); unchanged for inch sizes
    assert rolling_circumference_m(parse_tyre_size("13.6R38")) == pytest.approx(4.66, abs=0.005)
    # 480/70R38: pi * (38 in + 2 * 0.70 * 480 mm) * 0.956
    expected = 3.141592653589793 * (38 * 0.0254 + 2 * 0.70 * 0.480) * 0.956
    assert rolling_circumference_m("480/70R38") == pytest.approx(expected)
    # an explicit aspect ratio wins over the size's
    assert rolling_circumference_m("480/70R38", 0.85) > rolling_circumference_m("480/70R38")
    with pytest.raises(ValueError, match="aspect_ratio"):
        rolling_circumference_m("480/70R38", 0.0)


def test_load_index_table_known_points_and_structure():
    assert len(LOAD_INDEX_kg) == 280
    assert (load_index_kg(142), load_index_kg(165), load_index_kg(168)) == (2650, 5150, 5600)
    assert (load_index_kg(0), load_index_kg(100), load_index_kg(146), load_index_kg(279)) == (45, 800, 3000, 136000)
    assert all(b > a for a, b in zip(LOAD_INDEX_kg, LOAD_INDEX_kg[1:]))
    # from LI 100 on, 80 indices further is ten times the load
    assert [n for n in range(100, 200) if LOAD_INDEX_kg[n + 80] != 10 * LOAD_INDEX_kg[n]] == []
    # and LI 20-99 are the same series to fewer digits (within 1 %)
    assert all(abs(LOAD_INDEX_kg[n + 80] / (10 * LOAD_INDEX_kg[n]) - 1) < 0.01 for n in range(20, 100))
    with pytest.raises(ValueError, match="load_index"):
        load_index_kg(280)
    with pytest.raises(ValueError, match="load_index"):
        load_index_kg(1.5)


def test_speed_symbols():
    assert [speed_symbol_km_h(f"A{i}") for i in range(1, 9)] == [5, 10, 15, 20, 25, 30, 35, 40]
    assert (speed_symbol_km_h("B"), speed_symbol_km_h("C"), speed_symbol_km_h("D")) == (50, 60, 65)
    assert list(SPEED_SYMBOL_km_h.values())[8:] == sorted(list(SPEED_SYMBOL_km_h.values())[8:])
    with pytest.raises(ValueError, match="symbol"):
        speed_symbol_km_h("Z")


@pytest.mark.parametrize(
    "bad,part",
    [
        ("480/70R38 145Z", "'145Z'"),
        ("480R38", "implausible"),
        ("13.6R38 foo", "'FOO'"),
        ("IF VF 480/70R38", "both IF and VF"),
        ("480/70R38 300D", "load index 300"),
        ("480/70R38 13.6R38", "more than one size"),
    ],
)
def test_bad_designations_name_the_text_and_the_part(bad, part):
    with pytest.raises(TyreSizeError) as info:
        parse_tyre_size(bad)
    msg = str(info.value)
    assert repr(bad) in msg and part in msg
    if "both" not in msg and "load index 300" not in msg:
        assert "e.g. 480/70R38" in msg


def test_parsed_size_is_frozen():
    s = parse_tyre_size("480/70R38")
    with pytest.raises(AttributeError):
        s.aspect_ratio = 0.5


def test_load_index_and_speed_symbol_tables_against_the_standard():
    # ISO 4000-1 / ETRTO: LI 90-99 (common on tractor fronts) and every tenth index, as printed
    assert [load_index_kg(n) for n in range(90, 100)] == [600, 615, 630, 650, 670, 690, 710, 730, 750, 775]
    assert [load_index_kg(n) for n in range(60, 180, 10)] == [250, 335, 450, 600, 800, 1060, 1400, 1900, 2500,
                                                              3350, 4500, 6000]
    assert {s: speed_symbol_km_h(s) for s in "BCDEFGJKLMNPQRSTUHVWY"} == {
        "B": 50, "C": 60, "D": 65, "E": 70, "F": 80, "G": 90, "J": 100, "K": 110, "L": 120, "M": 130, "N": 140,
        "P": 150, "Q": 160, "R": 170, "S": 180, "T": 190, "U": 200, "H": 210, "V": 240, "W": 270, "Y": 300}


def test_catalogue_circumference_then_outer_diameter_then_size():
    from tyrelab.tyre.sizes import ROLLING_FACTOR, tyre_rolling_circumference_m

    assert tyre_rolling_circumference_m("480/70R38", catalogue_m=4.9, outer_diameter_m=1.65) == 4.9
    assert tyre_rolling_circumference_m("480/70R38", outer_diameter_m=1.65) == pytest.approx(math.pi * 1.65 * ROLLING_FACTOR)
    assert tyre_rolling_circumference_m("480/70R38", outer_diameter_m=float("nan")) == rolling_circumference_m("480/70R38")
