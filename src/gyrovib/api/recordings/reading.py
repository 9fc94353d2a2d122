"""Recordings: CSV, NumPy ``.npy``/``.npz`` and PX4 ULog (docs/model.md section 13).

:func:`read_recording` opens a file with the reader of its format
(:mod:`gyrovib.api.recordings.readers`: one parser per format behind one interface),
chooses its columns and units, and returns a :class:`Recording`: the
samples as float64 in deg/s and g (held in memory, or for a ``.npy`` read
from the file when asked), the sample rate fs and the contiguous segments
left after splitting at gaps.

Every problem of the input is a :class:`~gyrovib.errors.GyrovibError` naming
the file and, where it applies, the column or the sample (exit status 2).
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from gyrovib import units
from gyrovib.api.recordings.betaflight import PRESETS, open_betaflight
from gyrovib.api.recordings.px4 import ULOG_ACCEL, ULOG_RATE, ULOG_TOPIC
from gyrovib.api.recordings.readers import (
    TIME_NAMES,
    Axes,
    ColumnNames,
    Columns,
    RecordingError,
    Store,
    problem,
)
from gyrovib.api.recordings.registry import LOGS, Opener, reader_for
from gyrovib.api.recordings.results import source_words
from gyrovib.core._types import FloatArray
from gyrovib.core.recording import gap_segments
from gyrovib.errors import Note, OptionError, headed, literal
from gyrovib.frozen import Frozen

#: A gap is an interval longer than this many median intervals (docs/model.md section 13).
GAP_FACTOR = 1.5
AXES = ("X", "Y", "Z")


@dataclass(frozen=True, eq=False, repr=False)
class Recording(Frozen):
    """A recording in gyrovib's units.

    ``store`` holds the samples: ω about X, Y, Z in deg/s (0 on an axis not
    recorded, ``rate_axes`` False there) and, where recorded, the specific
    force in g, float64; ``rate`` and ``accel`` give them whole as (n, 3)
    arrays, ``store.block``/``store.column`` a stretch at a time. ``fs`` in
    Hz; ``segments`` (S, 2) start/stop sample indices of the contiguous
    segments (gaps split them); ``time_given``: the file had timestamps.
    ``file``, ``sha256``: provenance; ``topic`` and ``instance``: the topic or message
    read and which of its instances, for a log that has them (None otherwise).
    ``warnings``: what the reader noticed about the file without refusing it (damage:
    a log cut short, corrupt data, clipped samples; and what a log library printed).
    """

    file: str
    sha256: str
    fs: float
    rate_axes: tuple[bool, bool, bool]
    accel_axes: tuple[bool, bool, bool]
    segments: NDArray[np.intp]
    time_given: bool
    store: Store = field(compare=False, repr=False)
    warnings: tuple[str, ...] = ()
    topic: str | None = None
    instance: int | None = None

    @property
    def source(self) -> str | None:
        """The topic and instance read, in words (``sensor_gyro_fifo instance 1``), or
        None for a format without topics."""
        return source_words(self.topic, self.instance)

    @property
    def samples(self) -> int:
        """Number of samples read."""
        return int(self.store.rows)

    @property
    def rate(self) -> FloatArray:
        """ω (n, 3) in deg/s, whole (a copy for a .npy)."""
        return self.store.block("rate", 0, self.samples)

    def axis(self, k: int, lo: int = 0, hi: int | None = None) -> FloatArray:
        """ω about axis ``k`` (0, 1, 2), samples lo:hi, deg/s: only that column is read
        (a recorded axis; 0 on one not recorded, see ``rate_axes``)."""
        return self.store.column("rate", k, lo, self.samples if hi is None else hi)

    @property
    def accel(self) -> FloatArray | None:
        """Specific force (n, 3) in g, whole, or None when not recorded."""
        return self.store.block("accel", 0, self.samples) if self.store.has_accel else None


def file_sha256(path: str) -> str:
    """SHA-256 of a file's bytes, read in 1 MiB blocks."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def parse_columns(text: str | None, argument: str) -> tuple[str | int | None, ...] | None:
    """``X,Y,Z`` of ``rate_columns``/``accel_columns`` (named ``argument`` in an error):
    names, 0-based indices, or ``-`` for an axis not recorded; None when not given."""
    if text is None:
        return None
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 3 or any(p == "" for p in parts):
        raise OptionError(argument=argument, value=repr(text),
                          reason="give three columns X,Y,Z (a name, a 0-based index, or - "
                                 "for an axis not recorded)")
    out: list[str | int | None] = []
    for p in parts:
        out.append(None if p == "-" else int(p) if p.isdigit() else p)
    if all(p is None for p in out):
        raise OptionError(argument=argument, value=repr(text),
                          reason="at least one axis must be recorded")
    return tuple(out)


def read_recording(path: str, *, fs: float | None = None,
                   rate_columns: ColumnNames | None = None,
                   accel_columns: ColumnNames | None = None,
                   rate_unit: str | None = None, accel_unit: str | None = None,
                   topic: str | None = None, strict: bool = False,
                   instance: int | None = None, preset: str | None = None) -> Recording:
    """Read a recording (see the module docstring); units default to deg/s and g,
    and for a PX4 or ArduPilot log to its own (rad/s, m/s²). ``topic`` and
    ``instance``: which topic (ULog) or message (DataFlash) and which of its
    instances; ``preset``: a CSV written by another tool (``betaflight``).
    ``strict``: a file whose damage the reader would warn about (a log cut short,
    corrupt data, clipped samples) is refused instead."""
    kind, opener = _format(path, fs, topic, instance, preset)
    log = kind in LOGS
    scales = {"rate": units.scale(units.canonical_unit(rate_unit or ("rad/s" if log
                                                                     else "deg/s"))),
              "accel": units.acceleration(accel_unit or ("m/s^2" if log else "g"))}
    reader = (open_betaflight(path, accel_unit is not None) if preset is not None
              else opener(path, topic, instance))
    if strict and reader.warnings:
        raise problem(path, f"{literal(reader.warnings[0])} (refused under {{strict}})",
                      arguments=("strict",))
    axes = _axes(reader, rate_columns, accel_columns)
    n = reader.rows()
    if n < 2:
        raise problem(path, f"{n} sample(s): a recording needs at least two")
    store, time = reader.load(axes, scales, n)
    rate_fs, segments = _timing(reader, time, fs, store.rows)
    base = os.path.basename(path)
    return Recording(
        file=path, sha256=file_sha256(path), fs=rate_fs,
        rate_axes=_recorded(axes["rate"]), accel_axes=_recorded(axes["accel"]),
        segments=segments, time_given=time is not None, store=store,
        warnings=tuple(Note(f"{literal(base)}: {literal(w)} ({{strict}} refuses such a file)",
                            ("strict", True))
                       for w in reader.warnings)
        + tuple(headed(f"{base}: ", note) for note in reader.notes),
        topic=reader.topic, instance=reader.instance)


def _format(path: str, fs: float | None, topic: str | None, instance: int | None,
            preset: str | None) -> tuple[str, Opener]:
    """The checks before a file is opened, and its format's reader."""
    if fs is not None and not (np.isfinite(fs) and fs > 0):
        raise OptionError(argument="fs", value=f"{fs:g}",
                          reason="give a positive sample rate in Hz")
    if not os.path.exists(path):
        raise problem(path, "no such file")
    if os.path.isdir(path):
        raise problem(path, "is a directory, not a recording")
    if instance is not None and instance < 0:
        raise OptionError(argument="instance", value=str(instance),
                          reason="give an instance number, 0 or more")
    kind, opener = reader_for(path)
    if preset is not None and (preset not in PRESETS or kind != "csv"):
        raise OptionError(argument="preset", value=preset,
                          reason=f"the presets are {', '.join(PRESETS)}, for a CSV recording")
    if topic is not None and kind not in LOGS:
        raise OptionError(reason="{topic} applies only to a PX4 ULog (.ulg) or an ArduPilot "
                                 "DataFlash (.bin) recording", others=("topic",))
    if instance is not None and kind not in LOGS:
        raise OptionError(reason="{instance} applies only to a PX4 ULog (.ulg) or an "
                                 "ArduPilot DataFlash (.bin) recording", others=("instance",))
    return kind, opener


def _axes(reader: Columns, rate_columns: ColumnNames | None,
          accel_columns: ColumnNames | None) -> dict[str, Axes | None]:
    """The column of each axis, rate and acceleration (None: not recorded)."""
    rate_columns, accel_columns = reader.default_columns(rate_columns, accel_columns)
    r_idx = tuple(reader.index(c, "rate_columns") for c in rate_columns)
    a_idx = None if accel_columns is None else tuple(reader.index(c, "accel_columns")
                                                     for c in accel_columns)
    return {"rate": r_idx, "accel": a_idx}  # type: ignore[dict-item]


def _recorded(axes: Axes | None) -> tuple[bool, bool, bool]:
    return (False, False, False) if axes is None else (
        axes[0] is not None, axes[1] is not None, axes[2] is not None)


def _timing(reader: Columns, time: FloatArray | None, fs: float | None,
            n: int) -> tuple[float, NDArray[np.intp]]:
    """fs and the segments: from the timestamps (gaps split), else from --fs."""

    path = reader.path
    if time is None:
        if fs is None:
            raise problem(path, "no time column ('t' or 'time', in s): give the sample "
                                 "rate with {fs} HZ", arguments=("fs",))
        return float(fs), np.array([[0, n]], dtype=np.intp)
    if reader.time_scale != 1.0:
        time *= reader.time_scale
    if not np.all(np.isfinite(time)):
        bad = int(np.flatnonzero(~np.isfinite(time))[0])
        raise problem(path, f"sample {bad}: the timestamp is not a finite number",
                      *reader.where(bad))
    dt = np.diff(time)
    bad_dt = np.flatnonzero(dt <= 0)
    if bad_dt.size:
        k = int(bad_dt[0]) + 1
        what = "repeats" if dt[k - 1] == 0 else "goes back"
        raise problem(path, f"sample {k}: the time stamp {what} (t = {time[k]:.9g} s after "
                            f"{time[k - 1]:.9g} s); time stamps must increase",
                      *reader.where(k))
    segments, median = gap_segments(time, GAP_FACTOR)
    rate_fs = 1.0 / median
    if fs is not None and abs(fs - rate_fs) > 0.01 * rate_fs:
        raise problem(path, f"{{fs}} {fs:g} Hz disagrees with the timestamps' median "
                            f"interval (fs = {rate_fs:.6g} Hz); drop {{fs}} or the time column",
                      arguments=("fs",))
    return rate_fs, segments


#: sosfiltfilt's default padding of the 4th-order split (3·(2·sections + 1) samples):
#: a segment must be longer than it.
PADDING = 15


def iter_segments(recording: Recording, crossover: float) -> Iterator[tuple[int, int]]:
    """The segments kept for crossover f_c: those at least 4/f_c long (docs/model.md section 13)
    and longer than the filter's padding."""
    for lo, hi in recording.segments.tolist():
        if (hi - lo) / recording.fs >= 4.0 / crossover and hi - lo > PADDING:
            yield int(lo), int(hi)


__all__ = ["GAP_FACTOR", "TIME_NAMES", "ULOG_ACCEL", "ULOG_RATE", "ULOG_TOPIC", "Recording",
           "RecordingError", "file_sha256", "iter_segments", "parse_columns",
           "read_recording"]
