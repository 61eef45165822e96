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

__all__ = ["Context", "StageResult", "Progress", "QUARANTINE_COLUMNS", "write_quarantine", "quarantine_table"]

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
    #: The stage running (set by :func:`tyrelab.stages.run_stage`): a table or build path it reads or writes must be one it
    #: declares (:data:`tyrelab.stages.dag.STAGES`), so the declarations cannot drift from the code.
    stage: str | None = field(default=None, repr=False)

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
        """Path of table ``name``: ``build/parquet/<name>.parquet`` (``stages/analysed``: a table one
        stage passes to another, below ``parquet/stages/``, not published in the warehouse).

        Raises
        ------
        RuntimeError
            If the running stage (:attr:`stage`) declares the table neither among its reads nor its
            writes (:func:`tyrelab.stages.dag.may_read`)."""
        from .dag import table

        return self.path(table(name), f"table {name!r}")

    def path(self, rel: str, what: str | None = None) -> Path:
        """Build path ``rel`` (``warehouse.duckdb``, ``parquet/runs/``), which the running stage
        (:attr:`stage`) must declare among its reads or writes.

        Raises
        ------
        RuntimeError
            If it does not (:func:`tyrelab.stages.dag.may_read`): a read the graph does not know would
            be a dependency no cache key and no stage order holds.
        """
        if self.stage is not None:
            from .dag import may_read

            if not may_read(self.stage, rel):
                raise RuntimeError(f"stage {self.stage} reads {what or rel}, which it does not declare: add "
                                   f"{rel!r} to its reads in tyrelab.stages.dag.STAGES")
        return self.build / rel

    def raw_relative(self, path) -> str:
        """``path`` as a table holds it: relative to the raw folder (``.`` for the raw folder itself,
        ``campaign_a/manifest.csv``), never this machine's absolute path (a moved raw folder keeps
        its tables); a path outside the raw folder by its name alone.

        Examples
        --------
        >>> ctx = Context(raw=Path("/data/raw"), build=Path("/data/build"))
        >>> ctx.raw_relative(Path("/data/raw/c1/runs/r1.csv")), ctx.raw_relative(Path("/data/raw"))
        ('c1/runs/r1.csv', '.')
        """
        try:
            return Path(path).resolve().relative_to(self.raw).as_posix()
        except ValueError:
            return Path(path).name

    def build_relative(self, path) -> str:
        """``path`` (inside the build) as a table holds it: relative to the build folder
        (``manifest.run_path``: ``parquet/runs/tyre_id=T1/r1.parquet``), so that a moved build works.

        Examples
        --------
        >>> Context(build=Path("/b")).build_relative(Path("/b/parquet/runs/r1.parquet"))
        'parquet/runs/r1.parquet'
        """
        try:
            return Path(path).resolve().relative_to(self.build).as_posix()
        except ValueError:
            return str(path)

    def build_file(self, path) -> Path:
        """A build path a table holds (:meth:`build_relative`) as a path to open: below this build;
        an absolute one (a table written before paths were relative) as it is if it exists, else by
        its part below ``parquet/`` in this build (the build was moved)."""
        p = Path(str(path))
        if not p.is_absolute():
            return self.build / p
        if p.exists() or "parquet" not in p.parts:
            return p
        parts = p.parts
        return self.build.joinpath(*parts[len(parts) - 1 - parts[::-1].index("parquet"):])

    def raw_file(self, campaign, name=None) -> Path:
        """A campaign folder (and a file of it) a table holds (:meth:`raw_relative`) as a path below
        the raw folder; an absolute one (an older table) as it is."""
        p = Path(str(campaign))
        p = p if p.is_absolute() else self.raw / p
        return p if name is None else p / str(name)

    def has_table(self, name: str) -> bool:
        """Whether table ``name`` exists (``quarantine``: whether any stage wrote its part)."""
        if name == "quarantine":
            return any(self.table(part).exists() for part in _quarantine_parts())
        return self.table(name).exists()

    def read_table(self, name: str) -> pd.DataFrame:
        """Read table ``name`` into a DataFrame (one the running stage declares: :meth:`table`).

        ``quarantine`` is the union of the stages' parts (:func:`quarantine_table`), as the
        warehouse stage publishes it: right after any stage, not only after a whole run."""
        import pandas as pd

        if name == "quarantine":
            return quarantine_table(self)
        return pd.read_parquet(self.table(name))

    def write_table(self, name: str, df: pd.DataFrame) -> Path:
        """Write table ``name`` atomically.

        Raises
        ------
        RuntimeError
            If the running stage (:attr:`stage`) does not declare the table among its outputs.
        """
        if self.stage is not None:
            from .dag import table, writer

            if writer(table(name)) != self.stage:
                raise RuntimeError(f"stage {self.stage} writes table {name!r}, which it does not declare: add "
                                   f"{table(name)!r} to its writes in tyrelab.stages.dag.STAGES")
        return io.write_parquet_atomic(df, self.parquet / f"{name}.parquet")


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


_TEXT = {"run_id": "string", "campaign": "string", "file": "string"}


def _quarantine_parts() -> dict[str, str]:
    """Stage -> table name of its quarantine rows (:data:`tyrelab.stages.dag.QUARANTINE_PARTS`)."""
    from .dag import QUARANTINE_PARTS

    return {f"stages/quarantine_{s}": s for s in QUARANTINE_PARTS}


def write_quarantine(ctx: Context, stage: str, entries: list[dict]) -> None:
    """Write the quarantine rows of ``stage`` (its own part, ``parquet/stages/quarantine_<stage>.parquet``:
    each stage writes only its rows; the warehouse stage publishes the union, :func:`quarantine_table`)."""
    import pandas as pd

    ctx.write_table(f"stages/quarantine_{stage}", pd.DataFrame(entries, columns=QUARANTINE_COLUMNS).astype(_TEXT))


def quarantine_table(ctx: Context) -> pd.DataFrame:
    """The ``quarantine`` table: the rows of every stage's part, in pipeline order.

    A part that is missing or unreadable (a damaged build) contributes no rows; its stage
    rewrites it on the next run."""
    import pandas as pd

    parts = []
    for name in _quarantine_parts():
        try:
            parts.append(pd.read_parquet(ctx.table(name)))
        except (OSError, ValueError):
            continue
    parts = [df for df in parts if not df.empty]
    both = pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=QUARANTINE_COLUMNS)
    return both.reindex(columns=QUARANTINE_COLUMNS).astype(_TEXT)
