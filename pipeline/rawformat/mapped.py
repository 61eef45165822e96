"""Recording formats other than raw format v1: ASAM MDF4 (``.mf4``) and NI TDMS (``.tdms``).

A lab's data acquisition names channels its own way and may record in other
units. A ``channel_map.json`` beside the manifest (schema
``schemas/channel_map.json``) maps each v1 channel name to a source channel
and an optional linear scaling, ``v1 = scale * source + offset``::

    {"channels": {"accel_left_m_s2": {"source": "AccL", "scale": 9.80665},
                  "load_beam_1_N": "LB1", ...},
     "tdms_group": "Rig"}

Without a map (or for channels it does not list) the source channel is
expected under its v1 name. ``time_s`` may be mapped to a source channel;
otherwise the time base is the recording's own (the MDF master channel, or
the TDMS waveform properties ``wf_start_offset``/``wf_increment``).

asammdf and npTDMS are optional (``pip install 'tyrelab[formats]'``); they are
imported only when such a file is read. Every problem raises
:class:`FormatError` with a one-line reason.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

__all__ = ["SUFFIXES", "CHANNEL_MAP", "RunFileError", "FormatError", "load_channel_map", "read_mapped"]

#: Suffix -> reader name.
SUFFIXES = {".mf4": "mdf", ".mdf": "mdf", ".tdms": "tdms"}
CHANNEL_MAP = "channel_map.json"


class RunFileError(ValueError):
    """A run file that cannot be used; the message is the one-line reason.

    The one error type of the raw format (v1 files and mapped recordings alike).
    """


#: Former name of :class:`RunFileError` for mapped recordings (kept for callers).
FormatError = RunFileError


def load_channel_map(path: Path) -> dict:
    """Read and check a channel map; return ``{"channels": {v1: {"source", "scale", "offset"}}, ...}``.

    Raises
    ------
    FormatError
        If the file is not valid JSON or does not follow ``schemas/channel_map.json``.
    """
    try:
        raw = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise FormatError(f"unreadable channel map {path} ({exc})") from None
    if not isinstance(raw, dict) or not isinstance(raw.get("channels", {}), dict):
        raise FormatError(f"channel map {path}: expected an object with a 'channels' object")
    channels = {}
    for name, spec in raw.get("channels", {}).items():
        if isinstance(spec, str):
            spec = {"source": spec}
        if not isinstance(spec, dict) or not isinstance(spec.get("source"), str):
            raise FormatError(f"channel map {path}: channel {name!r} needs a 'source' name")
        try:
            scale, offset = float(spec.get("scale", 1.0)), float(spec.get("offset", 0.0))
        except (TypeError, ValueError):
            raise FormatError(f"channel map {path}: channel {name!r} has a non-numeric scale/offset") from None
        channels[name] = {"source": spec["source"], "scale": scale, "offset": offset}
    return {**raw, "channels": channels}


def _mapping(channel_map: dict | None, wanted: list[str]) -> dict[str, dict]:
    given = (channel_map or {}).get("channels", {})
    return {c: given.get(c, {"source": c, "scale": 1.0, "offset": 0.0}) for c in wanted}


def _read_mdf(path: Path) -> tuple[dict[str, tuple[np.ndarray, np.ndarray]], str]:
    """Every channel of an MDF file as (timestamps, samples)."""
    try:
        from asammdf import MDF
    except ImportError:
        raise FormatError("reading .mf4 needs asammdf: pip install 'tyrelab[formats]'") from None
    try:
        with MDF(str(path)) as mdf:
            out = {}
            for name in mdf.channels_db:
                sig = mdf.get(name)
                out[name] = (np.asarray(sig.timestamps, dtype=float), np.asarray(sig.samples))
    except Exception as exc:  # noqa: BLE001 - asammdf raises many types for corrupt files
        raise FormatError(f"corrupt MDF file ({type(exc).__name__}: {str(exc).strip()[:100]})") from None
    return out, "MDF file"


def _read_tdms(path: Path, group: str | None) -> tuple[dict[str, tuple[np.ndarray | None, np.ndarray]], str]:
    """Every channel of one TDMS group as (time track or None, samples)."""
    try:
        from nptdms import TdmsFile
    except ImportError:
        raise FormatError("reading .tdms needs npTDMS: pip install 'tyrelab[formats]'") from None
    try:
        tdms = TdmsFile.read(str(path))
        groups = tdms.groups()
        chosen = [g for g in groups if group is None or g.name == group]
        if not chosen:
            raise FormatError(f"TDMS file has no group {group!r} (groups: {', '.join(g.name for g in groups)})")
        out = {}
        for ch in chosen[0].channels():
            try:
                t = np.asarray(ch.time_track(), dtype=float)
            except KeyError:
                t = None
            out[ch.name] = (t, np.asarray(ch[:]))
    except FormatError:
        raise
    except Exception as exc:  # noqa: BLE001 - npTDMS raises many types for corrupt files
        raise FormatError(f"corrupt TDMS file ({type(exc).__name__}: {str(exc).strip()[:100]})") from None
    return out, f"TDMS group {chosen[0].name!r}"


def read_mapped(path: Path, channels: list[str], optional: list[str], channel_map: dict | None = None) -> pd.DataFrame:
    """Read an ``.mf4`` or ``.tdms`` recording as a raw-format-v1 frame.

    Parameters
    ----------
    path : Path
        The recording.
    channels : list of str
        Required v1 channel names (besides ``time_s``).
    optional : list of str
        v1 channels taken if present (e.g. ``force_plate_N``).
    channel_map : dict, optional
        From :func:`load_channel_map`.

    Returns
    -------
    DataFrame
        ``time_s`` and the v1 channels, float64, scaled.

    Raises
    ------
    FormatError
        Unknown suffix, missing library, corrupt file, a missing source
        channel, or channels of unequal length.
    """
    kind = SUFFIXES.get(Path(path).suffix.lower())
    if kind is None:
        raise FormatError(f"unknown file type {Path(path).suffix!r}")
    if kind == "mdf":
        source, where = _read_mdf(path)
    else:
        source, where = _read_tdms(path, (channel_map or {}).get("tdms_group"))
    mapping = _mapping(channel_map, channels)
    mapping.update({c: m for c, m in _mapping(channel_map, optional).items() if m["source"] in source})
    missing = [f"{c} (source {m['source']!r})" for c, m in mapping.items() if m["source"] not in source]
    if missing:
        raise FormatError(f"{where} lacks channel(s) {', '.join(missing)}")
    if not mapping:  # only optional channels asked for (a vehicle recording), and none is there
        raise FormatError(f"{where} has none of the channels {', '.join(optional)} (map them in {CHANNEL_MAP})")
    cols = {c: source[m["source"]][1].astype(float) * m["scale"] + m["offset"] for c, m in mapping.items()}
    lengths = {len(v) for v in cols.values()}
    if len(lengths) != 1:
        raise FormatError(f"{where}: channels have unequal lengths {sorted(lengths)}")
    time_map = (channel_map or {}).get("channels", {}).get("time_s")
    if time_map:
        if time_map["source"] not in source:
            raise FormatError(f"{where} lacks the time channel {time_map['source']!r}")
        t = source[time_map["source"]][1].astype(float) * time_map["scale"] + time_map["offset"]
    else:
        t = source[next(iter(mapping.values()))["source"]][0]  # the first channel's own time base
        if t is None:
            raise FormatError(f"{where}: no time base (map time_s or set wf_increment)")
    if len(t) != lengths.pop():
        raise FormatError(f"{where}: time base and channels have unequal lengths")
    return pd.DataFrame({"time_s": t, **cols})
