"""Progress of long steps: a bar on a terminal (``rich``), else a log line now and then.

The ``tyrelab`` command turns bars on (:func:`configure`) unless ``-q`` is given; a bar is
drawn only while standard error is a terminal, so a pipe, a log file, CI and library use
(``run_pipeline`` called from Python) get the plain log lines of :class:`Progress` and no
control characters. ``rich`` is imported only when a bar is drawn.

Log records written while a bar is shown go through :class:`StderrHandler`, which writes to
whatever ``sys.stderr`` is at the time: ``rich`` then prints them above the bar instead of
through it.

Examples
--------
>>> import logging
>>> p = Progress("analyse", 3, logger=logging.getLogger("doctest"))
>>> p.step(); p.step(2); p.done, p.bar is None
(3, True)
"""

from __future__ import annotations

import logging
import sys
import time

__all__ = ["configure", "bars_enabled", "Progress", "StderrHandler", "close_all", "say_library_warnings_once",
           "in_our_words"]

log = logging.getLogger("tyrelab")

_bars_wanted = False
_open: list["Progress"] = []


def configure(bars: bool) -> None:
    """Draw progress bars (on a terminal) from now on, or not (the default)."""
    global _bars_wanted
    _bars_wanted = bool(bars)


def bars_enabled() -> bool:
    """Whether a :class:`Progress` started now draws a bar: turned on and standard error is a terminal."""
    try:
        return _bars_wanted and sys.stderr.isatty()
    except (AttributeError, ValueError):  # a closed or replaced stream
        return False


class StderrHandler(logging.StreamHandler):
    """A logging handler that writes to the current ``sys.stderr`` (a bar's redirection included)."""

    def __init__(self):
        super().__init__(sys.stderr)

    @property
    def stream(self):
        return sys.stderr

    @stream.setter
    def stream(self, value) -> None:  # logging.StreamHandler.__init__ sets it; the current one is used
        pass


class Progress:
    """``done/total`` of a long step: a bar on a terminal (:func:`bars_enabled`), else a log line at
    most every ``every_s`` seconds and at the end.

    Parameters
    ----------
    label : str
        What is being done, e.g. ``"analyse"``.
    total : int
        Number of items.
    unit : str
        What the items are (``"runs"``, ``"figures"``).
    every_s : float
        Seconds between log lines without a bar.
    logger : logging.Logger, optional
        Where the lines go (default the ``tyrelab`` logger).
    """

    def __init__(self, label: str, total: int, every_s: float = 2.0, logger: logging.Logger | None = None,
                 unit: str = "runs"):
        if int(total) != total or total < 0:
            raise ValueError(f"total must be a non-negative whole number, got {total!r}")
        self.label, self.total, self.every_s, self.unit = label, int(total), every_s, unit
        self.log = logger or log
        self.t0 = self._last = time.perf_counter()
        self.done = 0
        self.bar = None
        if self.total and bars_enabled():
            self._start_bar()

    def _start_bar(self) -> None:
        from rich.console import Console
        from rich.progress import BarColumn, MofNCompleteColumn, Progress as Bar, TextColumn, TimeRemainingColumn

        self.bar = Bar(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                       TextColumn(self.unit), TimeRemainingColumn(), console=Console(stderr=True), transient=True)
        self._task = self.bar.add_task(self.label, total=self.total)
        self.bar.start()
        _open.append(self)

    def step(self, n: int = 1) -> None:
        """Count ``n`` items done; draw, or log if enough time has passed, and log at the end."""
        self.done += n
        now = time.perf_counter()
        if self.bar is not None:
            self.bar.update(self._task, completed=self.done)
        end = self.done >= self.total
        if end:
            self.close()
        if end or (self.bar is None and now - self._last >= self.every_s):
            rate = self.done / max(now - self.t0, 1e-9)
            self.log.info("%s: %d/%d %s (%.0f %s/s)", self.label, self.done, self.total, self.unit, rate, self.unit)
            self._last = now

    def iterate(self, items):
        """Yield each of ``items`` and count it done when the loop body has finished with it (a
        ``continue`` included), then close: ``for row in progress.iterate(rows): ...``.

        Examples
        --------
        >>> import logging
        >>> p = Progress("rides", 2, logger=logging.getLogger("doctest"))
        >>> [p.done for _ in p.iterate("ab")], p.done
        ([0, 1], 2)
        """
        try:
            for item in items:
                yield item
                self.step()
        finally:
            self.close()

    def close(self) -> None:
        """Remove the bar (if any) from the terminal; safe to call twice."""
        bar, self.bar = self.bar, None
        if bar is not None:
            bar.stop()
            if self in _open:
                _open.remove(self)

    @property
    def elapsed(self) -> float:
        """Seconds since the start."""
        return time.perf_counter() - self.t0


def close_all() -> None:
    """Remove every bar still shown (a step that ended early, by an error or Ctrl-C)."""
    for p in list(_open):
        p.close()


#: A library warning's text (its start) -> what it means for our numbers, said once per command.
OUR_WORDS = {
    "All-NaN slice encountered": "a statistic over values that are all missing (NaN) is left NaN",
    "Degrees of freedom <= 0": "a spread of fewer than two values is left NaN",
    "Mean of empty slice": "a mean of no values is left NaN",
    "invalid value encountered": "a computation met a value it cannot use (NaN or infinity); its result is NaN",
    "divide by zero encountered": "a computation divided by zero; its result is infinite or NaN",
    "overflow encountered": "a computation exceeded the range of floating point numbers; its result is infinite",
    "underflow encountered": "a computation fell below the smallest floating point number; its result is 0",
}


def in_our_words(message: str) -> str:
    """What a numpy/scipy/pandas warning means, in one line of ours (the library's words in brackets).

    Examples
    --------
    >>> in_our_words("All-NaN slice encountered")
    'a statistic over values that are all missing (NaN) is left NaN (All-NaN slice encountered)'
    """
    text = " ".join(str(message).split())
    ours = next((v for k, v in OUR_WORDS.items() if text.startswith(k) or k in text), None)
    return f"{ours} ({text})" if ours else f"a library warned: {text}"


def say_library_warnings_once(logger: logging.Logger | None = None):
    """From now on, say each different warning (``RuntimeWarning: All-NaN slice encountered`` and the
    like) once, as one log line of ours at WARNING level (:func:`in_our_words`), instead of the
    library's two lines with a source line on stderr. Returns the previous ``warnings.showwarning``
    (to put back).
    """
    import warnings

    logger = logger or log
    said: set = set()
    previous = warnings.showwarning

    def show(message, category, filename, lineno, file=None, line=None):
        key = (getattr(category, "__name__", str(category)), str(message))
        if key not in said:
            said.add(key)
            logger.warning("note: %s", in_our_words(str(message)))

    warnings.showwarning = show
    return previous
