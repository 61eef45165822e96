"""The report's "Vehicle FRFs" page (issue 43, thesis ch. 2): the verdict, each stand or track
recording's transfer functions measured and predicted, and the modes measured against predicted."""

from __future__ import annotations

from .chapters import Chapter, FigureSpec, TableSpec

__all__ = ["VEHICLE_FRF", "BEST_MODES_SQL", "VERDICT_SQL"]

#: Per recording and predicted mode the measured mode with the narrowest frequency interval (a mode
#: seen in several outputs is judged where it is best determined; one the recording determines first).
BEST_MODES_SQL = (
    "SELECT * EXCLUDE (rank) FROM (SELECT *, row_number() OVER (PARTITION BY ride_id, predicted_mode "
    "ORDER BY NOT coalesce(measured_determined, true), "
    "measured_frequency_ci95_high_Hz - measured_frequency_ci95_low_Hz, output, mode) AS rank "
    "FROM vehicle_frf_validation WHERE mode IS NOT NULL AND predicted_mode IS NOT NULL) WHERE rank = 1")

#: Per predicted mode: in how many recordings its frequency and damping ratio lie in the measured
#: 95 % intervals (of the best-determined measurement, :data:`BEST_MODES_SQL`), and the verdict; a mode
#: no recording determines (``measured_determined`` false: vehicle_modes' ``determined``) says so.
VERDICT_SQL = (
    "SELECT predicted_mode AS mode, count(*) AS recordings, "
    "sum(frequency_in_interval::INT) AS frequency_within, sum(damping_in_interval::INT) AS damping_within, "
    "sum((NOT coalesce(measured_determined, true))::INT) AS undetermined, "
    "CASE WHEN bool_and(NOT coalesce(measured_determined, true)) "
    "THEN 'not determined by the recordings (see vehicle_modes.undetermined_reason)' "
    "WHEN bool_and(frequency_in_interval AND damping_in_interval) "
    "THEN 'within the measured intervals in every recording' "
    "WHEN bool_or(frequency_in_interval AND damping_in_interval) "
    "THEN 'within in ' || sum((frequency_in_interval AND damping_in_interval)::INT) || ' of ' || count(*) "
    "|| ' recordings' "
    "WHEN bool_or(frequency_in_interval) THEN 'frequency within, damping ratio outside the measured interval' "
    "ELSE 'outside the measured intervals' END AS verdict, "
    "round(median(frequency_ratio), 3) AS median_frequency_ratio, "
    "round(median(damping_ratio_ratio), 3) AS median_damping_ratio_ratio "
    f"FROM ({BEST_MODES_SQL}) GROUP BY predicted_mode "
    "ORDER BY bool_and(frequency_in_interval AND damping_in_interval) DESC, count(*) DESC, predicted_mode")

VEHICLE_FRF = Chapter(
    "vehicle-frf", "Vehicle FRFs — the tractor's transfer functions and modes, measured and predicted",
    "Thesis ch. 2 measured the tractor itself: the transfer functions from the ground under each wheel to the "
    "cab floor on a four-post stand (each wheel excited, the others still or correlated as on a track; wheels "
    "stationary or rolling at 6 and 11 km/h) and on a track with one wheel on a rough profile. Each recording "
    "with wheel inputs gives its multiple-input FRFs (H1 = S_yx S_xx⁻¹, coherences, random error; bins at a "
    "wheel's rotation and lug passing masked, inputs that cannot be separated flagged and never fitted) and "
    "its modes fitted with 95 % intervals; a recording whose row names a scenario is compared with that "
    "scenario's model at its speed (stationary tyres at 0 km/h, rolling tyres with their series damper "
    "c₂ = a/v above: issue 42), its damped modes from the complex roots. The verdict first: which of the "
    "model's modes lie within the measured intervals.",
    (
        TableSpec("", "Verdict: the model's modes against the measured 95 % intervals (per mode, over the "
                      "recordings naming a scenario)", "vehicle_frf_validation", "rides", ours_sql=VERDICT_SQL,
                  note="Per recording a mode is judged where it is best determined (the output with the narrowest "
                       "frequency interval); frequency_within and damping_within count the recordings whose "
                       "prediction lies in that interval. Heavily damped modes (the rolling tyre's lateral-roll "
                       "and yaw, 40-80 % of critical) have wide intervals but overlap: their fitted frequency "
                       "scatters by several per cent between recordings."),
        FigureSpec("", "FRF magnitude per stand or track recording and output (measured with its 95 % band, "
                       "predicted dashed) and the output's multiple coherence (shaded: bins not used)",
                   "frf_panels", ("vehicle_frf", "recordings"), "rides", module="frf_figures"),
        TableSpec("", "Modes measured against predicted, per recording (each predicted mode at its "
                      "best-determined output)", "vehicle_frf_validation", "rides",
                  ours_sql=BEST_MODES_SQL + " ORDER BY ride_id, measured_frequency_Hz",
                  note="Every output's fitted modes are in the warehouse tables vehicle_modes and "
                       "vehicle_frf_validation; the FRFs, bin by bin, in vehicle_frf.",
                  columns=("ride_id", "speed_km_h", "predicted_mode", "output", "measured_frequency_Hz",
                           "measured_frequency_ci95_low_Hz", "measured_frequency_ci95_high_Hz",
                           "predicted_frequency_Hz", "frequency_in_interval", "measured_damping_ratio",
                           "measured_damping_ci95_low", "measured_damping_ci95_high", "predicted_damping_ratio",
                           "damping_in_interval", "measured_determined", "frf_magnitude_error")),
    ),
)
