"""What every stage shares: the run context, the result record and progress."""

from __future__ import annotations

import logging
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from .. import io
from ..progress import Progress  # noqa: F401 - the stages' progress (a bar on a terminal, else log lines)

if TYPE_CHECKING:  # imported where used: a no-op run never needs pandas
    import pandas as pd

__all__ = ["Context", "StageResult", "Progress", "QUARANTINE_COLUMNS", "write_quarantine"]

log = logging.getLogger("tyrelab")


@dataclass
class Context:
    """Where a pipeline run reads and writes, and how it executes.

    Attributes
    ----------
    raw : Path
        Raw data folder (campaigns, ``published/``, ``tyres.csv``).
    build : Path
        Output folder (``parquet/``, ``warehouse.duckdb``, ``reports/``).
    force : bool
        Recompute everything, ignoring recorded hashes.
    jobs : int
        Worker processes for ``executor="local"``.
    executor : str
        ``"local"`` (process pool) or ``"dask"``.
    scheduler : str or None
        Dask scheduler address for ``executor="dask"``.
    calibration_correct : bool
        Correct each run by its day's force-plate transfer function (thesis
        §3.6; the calibrate stage).
    """

    raw: Path = Path("raw")
    build: Path = Path("build")
    force: bool = False
    jobs: int = field(default_factory=lambda: os.cpu_count() or 1)
    executor: str = "local"
    scheduler: str | None = None
    calibration_correct: bool = False
    log: logging.Logger = field(default=log, repr=False)

    def __post_init__(self) -> None:
        self.raw = Path(self.raw).resolve()
        self.build = Path(self.build).resolve()

    @property
    def parquet(self) -> Path:
        """Folder of the Parquet tables, ``build/parquet``."""
        return self.build / "parquet"

    @property
    def state(self) -> Path:
        """Folder of per-stage bookkeeping (hashes of what was consumed)."""
        return self.build / "state"

    def table(self, name: str) -> Path:
        """Path of table ``name``: ``build/parquet/<name>.parquet``."""
        return self.parquet / f"{name}.parquet"

    def has_table(self, name: str) -> bool:
        """Whether table ``name`` exists."""
        return self.table(name).exists()

    def read_table(self, name: str) -> pd.DataFrame:
        """Read table ``name`` into a DataFrame."""
        import pandas as pd

        return pd.read_parquet(self.table(name))

    def write_table(self, name: str, df: pd.DataFrame) -> Path:
        """Write table ``name`` atomically."""
        return io.write_parquet_atomic(df, self.table(name))


@dataclass
class StageResult:
    """What a stage did, for the one-line summary and the exit code."""

    name: str
    n_in: int = 0
    n_ok: int = 0
    n_quarantined: int = 0
    #: Input files refused as a whole (a manifest or tyre catalogue that cannot be read or lacks
    #: columns): no run of theirs went through, so the exit code is non-zero.
    n_rejected: int = 0
    seconds: float = 0.0
    skipped: bool = False
    message: str = ""

    def summary(self) -> str:
        """One line: ``analyse: 120 in, 118 ok, 2 quarantined, 1.3 s``."""
        if self.skipped:
            return f"{self.name}: up to date: {self.message or 'inputs unchanged'}"
        text = (
            f"{self.name}: {self.n_in} in, {self.n_ok} ok, "
            f"{self.n_quarantined} quarantined, {self.seconds:.1f} s"
        )
        if self.n_rejected:
            text += f", {self.n_rejected} file(s) rejected"
        return f"{text}; {self.message}" if self.message else text


QUARANTINE_COLUMNS = ["campaign", "run_id", "file", "stage", "reason"]


def write_quarantine(ctx: Context, stage: str, entries: list[dict]) -> None:
    """Replace the quarantine rows of ``stage`` with ``entries`` (other stages' rows are kept)."""
    import pandas as pd

    old = ctx.read_table("quarantine") if ctx.has_table("quarantine") else pd.DataFrame(columns=QUARANTINE_COLUMNS)
    old = old[old["stage"] != stage]
    new = pd.DataFrame(entries, columns=QUARANTINE_COLUMNS)
    both = pd.concat([df for df in (old, new) if not df.empty], ignore_index=True) if len(old) or len(new) else new
    ctx.write_table("quarantine", both.astype({"run_id": "string", "campaign": "string", "file": "string"}))
