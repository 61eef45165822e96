"""What each report page shows: thesis tables and figures per chapter (pure data).

A :class:`TableSpec` names our warehouse table (or a query producing our
values), the digitised thesis table and the stage that produces ours, so a
missing table gets a "not produced yet by stage X" note. A :class:`FigureSpec`
names a function of :mod:`tyrelab.report.figures` and the warehouse tables it
takes. :data:`CHAPTERS` lists the pages in thesis order.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .docs import Gap

__all__ = ["TableSpec", "FigureSpec", "Chapter", "CHAPTERS", "SPOKE_FIGURES", "ABBREVIATIONS", "Gap",
           "REFERENCE_VEHICLE_GAP"]


#: Abbreviations spelled out once on every page that uses them (first use on the page).
ABBREVIATIONS = {
    "SBT": "the artificial standard rough track (thesis §7.3; here a seeded stand-in of the ISO/TR 5007 "
           "slatted track)",
    "HH": "the Hussey Highway, an unmetalled farm track (thesis §7.3; here a seeded ISO 8608 class D track)",
    "EAV": "exposure action value of EU Directive 2002/44/EC, A(8) = 0.5 m/s²",
    "ELV": "exposure limit value of EU Directive 2002/44/EC, A(8) = 1.15 m/s²",
    "A(8)": "daily vibration exposure normalised to 8 h",
    "VDV": "vibration dose value (m/s^1.75)",
    "a_wz": "frequency-weighted r.m.s. vertical seat acceleration (ISO 2631-1, W_k), m/s²",
    "a_wx": "frequency-weighted r.m.s. fore-and-aft acceleration (ISO 2631-1, W_d), m/s²",
    "a_v": "vector sum of the weighted r.m.s. accelerations (ISO 2631-1), m/s²",
    "CG": "centre of gravity",
    "PSD": "power spectral density",
}


@dataclass(frozen=True)
class TableSpec:
    """A thesis table (or one of our own tables) shown on a chapter page.

    Attributes
    ----------
    number : str
        Thesis table number (``"III"``) or ``""`` for tables of our own.
    title : str
        Caption.
    view : str
        Our warehouse table.
    stage : str
        Stage that writes ``view``.
    published : str or None
        Digitised thesis table view (``published_table_iii``).
    ours_sql : str or None
        Query for our values when ``view`` has no thesis columns (input tables).
    keys : tuple of str
        Join keys between ``ours_sql`` and ``published``.
    values : dict
        our column -> thesis column, for ``ours_sql``.
    thesis_rename : dict
        Renames of the thesis table's columns before joining.
    columns : tuple of str
        Columns shown (all when empty); of a comparison table, the key and extra columns (its
        compared quantities are always shown).
    note : str
        Explanation shown under the caption.
    is_input : bool
        A thesis table the simulations take as printed (XV, XIX): shown with the
        thesis values and the note, never as "not produced yet".
    gaps : tuple of Gap
        Why ours differs from the thesis where ``docs/findings.md`` or ``docs/simulation.md``
        explains it: one sentence each and the section that explains it (a link on the page).
    """

    number: str
    title: str
    view: str
    stage: str
    published: str | None = None
    ours_sql: str | None = None
    keys: tuple[str, ...] = ()
    values: dict = field(default_factory=dict)
    thesis_rename: dict = field(default_factory=dict)
    columns: tuple[str, ...] = ()
    note: str = ""
    is_input: bool = False
    gaps: tuple[Gap, ...] = ()

    @property
    def anchor(self) -> str:
        """HTML id of the table's section."""
        return f"table-{self.number.lower()}" if self.number else self.view.replace("_", "-")


@dataclass(frozen=True)
class FigureSpec:
    """A figure: ``tyrelab.report.<module>.<function>(*tables, **kwargs)``.

    Attributes
    ----------
    number : str
        Thesis figure number(s).
    caption : str
        Caption.
    function : str
        Name of the drawing function in ``module``.
    inputs : tuple of str
        Warehouse tables passed positionally (empty DataFrame when missing).
    stage : str
        Stage that writes the first input.
    kwargs : dict
        Extra keyword arguments.
    module : str
        Module of this package holding ``function`` (:mod:`tyrelab.report.figures` by default;
        imported only where figures are drawn).
    """

    number: str
    caption: str
    function: str
    inputs: tuple[str, ...]
    stage: str
    kwargs: dict = field(default_factory=dict)
    module: str = "figures"


@dataclass(frozen=True)
class Chapter:
    """One report page."""

    slug: str
    title: str
    intro: str
    items: tuple = ()


#: Why the ch. 6-7 accuracy statistics (Tables XIII, XIV, XVII) differ from the thesis'.
REFERENCE_VEHICLE_GAP = Gap("Our \"measured\" vibration is the campaign's recordings, in the demo those of virtual "
                            "vehicles (dry-friction linkage, lift-off, a seeded stand-in for the surveyed tracks), not "
                            "the thesis' recordings, so these statistics reproduce the thesis' pattern, not its values.",
                            "simulation", 'The "measured" side: recordings (issue 24)')

#: Spoke-model curves: table -> (x column, x label, thesis figure).
SPOKE_FIGURES = {
    "spoke_speed": ("speed_km_h", "rolling speed (km/h)", "Figs 44–45"),
    "spoke_frequency": ("frequency_Hz", "forcing frequency (Hz)", "Fig. 46"),
    "spoke_amplitude": ("amplitude_mm_pp", "amplitude (mm p-p)", "Fig. 47"),
    "spoke_deflection": ("deflection_percent", "tyre deflection (% of radius)", "Fig. 48"),
}


def _spoke(table: str, number: str, caption: str) -> FigureSpec:
    x, xlabel, fig = SPOKE_FIGURES[table]
    return FigureSpec(number, caption, "spoke_curves", (table,), "regress", {"x": x, "xlabel": xlabel, "figure": fig})


CHAPTERS: tuple[Chapter, ...] = (
    Chapter("ch3-measurement", "Chapter 3 — measurement and calibration",
            "Apparent-mass method (§3.2–3.5): each run's K and C from the tyre force and axle acceleration "
            "at the excitation frequency; the force plate checks the load-beam calibration every day. "
            "Every run's K and C carry a standard uncertainty and a 95 % interval (results columns "
            "stiffness_ci95_low/high_N_per_m, damping_ci95_low/high_N_s_per_m, shown on each run's page): "
            "the run's own residual force near the excitation, combined (GUM) with the day's force-plate "
            "check, or with the §3.2.9 limits (±3 %, ±1°) on a day without one (docs/uncertainty.md).",
            (
                TableSpec("I", "Stiffness and damping by measurement method", "table_i", "methods",
                          "published_table_i",
                          gaps=(Gap("Our values are about 41 % above the printed ones because our virtual rig "
                                    "follows Table III (633 kN/m for stationary T1 at 1.38 bar where Table I prints "
                                    "450); the ratios between the methods are what we reproduce.",
                                    "findings", "Chapter 3"),)),
                TableSpec("", "Force-plate calibration per day", "calibration", "calibrate"),
                TableSpec("", "Calibration transfer function", "calibration_tf", "calibrate"),
            )),
    Chapter("ch4-stiffness", "Chapter 4 — tyre stiffness",
            "Stiffness K = K_c + ΔK_p·P fitted per tyre (§4.3); effects of amplitude, surface and the "
            "other factors; size regressions and the empirical formula (§4.5). Our coefficients carry their "
            "95 % confidence intervals (below each value), fitted by least squares weighted by the runs' "
            "uncertainties and the tyre's run-to-run scatter where these differ (docs/uncertainty.md). "
            "The virtual rig now repeats a tyre as §3.6 describes (run to run 2 % in K and 4 % in C, day to "
            "day 1.5 % and 3 %, standard deviations), so our r² are below 1 like the thesis'. Differences "
            "that remain: our scatter is one Gaussian model for every tyre, while the thesis' r² mix real "
            "scatter, tyre-to-tyre differences and experiments of different sizes; the virtual tyre follows "
            "straight lines in pressure exactly, so our r² only measure the scatter; and our coefficients "
            "come back from the generator within their intervals, not exactly (a small campaign has three "
            "pressures per line, so the intervals are wide).",
            (
                TableSpec("III", "Carcass stiffness K_c (kN/m) and pressure dependence ΔK_p (kN/m per bar)",
                          "table_iii", "regress", "published_table_iii"),
                FigureSpec("20", "Variation in vertical stiffness with inflation pressure (vertical stepped-sine runs)", "stiffness_vs_pressure",
                           ("results",), "analyse"),
                FigureSpec("21", "Variation of vertical stiffness with rolling speed, tyres T1–T5 at 1.38 bar (vertical runs)",
                           "stiffness_vs_speed", ("results",), "analyse"),
                TableSpec("IV", "Rate of change of stiffness with amplitude (kN/m per mm)", "table_iv", "regress",
                          "published_table_iv"),
                TableSpec("V", "Change of stiffness on other surfaces (% of concrete)", "table_v", "regress",
                          "published_table_v"),
                TableSpec("VI", "Summary of the factors affecting stiffness", "table_vi", "regress",
                          "published_table_vi"),
                TableSpec("", "Size regressions (Figs 30–31): ours and from the printed Table III",
                          "size_regressions", "regress",
                          columns=("fit", "source", "condition", "selection", "n", "finding"),
                          gaps=(Gap("No choice of up to three further excluded tyres reproduces all three printed "
                                    "numbers of the K_c-against-R fit, and the W·R fit's printed intercept 0.297 "
                                    "lies inside its 95 % interval.", "findings", "Chapters 4–5"),)),
                FigureSpec("30", "ΔK_p against section width × rim diameter", "pressure_dependence_vs_wr",
                           ("table_iii", "tyres", "size_regressions"), "regress"),
                FigureSpec("31", "Carcass stiffness against rim diameter", "carcass_stiffness_vs_rim",
                           ("table_iii", "tyres", "size_regressions"), "regress"),
                TableSpec("", "Accuracy of the empirical stiffness formula (§4.5)", "formula_accuracy", "regress"),
                FigureSpec("32", "Predicted against measured tyre stiffness", "predicted_vs_measured",
                           ("formula_predictions",), "regress"),
                TableSpec("", "The formula K = a + b R + c A + d W R P as a fitted model: the printed coefficients, "
                          "the refit on the printed Table III and the refit on our tyres (WLS, cluster-robust by "
                          "tyre; leave-one-tyre-out errors beside the printed formula's)", "formula_fit", "regress",
                          columns=("source", "n_tyres", "n_points", "r_squared", "relative_residual_sd_percent",
                                   "intercept", "intercept_se", "rim_diameter", "rim_diameter_se", "age", "age_se",
                                   "wrp", "wrp_se", "loto_mean_abs_error_percent", "printed_mean_abs_error_percent",
                                   "loto_coverage_fraction", "reason"),
                          note="The thesis built its coefficients from three separate regressions (Figs 26, 30, 31); "
                               "one joint fit gives each within two standard errors (docs/regressions.md). "
                               "estimate-stiffness quotes the printed formula with the refit's interval; "
                               "--build uses our fit."),
                FigureSpec("", "Width of the formula's 95 % prediction interval against W·R", "formula_interval_width",
                           ("formula_fit",), "regress", module="tyre_figures"),
            )),
    Chapter("ch5-damping", "Chapter 5 — tyre damping",
            "Damping C = C_c + ΔC_p·P per tyre and speed (§5.3) and the rotating-spoke model (§5.5).",
            (
                TableSpec("VII", "Carcass damping C_c (kN s/m) and pressure dependence (kN s/m per bar)",
                          "table_vii", "regress", "published_table_vii"),
                FigureSpec("34", "Variation in vertical damping with rolling speed at 1.38 bar, tyres T1–T5 (vertical runs)",
                           "damping_vs_speed", ("results",), "analyse"),
                TableSpec("VIII", "Rate of change of damping with amplitude (kN s/m per mm)", "table_viii",
                          "regress", "published_table_viii"),
                TableSpec("IX", "Change of damping on other surfaces (% of concrete)", "table_ix", "regress",
                          "published_table_ix"),
                TableSpec("X", "Summary of the factors affecting damping", "table_x", "regress",
                          "published_table_x"),
                TableSpec("", "Damping of an unmeasured tyre: C = c0 + c_A A + c_v v + c_P P fitted to the Table VII "
                          "lines and to ours (cluster-robust by tyre)", "damping_fit", "regress",
                          columns=("source", "n_tyres", "n_points", "r_squared", "residual_sd_kN_s_per_m", "intercept",
                                   "intercept_se", "age", "age_se", "speed", "speed_se", "pressure", "pressure_se",
                                   "speed_km_h_min", "speed_km_h_max", "sizes", "reason")),
                _spoke("spoke_speed", "44–45", "Apparent viscous damping of the spoke model against rolling speed"),
                _spoke("spoke_frequency", "46", "Modelled damping against forcing frequency"),
                _spoke("spoke_amplitude", "47", "Modelled damping against vibration amplitude"),
                _spoke("spoke_deflection", "48", "Modelled damping against tyre deflection"),
                TableSpec("", "Spoke-model coefficients fitted to our damping per tyre", "spoke_fit", "regress",
                          columns=("tyre_id", "size", "n_runs", "speeds_km_h", "c_coulomb_kN_per_rad",
                                   "c_viscous_kN_s_per_m_per_rad", "max_abs_error_percent", "status"),
                          gaps=(Gap("T3's damping rises with speed and F1's falls too fast for any non-negative "
                                    "pair of coefficients, and the viscous/Coulomb ratio is 0.8–1.2 s/m, not Fig. "
                                    "45's 4.", "findings", "Chapters 4–5"),)),
            )),
    Chapter("ch6-carriage", "Chapter 6 — single-wheel carriage",
            "Simulated ride of the single-wheel carriage (tyre T4) on the artificial rough track, "
            "with rolling and stationary tyre characteristics (§6.2–6.5).",
            (
                TableSpec("XI", "Carriage test conditions", "carriage_runs", "simulate", "published_table_xi",
                          ours_sql="SELECT DISTINCT load_condition, speed_km_h, load_kg FROM carriage_runs ORDER BY ALL",
                          keys=("load_condition", "speed_km_h"), values={"load_kg": "load_kg"}),
                TableSpec("XII", "Tyre characteristics used in the carriage simulations", "carriage_runs",
                          "simulate", "published_table_xii",
                          # Table XII quotes the stiffness before the 10 % slat-surface reduction (§6.3),
                          # and the stationary characteristics once for all speeds.
                          ours_sql="SELECT DISTINCT characteristics, load_condition, "
                                   "CASE WHEN characteristics = 'stationary' THEN NULL ELSE speed_km_h END AS speed_km_h, "
                                   "quoted_stiffness_kN_per_m AS stiffness_kN_per_m, damping_kN_s_per_m "
                                   "FROM carriage_runs WHERE characteristics IN ('rolling', 'stationary') ORDER BY ALL",
                          keys=("characteristics", "load_condition", "speed_km_h"),
                          values={"stiffness_kN_per_m": "stiffness_kN_per_m", "damping_kN_s_per_m": "damping_kN_s_per_m"},
                          thesis_rename={"nominal_speed_km_h": "speed_km_h"}),
                FigureSpec("51", "Power spectral estimates of the track profile", "profile_spectra",
                           ("profile_spectra",), "simulate"),
                TableSpec("XIII", "Accuracy of the carriage predictions, surveyed profile", "table_xiii", "simulate",
                          "published_table_xiii", gaps=(REFERENCE_VEHICLE_GAP,)),
                TableSpec("XIV", "Accuracy of the carriage predictions, recorded profile", "table_xiv", "simulate",
                          "published_table_xiv", gaps=(REFERENCE_VEHICLE_GAP,)),
                FigureSpec("54", "Measured and predicted rms acceleration", "carriage_rms",
                           ("carriage_comparisons",), "simulate"),
                FigureSpec("55", "Ratio errors of the rms acceleration", "carriage_ratio_errors",
                           ("carriage_comparisons",), "simulate"),
                FigureSpec("56", "Measured and predicted vibration spectra at 12.5 km/h", "acceleration_spectra",
                           ("carriage_spectra",), "simulate"),
            )),
    Chapter("ch7-tractor", "Chapter 7 — tractor ride",
            "Bounce–pitch simulation of the MF698T tractor on the ISO tracks (§7.2–7.5).",
            (
                TableSpec("XV", "Tractor parameters", "table_xv", "simulate", "published_table_xv", is_input=True,
                          note="An input table: simulate takes these values as printed (see simulate_inputs)."),
                TableSpec("XVI", "Tyre characteristics used in the tractor simulations", "tractor_runs", "simulate",
                          "published_table_xvi",
                          ours_sql="SELECT DISTINCT characteristics, load_condition, track, speed_km_h, "
                                   "rear_stiffness_kN_per_m, front_stiffness_kN_per_m, rear_damping_kN_s_per_m, "
                                   "front_damping_kN_s_per_m FROM tractor_runs WHERE NOT sweep ORDER BY ALL",
                          keys=("characteristics", "load_condition", "track", "speed_km_h"),
                          values={c: c for c in ("rear_stiffness_kN_per_m", "front_stiffness_kN_per_m",
                                                 "rear_damping_kN_s_per_m", "front_damping_kN_s_per_m")}),
                TableSpec("XVII", "Accuracy of the tractor predictions", "table_xvii", "simulate",
                          "published_table_xvii", gaps=(REFERENCE_VEHICLE_GAP,)),
                TableSpec("XVIII", "Effect of longitudinal tyre stiffness and damping", "table_xviii", "simulate",
                          "published_table_xviii"),
            )),
    Chapter("ch8-frequencies", "Chapter 8 — natural frequencies",
            "Bounce and pitch natural frequencies of five tractors from the formula and from measured "
            "stationary tyre stiffness (§8.2–8.3).",
            (
                TableSpec("XIX", "Tractor data", "table_xix", "simulate", "published_table_xix", is_input=True,
                          note="An input table: simulate takes these values as printed (see simulate_inputs)."),
                TableSpec("XX", "Predicted and measured natural frequencies", "table_xx", "simulate",
                          "published_table_xx",
                          gaps=(Gap("The thesis' rear formula stiffnesses are 1.4–2.4 kN/m above what its printed "
                                    "formula gives, and the Deutz and David Brown front stiffnesses follow neither of "
                                    "its rules at the printed pressures.", "findings", "Chapter 8"),
                                Gap("With the thesis' own printed stiffnesses, 16 of the 20 frequencies recompute "
                                    "within 0.01 Hz of Table XX: the differences come from the stiffnesses, not the "
                                    "model.", "simulation", "Table XX findings"))),
                TableSpec("", "Ratio errors of the natural frequencies", "table_xx_statistics", "simulate",
                          columns=("stiffness_source", "basis", "n", "mean", "sd", "p_within_10", "p_within_30",
                                   "thesis_printed_mean", "thesis_printed_sd", "thesis_printed_p_within_10"),
                          note="basis: thesis = frequencies recomputed from the thesis' printed stiffnesses; "
                               "ours = from our formula stiffnesses. thesis_printed_* are the §8.2 figures."),
                FigureSpec("69", "Predicted against measured natural frequencies", "natural_frequencies",
                           ("table_xx",), "simulate"),
            )),
    Chapter("ride", "Ride — whole-body vibration",
            "What the operator gets: ISO 2631-1 weighted seat vibration and the EU Directive 2002/44/EC daily "
            "exposure of every ride scenario (tyrelab ride; raw/scenarios/*.toml), and of the ch. 6–7 studies' "
            "simulated runs, against the action (EAV, 0.5 m/s²) and limit (ELV, 1.15 m/s²) values. After the "
            "overview, one section per scenario as tyrelab ride's page shows it: each variant's tyres and natural "
            "frequencies, per-axis a_w against speed, the hours to the action value over two swept keys, and the "
            "seat PSD and transmissibility per axis.",
            (
                FigureSpec("", "Seat a_w (highest axis: a_wz, 1.4·a_wx or 1.4·a_wy) against speed per scenario, at the "
                               "scenario's tyre pressures; lines: the levels that reach EAV and ELV in 8 h",
                           "ride_aw_speed", ("ride_results",), "simulate", module="ride_figures"),
                TableSpec("", "Ride scenarios: seat vibration per speed", "ride_results", "simulate",
                          ours_sql="SELECT scenario, variant, speed_km_h, front_pressure_bar, rear_pressure_bar, a_wz_m_s2, "
                                   "expected_a_wz_m_s2, a_wx_m_s2, a_wy_m_s2, a_v_m_s2, vdv_m_s1_75, crest_factor, "
                                   "lift_off_fraction_front, lift_off_fraction_rear, a8_m_s2, hours_to_eav, "
                                   "hours_to_elv, verdict FROM ride_results WHERE is_nominal "
                                   "QUALIFY row_number() OVER (PARTITION BY file, variant, speed_km_h "
                                   "ORDER BY method = 'spectral' DESC) = 1 ORDER BY scenario, variant, speed_km_h",
                          note="A(8) = max(1.4·a_wx, 1.4·a_wy, a_wz)·√(T/8 h) (the Directive's highest axis, not the "
                               "vector sum a_v; a_wy = 0 in the pitch-plane model); expected_a_wz is the "
                               "frequency-domain expectation of the linear model; of a scenario with a sweep, the "
                               "nominal variant's spectral rows (ride_results.method: time or spectral). "
                               "Pressure sweeps: tyrelab sql \"SELECT * FROM ride_results\"."),
                TableSpec("", "Ride scenarios", "ride_scenarios", "simulate",
                          columns=("scenario", "source", "mass_kg", "front_size", "front_pressure_bar", "rear_size",
                                   "rear_pressure_bar", "track", "enveloping", "speeds_km_h", "bounce_Hz", "pitch_Hz",
                                   "pressure_pairs")),
                FigureSpec("", "Vertical weighted r.m.s. of the ch. 6–7 simulated runs against speed (carriage: at "
                               "the tyre; tractor: at the CG; mean over load conditions)",
                           "study_aw_speed", ("iso2631",), "simulate", module="ride_figures"),
                TableSpec("", "Whole-body vibration of the ch. 6–7 simulated runs, summarised", "iso2631", "simulate",
                          ours_sql="SELECT study, COALESCE(track, '') AS track, characteristics, "
                                   "COALESCE(longitudinal, '') AS longitudinal, COUNT(*) AS runs, "
                                   "MIN(speed_km_h) AS speed_min_km_h, MAX(speed_km_h) AS speed_max_km_h, "
                                   "MIN(COALESCE(iso_weighted_rms_m_s2, iso_vertical_weighted_rms_m_s2)) AS a_wz_min_m_s2, "
                                   "MAX(COALESCE(iso_weighted_rms_m_s2, iso_vertical_weighted_rms_m_s2)) AS a_wz_max_m_s2, "
                                   "MAX(iso_a8_m_s2) AS a8_max_m_s2, AVG(CAST(iso_exceeds_action AS DOUBLE)) "
                                   "AS share_above_eav, AVG(CAST(iso_exceeds_limit AS DOUBLE)) AS share_above_elv "
                                   "FROM iso2631 GROUP BY ALL ORDER BY ALL",
                          note="Every row of the iso2631 table (tyrelab sql \"SELECT * FROM iso2631\") grouped by "
                               "study, track, tyre characteristics and longitudinal model."),
            )),
)
