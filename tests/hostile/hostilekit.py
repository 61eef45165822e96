"""A tiny campaign from the virtual rig with one good and one failed calibration day (issue 11 tests)."""

from pathlib import Path

from tyrelab import io
from tyrelab.generate import write_run
from tyrelab.rig.campaigns import MANIFEST_COLUMNS, campaign_plan, simulate_run


def calibrated_campaign(folder: Path, per_day: int = 3, seed: int = 1991) -> Path:
    """Two days of the small plan: a passing and a failing force-plate check, ``per_day`` runs on each."""
    plan = campaign_plan("small")
    cal = plan[plan["kind"] == "calibration"]
    stepped_days = set(plan.loc[plan["method"] == "stepped_sine", "recorded_on"]) - set(
        plan.loc[plan["method"] != "stepped_sine", "recorded_on"])  # not the day of the other methods (issue 34)
    good = cal[(cal["plan_beam_gain_error"] == 0) & cal["recorded_on"].isin(stepped_days)].iloc[-1]
    bad = cal[cal["plan_beam_gain_error"] > 0].iloc[0]
    meas = plan[plan["kind"] == "measurement"]
    rows = [good, bad]
    for day in (good["recorded_on"], bad["recorded_on"]):
        rows.extend(r for _, r in meas[meas["recorded_on"] == day].head(per_day).iterrows())
    rows = [r.to_dict() for r in rows]
    for r in rows:
        run, info = simulate_run(r, seed)
        write_run(run, Path(folder) / r["file"])
        if r["kind"] == "calibration":  # as tyrelab generate: the p-p equivalent of the axle rms
            r["amplitude_mm_pp"] = round(info["amplitude_mm_pp"], 2)
    import pandas as pd

    manifest = pd.DataFrame(rows)[MANIFEST_COLUMNS]
    io.write_text_atomic(manifest.to_csv(index=False, float_format="%.6g", lineterminator="\n"),
                         Path(folder) / "manifest.csv")
    return Path(folder)
