"""Analytic recordings in raw format v1, independent of tyrelab's generator.

The axle moves sinusoidally, ``x = X sin(ωt)`` (upward positive); a
Kelvin-Voigt tyre pushes on it with ``f_t = W - (K x + C x')`` (W the static
load); the carriage supplies the rest through four load beams so that
``M a = f_t + Σ beams`` (beams upward positive). Everything is closed-form, so
the K and C that the analysis must recover are known exactly.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from tyrelab.rawformat import CHANNELS  # noqa: F401  (the raw format's one home; re-exported for the tests)


def spring_damper_recording(
    stiffness_N_per_m: float = 250e3,
    damping_N_s_per_m: float = 2000.0,
    frequency_Hz: float = 4.0,
    amplitude_mm_pp: float = 14.0,
    axle_mass_kg: float = 600.0,
    static_load_N: float = 18300.0,
    sample_rate_Hz: float = 256.0,
    duration_s: float = 50.0,
    force_noise_N: float = 0.0,
    accel_noise_m_s2: float = 0.0,
    seed: int = 0,
) -> pd.DataFrame:
    """A recording of a pure spring-damper tyre in raw format v1."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(round(duration_s * sample_rate_Hz))) / sample_rate_Hz
    w = 2 * np.pi * frequency_Hz
    amp = amplitude_mm_pp / 2e3
    x = amp * np.sin(w * t)
    v = amp * w * np.cos(w * t)
    a = -(w**2) * x
    f_t = static_load_N - (stiffness_N_per_m * x + damping_N_s_per_m * v)
    beams_total = axle_mass_kg * a - f_t
    split = np.array([0.26, 0.24, 0.27, 0.23])
    df = pd.DataFrame({"time_s": t})
    df["accel_left_m_s2"] = a + rng.normal(0, accel_noise_m_s2, t.size) if accel_noise_m_s2 else a
    df["accel_right_m_s2"] = a + rng.normal(0, accel_noise_m_s2, t.size) if accel_noise_m_s2 else a
    for i, s in enumerate(split, start=1):
        noise = rng.normal(0, force_noise_N / 2, t.size) if force_noise_N else 0.0
        df[f"load_beam_{i}_N"] = s * beams_total + noise
    return df


def manifest_row(run_id: str, file: str, **over) -> dict:
    """A valid manifest row (nominal thesis conditions), overridable."""
    row = dict(
        run_id=run_id, file=file, tyre_id="T1", speed_km_h=10.0, pressure_bar=1.38, load_kN=18.3,
        excitation_frequency_Hz=4.0, amplitude_mm_pp=14.0, torque_kNm=0.0, surface="concrete",
        axle_mass_kg=600.0, recorded_on="1990-06-01",
    )
    row.update(over)
    return row


def write_campaign(folder: Path, runs: list[tuple[dict, pd.DataFrame | bytes | None]], fmt: str = "parquet") -> Path:
    """Write a campaign folder: ``manifest.csv`` and the given run files.

    ``runs`` holds (manifest row, content) pairs; content is a DataFrame
    (written as ``fmt``), raw bytes (written as they are) or None (no file).
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for row, content in runs:
        path = folder / row["file"]
        if content is None:
            continue
        if isinstance(content, bytes):
            path.write_bytes(content)
        elif path.suffix == ".csv":
            content.to_csv(path, index=False)
        else:
            content.to_parquet(path, index=False)
    pd.DataFrame([r for r, _ in runs]).to_csv(folder / "manifest.csv", index=False)
    return folder


def edit_csv(path: Path, edit) -> list[dict]:
    """Rewrite the CSV file ``path`` after ``edit(rows)`` changed its rows (dicts by column) in place;
    return the rows written."""
    import csv

    with open(path, newline="") as fh:
        reader = csv.DictReader(fh)
        fields, rows = list(reader.fieldnames or []), list(reader)
    edit(rows)
    with open(path, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)
    return rows
