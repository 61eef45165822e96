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
