"""The sixth hostile round, the library's arguments (issue 46, Deliver 4): every numeric argument of
``tyrelab.ride``, ``ride_sweep``, ``road_class``, ``vehicle_frf`` and ``analyse_recording`` finite and
in the range of the ``tyrelab`` option of the same meaning, checked before any file is read: an
integer of 400 digits, a bool, NaN or a string is one ValueError naming the argument, never an
OverflowError; a bound given to the work (``max_*``) is a bound, up to the CLI's ceiling."""

import pytest

import tyrelab
from tyrelab.cli import build_parser
from tyrelab.resources import scenarios_dir
from tyrelab.vehicle.scenario import limits

H = 10**400
MODERN = scenarios_dir() / "modern_tractor.toml"


def _no_reading(monkeypatch):
    """Reading a recording or a road fails the test: the arguments are refused first."""
    def fail(*a, **k):
        pytest.fail("a file was read")

    for target in ("tyrelab.api.read_run_file", "tyrelab.rawformat.rides.open_recording",
                   "tyrelab.scenario_io.read_crg", "tyrelab.scenario_io.read_profile_csv"):
        monkeypatch.setattr(target, fail)


@pytest.mark.parametrize("call, name", [
    (lambda: tyrelab.ride_sweep(MODERN, front_pressures_bar=[H]), "front_pressures_bar[0]"),
    (lambda: tyrelab.ride_sweep(MODERN, rear_pressures_bar=[1.2, True]), "rear_pressures_bar[1]"),
    (lambda: tyrelab.ride_sweep(MODERN, rear_pressures_bar="1.2"), "rear_pressures_bar"),
    (lambda: tyrelab.ride_sweep(MODERN, sets={"tractor.mass_kg": [H]}), "sets['tractor.mass_kg'][0]"),
    (lambda: tyrelab.ride_sweep(MODERN, sets={"tractor.mass_kg": ["x"]}), "sets['tractor.mass_kg'][0]"),
    (lambda: tyrelab.ride_sweep(MODERN, sets={"tractor.mass_kg": [True]}), "sets['tractor.mass_kg'][0]"),
    (lambda: tyrelab.ride_sweep(MODERN, max_variants=H), "max_variants"),
    (lambda: tyrelab.ride_sweep(MODERN, max_samples=10**12 + 1), "max_samples"),
    (lambda: tyrelab.ride_sweep(MODERN, max_rows=True), "max_rows"),
    (lambda: tyrelab.ride(MODERN, max_samples=H), "max_samples"),
    (lambda: tyrelab.ride(MODERN, max_rows=10**9 + 1), "max_rows"),
    (lambda: tyrelab.road_class("road.csv", track_width_m=H), "track_width_m"),
    (lambda: tyrelab.road_class("road.csv", start_m=True), "start_m"),
    (lambda: tyrelab.road_class("road.csv", length_m=1e308), "length_m"),
    (lambda: tyrelab.road_class("road.crg", lateral_offset_m=float("nan")), "lateral_offset_m"),
    (lambda: tyrelab.road_class("road.csv", fill_missing=2), "fill_missing"),
    (lambda: tyrelab.vehicle_frf("ride.csv", speed_km_h=H), "speed_km_h"),
    (lambda: tyrelab.vehicle_frf("ride.csv", speed_km_h=True), "speed_km_h"),
    (lambda: tyrelab.vehicle_frf("ride.csv", speed_km_h=1e308), "speed_km_h"),
    (lambda: tyrelab.vehicle_frf("ride.csv", sample_rate_Hz=float("nan")), "sample_rate_Hz"),
    (lambda: tyrelab.analyse_recording("run.parquet", axle_mass_kg=600.0, interference_Hz=[H]), "interference_Hz[0]"),
    (lambda: tyrelab.analyse_recording("run.parquet", axle_mass_kg=600.0, interference_Hz=[True]), "interference_Hz[0]"),
    (lambda: tyrelab.analyse_recording("run.parquet", axle_mass_kg=600.0, interference_Hz="5"), "interference_Hz"),
])
def test_a_bad_library_argument_is_one_value_error_naming_it_before_reading(monkeypatch, call, name):
    _no_reading(monkeypatch)
    with pytest.raises(ValueError) as info:
        call()
    assert str(info.value).startswith(name + " must"), str(info.value)
    assert "\n" not in str(info.value)


def test_road_class_checks_as_tyrelab_road_does():
    parser = build_parser()
    args = parser.parse_args(["road", "x.csv", "--track-width-m", "9"])
    from tyrelab.cli import _option_problems

    (cli,) = _option_problems(args, ("track_width_m",))
    with pytest.raises(ValueError) as info:
        tyrelab.road_class("x.csv", track_width_m=9.0)
    assert str(info.value) == cli.replace("--track-width-m", "track_width_m")  # one range, one line


def test_the_clis_bound_options_stop_where_the_librarys_do():
    parser = build_parser()
    for name, high in limits.BOUND_CEILINGS.items():
        option = "--" + name.replace("_", "-")
        assert getattr(parser.parse_args(["ride", "s.toml", option, str(high)]), name) == high
        with pytest.raises(SystemExit):
            parser.parse_args(["ride", "s.toml", option, str(high + 1)])
        assert limits.bound_argument(name, high) == high
        with pytest.raises(ValueError, match=name):
            limits.bound_argument(name, high + 1)
