"""The Measured ride page's recordings table lists only recordings with a seat value (issue 38)."""

import duckdb

from tyrelab.report.measured_page import MEASURED_RIDE


def _sql():
    return next(t.ours_sql for t in MEASURED_RIDE.items if getattr(t, "view", "") == "recordings")


def test_recordings_without_seat_values_are_left_out():
    con = duckdb.connect()
    con.execute("CREATE TABLE recordings AS SELECT * FROM (VALUES ('seat', NULL, 0.5, 0.5), ('axle', NULL, NULL, 0.0), "
                "('fore-aft', 0.2, NULL, 0.28)) t(ride_id, a_w_x_m_s2, a_w_z_m_s2, a_v_m_s2)")
    assert [r[0] for r in con.execute(_sql()).fetchall()] == ["fore-aft", "seat"]
    assert "a_w_0_m_s2" not in [d[0] for d in con.execute(_sql()).description]


def test_a_campaign_without_any_seat_channel_lists_none():
    con = duckdb.connect()
    con.execute("CREATE TABLE recordings AS SELECT 'axle' AS ride_id, 0.0 AS a_v_m_s2")
    assert con.execute(_sql()).fetchall() == []
