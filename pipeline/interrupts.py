"""Ctrl-C and SIGTERM that no library can swallow.

A command-line verb ends on Ctrl-C (SIGINT) or SIGTERM with one line and exit 130
(:func:`tyrelab.cli.main`). Python turns the signal into a ``KeyboardInterrupt`` in the main
thread, but a library that checks for signals while it works may catch that exception and carry
on: DuckDB's Python module calls ``PyErr_CheckSignals`` during a statement run on the main thread,
clears the ``KeyboardInterrupt`` and either raises its own ``RuntimeError: Query interrupted``
(a ``SET`` while connecting) or, when the statement finished anyway, nothing at all — and the
command then ran on (``tyrelab sql`` over a statement of minutes, once in about a hundred Ctrl-Cs
that landed while the connection was being set up).

The handler installed here records the request before raising, so that the code that waits for
long work (:func:`check`, e.g. the loop that waits for a DuckDB statement in a helper thread) and
the command's end (:func:`requested`) still see it when the exception itself was lost.

Nothing is installed on import: a library user's own handlers are left alone; only
:func:`install` (called by the command-line entry point) changes them.
"""

from __future__ import annotations

import signal
import threading

__all__ = ["install", "restore", "requested", "check", "handler"]

_requested = threading.Event()


def handler(signum, frame) -> None:  # noqa: ARG001 - the signal module's handler signature
    """The SIGINT/SIGTERM handler: record the request, then raise ``KeyboardInterrupt``.

    Parameters
    ----------
    signum : int
        The signal's number (unused: both signals end a command alike).
    frame : frame or None
        The interrupted frame (unused).

    Raises
    ------
    KeyboardInterrupt
        Always.

    Examples
    --------
    >>> try:
    ...     handler(signal.SIGINT, None)
    ... except KeyboardInterrupt:
    ...     print("interrupted", requested())
    interrupted True
    >>> _requested.clear()
    """
    _requested.set()
    raise KeyboardInterrupt


def requested() -> bool:
    """Whether Ctrl-C or SIGTERM arrived since :func:`install` (even if a library swallowed its
    ``KeyboardInterrupt``).

    Examples
    --------
    >>> requested()
    False
    """
    return _requested.is_set()


def check() -> None:
    """Raise ``KeyboardInterrupt`` if Ctrl-C or SIGTERM arrived (see :func:`requested`); else return.

    Raises
    ------
    KeyboardInterrupt
        When an interrupt was requested.

    Examples
    --------
    >>> check()  # nothing requested: returns
    """
    if _requested.is_set():
        raise KeyboardInterrupt


def install() -> dict | None:
    """Install :func:`handler` for SIGINT and SIGTERM; returns the previous handlers for :func:`restore`
    (None, and nothing changed, outside the main thread, where Python cannot set handlers).

    A signal this process was started ignoring keeps being ignored (a shell starts a background
    job, ``tyrelab run &`` in a script, with SIGINT ignored: a Ctrl-C meant for the foreground is not
    its), as Python itself leaves an ignored SIGINT alone.

    Returns
    -------
    dict or None
        The previous handler of each signal.

    Examples
    --------
    >>> previous = install()
    >>> signal.getsignal(signal.SIGINT) is handler
    True
    >>> restore(previous)
    >>> signal.getsignal(signal.SIGINT) is handler
    False
    """
    if threading.current_thread() is not threading.main_thread():
        return None
    _requested.clear()
    return {sig: signal.signal(sig, handler) for sig in (signal.SIGINT, signal.SIGTERM)
            if signal.getsignal(sig) is not signal.SIG_IGN}


def restore(previous: dict | None) -> None:
    """Put back the handlers :func:`install` replaced (a no-op for None).

    Parameters
    ----------
    previous : dict or None
        What :func:`install` returned.

    Examples
    --------
    >>> restore(None)
    """
    if not previous:
        return
    for sig, old in previous.items():
        signal.signal(sig, old if old is not None else signal.SIG_DFL)
