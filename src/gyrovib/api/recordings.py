"""Reading recordings: CSV, NumPy ``.npy``/``.npz`` and PX4 ULog (docs/model.md section 13).

A recording is read into preallocated float arrays: the angular rate (n, 3)
in deg/s and, where recorded, the specific force (n, 3) in g, with the sample
rate fs and the contiguous segments left after splitting at gaps. A CSV is
streamed a block of lines at a time into those arrays (its lines are counted
first), so a large file needs little more than the arrays themselves.

Every problem of the input is a :class:`~gyrovib.errors.GyrovibError` naming
the file and, where it applies, the column or the sample (exit status 2).
"""

from __future__ import annotations

import hashlib
import itertools
import os
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gyrovib import units
from gyrovib.core.transmissibility import FloatArray
from gyrovib.errors import GyrovibError, OptionError, Problem
from gyrovib.frozen import Frozen

#: The time column's names in a CSV or an .npz (seconds).
TIME_NAMES = ("t", "time")
#: ULog's default topic and its fields (rad/s, m/s², timestamps in µs).
ULOG_TOPIC = "sensor_combined"
ULOG_RATE = ("gyro_rad[0]", "gyro_rad[1]", "gyro_rad[2]")
ULOG_ACCEL = ("accelerometer_m_s2[0]", "accelerometer_m_s2[1]", "accelerometer_m_s2[2]")
#: Lines of a CSV parsed at once.
CSV_BLOCK = 200_000
#: A gap is an interval longer than this many median intervals (docs/model.md section 13).
GAP_FACTOR = 1.5
AXES = ("X", "Y", "Z")


class RecordingError(GyrovibError):
    """A recording cannot be read, or does not suit the analysis asked of it."""


def _problem(file: str, message: str, line: int | None = None,
             column: int | None = None) -> RecordingError:
    return RecordingError(Problem(message, file, line, column))


@dataclass(frozen=True, eq=False, repr=False)
class Recording(Frozen):
    """A recording in gyrovib's units.

    ``rate`` (n, 3) ω about X, Y, Z in deg/s (0 on an axis not recorded,
    ``rate_axes`` False there); ``accel`` (n, 3) specific force in g, or None;
    ``fs`` in Hz; ``segments`` (S, 2) start/stop sample indices of the
    contiguous segments (gaps split them); ``time_given``: the file had
    timestamps. ``file``, ``sha256``: provenance.
    """

    file: str
    sha256: str
    fs: float
    rate: FloatArray
    accel: FloatArray | None
    rate_axes: tuple[bool, bool, bool]
    accel_axes: tuple[bool, bool, bool]
    segments: NDArray[np.intp]
    time_given: bool

    @property
    def samples(self) -> int:
        """Number of samples read."""
        return int(self.rate.shape[0])


def file_sha256(path: str) -> str:
    """SHA-256 of a file's bytes, read in 1 MiB blocks."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def parse_columns(text: str | None, option: str) -> tuple[str | int | None, ...] | None:
    """``X,Y,Z`` of ``--rate-columns``/``--accel-columns``: names, 0-based indices, or
    ``-`` for an axis not recorded; None when the option is not given."""
    if text is None:
        return None
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 3 or any(p == "" for p in parts):
        raise OptionError(f"{option} {text!r}: give three columns X,Y,Z (a name, a 0-based "
                          "index, or - for an axis not recorded)")
    out: list[str | int | None] = []
    for p in parts:
        out.append(None if p == "-" else int(p) if p.isdigit() else p)
    if all(p is None for p in out):
        raise OptionError(f"{option} {text!r}: at least one axis must be recorded")
    return tuple(out)


def read_recording(path: str, *, fs: float | None = None,
                   rate_columns: Sequence[str | int | None] | None = None,
                   accel_columns: Sequence[str | int | None] | None = None,
                   rate_unit: str | None = None, accel_unit: str | None = None,
                   topic: str | None = None) -> Recording:
    """Read a recording (see the module docstring); units default to deg/s and g,
    and for ULog to the topic's own (rad/s, m/s²)."""
    if fs is not None and not (np.isfinite(fs) and fs > 0):
        raise OptionError(f"--fs {fs:g}: give a positive sample rate in Hz")
    if not os.path.exists(path):
        raise _problem(path, "no such file")
    if os.path.isdir(path):
        raise _problem(path, "is a directory, not a recording")
    lower = path.lower()
    if lower.endswith(".ulg"):
        kind = "ulog"
    elif lower.endswith(".npy"):
        kind = "npy"
    elif lower.endswith(".npz"):
        kind = "npz"
    elif lower.endswith((".csv", ".txt")):
        kind = "csv"
    else:
        raise _problem(path, "unknown recording format: use .csv (header row), .npy, .npz "
                             "or .ulg (PX4 ULog)")
    if topic is not None and kind != "ulog":
        raise OptionError("--topic applies only to a ULog (.ulg) recording")
    ulog = kind == "ulog"
    r_scale = units.scale(units.canonical_unit(rate_unit or ("rad/s" if ulog else "deg/s")))
    a_scale = units.acceleration(accel_unit or ("m/s^2" if ulog else "g"))
    reader: _Columns
    if kind == "csv":
        names, columns = _csv_header(path)
        reader = _CsvColumns(path, names, columns)
    elif kind == "ulog":
        reader = _ulog_columns(path, topic or ULOG_TOPIC)
        if rate_columns is None:  # sensor_combined's, or x, y, z of a sensor_gyro topic
            plain = ("x", "y", "z")
            rate_columns = (plain if all(c in reader.names for c in plain)
                            and ULOG_RATE[0] not in reader.names else ULOG_RATE)
        if accel_columns is None and all(c in reader.names for c in ULOG_ACCEL):
            accel_columns = ULOG_ACCEL
    else:
        reader = _npy_columns(path, kind)
    time_col = reader.time_index()
    if rate_columns is None:
        others = [i for i in range(len(reader.names)) if i != time_col]
        if len(others) < 1:
            raise _problem(path, "no rate column: name them with --rate-columns X,Y,Z")
        rate_columns = tuple(others[:3]) + (None,) * (3 - len(others[:3]))
    r_idx = [reader.index(c, "--rate-columns") for c in rate_columns]
    a_idx = None if accel_columns is None else [reader.index(c, "--accel-columns")
                                                 for c in accel_columns]
    n = reader.rows()
    if n < 2:
        raise _problem(path, f"{n} sample(s): a recording needs at least two")
    rate = np.zeros((n, 3))
    accel = None if a_idx is None else np.zeros((n, 3))
    time = np.empty(n) if time_col is not None else None
    targets: list[tuple[int, FloatArray, int, float]] = []
    for axis, c in enumerate(r_idx):
        if c is not None:
            targets.append((c, rate, axis, r_scale))
    if accel is not None and a_idx is not None:
        for axis, c in enumerate(a_idx):
            if c is not None:
                targets.append((c, accel, axis, a_scale))
    n = reader.fill(targets, time, time_col)
    rate, accel = rate[:n], None if accel is None else accel[:n]
    time = None if time is None else time[:n]
    rate_fs, segments = _timing(path, time, fs, reader.time_scale, n)
    return Recording(
        file=path, sha256=file_sha256(path), fs=rate_fs, rate=rate, accel=accel,
        rate_axes=tuple(c is not None for c in r_idx),  # type: ignore[arg-type]
        accel_axes=((False, False, False) if a_idx is None
                    else tuple(c is not None for c in a_idx)),  # type: ignore[arg-type]
        segments=segments, time_given=time is not None)


def _timing(path: str, time: FloatArray | None, fs: float | None,
            time_scale: float, n: int) -> tuple[float, NDArray[np.intp]]:
    """fs and the segments: from the timestamps (gaps split), else from --fs."""
    from gyrovib.core.recording import gap_segments

    if time is None:
        if fs is None:
            raise _problem(path, "no time column ('t' or 'time', in s): give the sample "
                                 "rate with --fs HZ")
        return float(fs), np.array([[0, n]], dtype=np.intp)
    if time_scale != 1.0:
        time *= time_scale
    if not np.all(np.isfinite(time)):
        bad = int(np.flatnonzero(~np.isfinite(time))[0])
        raise _problem(path, f"sample {bad}: the timestamp is not a finite number")
    dt = np.diff(time)
    bad_dt = np.flatnonzero(dt <= 0)
    if bad_dt.size:
        k = int(bad_dt[0]) + 1
        raise _problem(path, f"sample {k}: timestamps must increase (t = {time[k]:.9g} s "
                             f"after {time[k - 1]:.9g} s)")
    segments, median = gap_segments(time, GAP_FACTOR)
    rate_fs = 1.0 / median
    if fs is not None and abs(fs - rate_fs) > 0.01 * rate_fs:
        raise _problem(path, f"--fs {fs:g} Hz disagrees with the timestamps' median "
                             f"interval (fs = {rate_fs:.6g} Hz); drop --fs or the time column")
    return rate_fs, segments


# ----------------------------------------------------------------- column sources


class _Columns:
    """A table of named columns that fills preallocated arrays."""

    names: list[str]
    path: str
    time_scale: float = 1.0

    def time_index(self) -> int | None:
        for i, name in enumerate(self.names):
            if name.strip().lower() in TIME_NAMES:
                return i
        return None

    def index(self, column: str | int | None, option: str) -> int | None:
        if column is None:
            return None
        if isinstance(column, int):
            if not 0 <= column < len(self.names):
                raise _problem(self.path, f"{option}: column {column} does not exist "
                                          f"(the file has {len(self.names)} columns, 0 to "
                                          f"{len(self.names) - 1})")
            return column
        if column in self.names:
            return self.names.index(column)
        shown = ", ".join(self.names[:20]) + (" ..." if len(self.names) > 20 else "")
        raise _problem(self.path, f"{option}: no column named {column!r} (the columns "
                                  f"are: {shown})")

    def rows(self) -> int:
        raise NotImplementedError

    def fill(self, targets: list[tuple[int, FloatArray, int, float]],
             time: FloatArray | None, time_col: int | None) -> int:
        raise NotImplementedError


def _csv_header(path: str) -> tuple[list[str], int]:
    try:
        with open(path, encoding="utf-8-sig", newline="") as fh:
            header = fh.readline()
    except UnicodeDecodeError:
        raise _problem(path, "not a text file (a CSV recording is UTF-8 text)") from None
    except OSError as exc:
        raise _problem(path, f"cannot read: {exc.strerror or exc}") from None
    names = [c.strip().strip('"') for c in header.rstrip("\r\n").split(",")]
    if not header.strip():
        raise _problem(path, "empty file: a CSV recording starts with a header row", 1, 1)
    if all(_is_number(c) for c in names):
        raise _problem(path, "the first row must be a header naming the columns", 1, 1)
    return names, len(names)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


class _CsvColumns(_Columns):
    def __init__(self, path: str, names: list[str], count: int) -> None:
        self.path, self.names, self.count = path, names, count

    def rows(self) -> int:
        lines = 0
        last = b"\n"
        with open(self.path, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 22), b""):
                lines += block.count(b"\n")
                last = block[-1:]
        return lines - 1 + (last != b"\n")

    def fill(self, targets: list[tuple[int, FloatArray, int, float]],
             time: FloatArray | None, time_col: int | None) -> int:
        cols = sorted({c for c, *_ in targets} | ({time_col} if time_col is not None else set()))
        where = {c: k for k, c in enumerate(cols)}
        row = 0
        with open(self.path, encoding="utf-8-sig", newline="") as fh:
            fh.readline()
            line_no = 2
            while True:
                lines = [ln for ln in itertools.islice(fh, CSV_BLOCK)]
                if not lines:
                    break
                block = self._parse(lines, cols, line_no)
                m = block.shape[0]
                for c, array, axis, scale in targets:
                    np.multiply(block[:, where[c]], scale, out=array[row:row + m, axis])
                if time is not None and time_col is not None:
                    time[row:row + m] = block[:, where[time_col]]
                row += m
                line_no += len(lines)
        return row

    def _parse(self, lines: list[str], cols: list[int], first_line: int) -> FloatArray:
        try:
            with np.errstate(all="ignore"):
                out: FloatArray = np.loadtxt(lines, delimiter=",", usecols=cols, ndmin=2,
                                             dtype=float, comments=None)
        except ValueError:
            self._locate(lines, cols, first_line)
            raise  # _locate always raises; this is for the type checker
        if out.shape[0] != sum(1 for ln in lines if ln.strip()):
            self._locate(lines, cols, first_line)
        if not np.all(np.isfinite(out)):
            self._locate(lines, cols, first_line)
        return out

    def _locate(self, lines: list[str], cols: list[int], first_line: int) -> None:
        for k, line in enumerate(lines):
            if not line.strip():
                continue  # blank lines are skipped, as the parser skips them
            cells = line.rstrip("\r\n").split(",")
            if len(cells) != self.count:
                raise _problem(self.path, f"{len(cells)} cells where the header has "
                                          f"{self.count}", first_line + k, 1)
            for c in cols:
                cell = cells[c].strip()
                column = 1 + sum(len(x) + 1 for x in cells[:c])
                try:
                    value = float(cell)
                except ValueError:
                    raise _problem(self.path, f"column {self.names[c]!r}: {cell!r} is not "
                                              "a number", first_line + k, column) from None
                if not np.isfinite(value):
                    raise _problem(self.path, f"column {self.names[c]!r}: {cell!r} is "
                                              "not a finite number", first_line + k, column)
        raise _problem(self.path, "cannot parse the data block", first_line, 1)


class _ArrayColumns(_Columns):
    def __init__(self, path: str, names: list[str], columns: Sequence[NDArray[np.generic]],
                 time_scale: float = 1.0) -> None:
        self.path, self.names, self.columns = path, names, list(columns)
        self.time_scale = time_scale

    def time_index(self) -> int | None:
        if self.time_scale != 1.0:  # ULog: "timestamp" in µs
            return self.names.index("timestamp")
        return super().time_index()

    def rows(self) -> int:
        return int(self.columns[0].shape[0]) if self.columns else 0

    def fill(self, targets: list[tuple[int, FloatArray, int, float]],
             time: FloatArray | None, time_col: int | None) -> int:
        n = self.rows()
        for c, array, axis, scale in targets:
            col = self.columns[c]
            if not np.issubdtype(col.dtype, np.number):
                raise _problem(self.path, f"column {self.names[c]!r} is not numeric "
                                          f"({col.dtype})")
            for lo in range(0, n, 1 << 20):
                np.multiply(col[lo:lo + (1 << 20)], scale,
                            out=array[lo:lo + (1 << 20), axis], casting="unsafe")
            bad = np.flatnonzero(~np.isfinite(array[:n, axis]))
            if bad.size:
                raise _problem(self.path, f"column {self.names[c]!r}, sample {int(bad[0])}: "
                                          "not a finite number")
        if time is not None and time_col is not None:
            column = self.columns[time_col]
            if not np.issubdtype(column.dtype, np.number):
                raise _problem(self.path, f"time column {self.names[time_col]!r} is not "
                                          f"numeric ({column.dtype})")
            time[:n] = column
        return n


def _npy_columns(path: str, kind: str) -> _ArrayColumns:
    try:
        if kind == "npy":
            arr = np.load(path, mmap_mode="r", allow_pickle=False)
            if arr.ndim != 2:
                raise _problem(path, f"a .npy recording is a 2-D array (samples × columns), "
                                     f"not {arr.ndim}-D")
            names = [str(i) for i in range(arr.shape[1])]
            return _ArrayColumns(path, names, [arr[:, i] for i in range(arr.shape[1])])
        with np.load(path, allow_pickle=False) as z:
            keys = list(z.keys())
            if len(keys) == 1 and z[keys[0]].ndim == 2:
                arr = z[keys[0]]
                return _ArrayColumns(path, [str(i) for i in range(arr.shape[1])],
                                     [arr[:, i] for i in range(arr.shape[1])])
            cols = [np.asarray(z[k]) for k in keys]
    except GyrovibError:
        raise
    except (OSError, ValueError, EOFError) as exc:
        raise _problem(path, f"cannot read as NumPy {kind}: {exc}") from None
    if any(c.ndim != 1 for c in cols) or len({c.shape[0] for c in cols}) != 1:
        raise _problem(path, "an .npz recording holds one 2-D array, or 1-D arrays of one "
                             "length named as columns")
    return _ArrayColumns(path, keys, cols)


def _ulog_columns(path: str, topic: str) -> _ArrayColumns:
    try:
        from pyulog import ULog
    except ImportError:
        raise _problem(path, "reading PX4 ULog needs pyulog: pip install 'gyrovib[ulog]'") \
            from None
    try:
        log = ULog(path, [topic])
    except Exception as exc:  # pyulog raises many kinds on a damaged file
        raise _problem(path, f"cannot read as PX4 ULog: {type(exc).__name__}: {exc}") \
            from None
    found = [d for d in log.data_list if d.name == topic]
    if not found:
        raise _problem(path, f"no topic {topic!r} in this log (choose one with --topic)")
    data = max(found, key=lambda d: len(d.data["timestamp"])).data
    names = ["timestamp", *[k for k in data if k != "timestamp"]]
    return _ArrayColumns(path, names, [data[k] for k in names], time_scale=1e-6)


#: sosfiltfilt's default padding of the 4th-order split (3·(2·sections + 1) samples):
#: a segment must be longer than it.
PADDING = 15


def iter_segments(recording: Recording, crossover: float) -> Iterator[tuple[int, int]]:
    """The segments kept for crossover f_c: those at least 4/f_c long (docs/model.md section 13)
    and longer than the filter's padding."""
    for lo, hi in recording.segments.tolist():
        if (hi - lo) / recording.fs >= 4.0 / crossover and hi - lo > PADDING:
            yield int(lo), int(hi)


__all__ = ["Recording", "RecordingError", "file_sha256", "iter_segments", "parse_columns",
           "read_recording"]
