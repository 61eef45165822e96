"""The report's "Measured ride" page (issue 24): recordings, daily exposure, predictions checked."""

from __future__ import annotations

from .chapters import Chapter, FigureSpec, TableSpec

__all__ = ["MEASURED_RIDE"]

MEASURED_RIDE = Chapter(
    "measured-ride", "Measured ride — recordings, daily exposure and predictions checked",
    "Vehicle recordings listed in a campaign's rides.csv (seat and cab floor accelerometers), analysed as "
    "ISO 2631-1 prescribes (W_k on z, W_d on x/y; running r.m.s. τ = 1 s and MTVV; VDV; crest factor) with the "
    "ISO 2631-5:2018 dose D_z, and combined per vehicle and day into the EU Directive 2002/44/EC daily exposure "
    "A(8) (highest axis, k = 1.4 on x and y), the daily VDV and HSE points. A recording whose row names a "
    "scenario is compared with that scenario's prediction at its speed on its track, by the same analysis "
    "(thesis §6.4: a_w ratio, peak frequency and width, envelope similarity R on known tracks).",
    (
        TableSpec("", "Daily exposure per vehicle and day (Directive 2002/44/EC; A(8): EAV 0.5, ELV 1.15 m/s²; VDV: EAV 9.1, ELV 21 m/s^1.75)",
                  "exposure_days", "rides",
                  columns=("vehicle", "recorded_on", "tasks", "hours_per_day", "a8_m_s2", "a8_axis",
                           "vdv_daily_m_s1_75", "vdv_verdict", "hours_to_eav", "hours_to_elv", "exposure_points",
                           "verdict", "dzd_m_s2")),
        TableSpec("", "Recordings: seat values per recording (a_w without k)", "recordings", "rides",
                  # at least one seat axis' a_w (a column per axis recorded anywhere in the campaign; the
                  # null a_w_0_m_s2 keeps the pattern matching when none is)
                  ours_sql="SELECT * EXCLUDE (a_w_0_m_s2) FROM (SELECT *, NULL::DOUBLE AS a_w_0_m_s2 FROM recordings) "
                           "WHERE list_count([*COLUMNS('^a_w_[0xyz]_m_s2$')]) > 0 ORDER BY ride_id",
                  note="Only recordings with a seat channel: those without (the chapter 6-7 studies' axle and "
                       "carriage recordings) have no seat values to show; every recording is in the warehouse "
                       "table recordings.",
                  columns=("ride_id", "vehicle", "speed_km_h", "track", "task", "hours_per_day", "duration_s",
                           "a_w_x_m_s2", "a_w_y_m_s2", "a_w_z_m_s2", "a_v_m_s2", "dz_m_s2", "seat_factor_z")),
        TableSpec("", "Measured against predicted, per recording and axis (ratio = measured / predicted)",
                  "ride_validation", "rides",
                  columns=("ride_id", "speed_km_h", "track", "axis", "measured_a_w_m_s2", "predicted_a_w_m_s2",
                           "ratio_a_w", "measured_peak_frequency_Hz", "predicted_peak_frequency_Hz",
                           "measured_half_power_width_Hz", "predicted_half_power_width_Hz", "envelope_similarity")),
        TableSpec("", "Ratio errors predicted / measured over the recordings (thesis §6.4.1 statistics)",
                  "ride_validation_statistics", "rides"),
        FigureSpec("", "Seat vertical PSD per recording (0.1 Hz): measured, and its scenario's prediction",
                   "psd_overlay", ("recording_spectra",), "rides", module="measured_figures"),
    ),
)
