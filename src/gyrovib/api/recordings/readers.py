"""One reader per recording format, behind one interface (docs/model.md section 13).

A reader opens a file as a :class:`Columns` table: named columns, which
one is the time, how many rows, and :meth:`Columns.load`, which gives the
chosen columns as a :class:`Store` of float64 samples in deg/s and g. The
formats are registered by suffix in :data:`gyrovib.api.recordings.registry.READERS`;
this module holds the interface and the plain formats:

* CSV (``.csv``, ``.txt``): streamed a block of lines at a time into
  preallocated arrays (its lines are counted first);
* NumPy ``.npy``: never loaded whole. The header is read by
  ``numpy.load(mmap_mode="r")`` (pickled arrays refused, as everywhere);
  the samples are read a block of rows at a time from the file when the
  analysis asks for them (:class:`NpyStore`), so a recording larger than
  memory costs the columns being worked on, not the array;
* NumPy ``.npz``: its arrays copied into float64 arrays (:class:`ArrayColumns`, which
  the log readers use too: PX4 ULog in :mod:`~gyrovib.api.recordings.px4`, ArduPilot
  DataFlash in :mod:`~gyrovib.api.recordings.dataflash`, Betaflight's CSV in
  :mod:`~gyrovib.api.recordings.betaflight`).

Every sample is promoted to float64 before any arithmetic (a float32 ULog
gyro, an int16 ADC column): scaling to deg/s or g happens in float64.

Every problem is a :class:`RecordingError` naming the file and, where it
applies, the column or the sample (exit status 2).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from gyrovib.api.recordings.located import RecordingError, check_magic, csv_where, problem, unplaced
from gyrovib.core._types import FloatArray
from gyrovib.errors import literal

#: Columns as a user names them, per axis X, Y, Z: a name, a 0-based index, or None (an
#: axis not recorded).
ColumnNames = Sequence[str | int | None]
#: The time column's names in a CSV or an .npz (seconds).
TIME_NAMES = ("t", "time")
#: Lines of a CSV parsed at once.
CSV_BLOCK = 200_000
#: Bytes of a .npy read at once.
NPY_BLOCK = 1 << 24
#: Samples of a column promoted and scaled at once.
_CHUNK = 1 << 20

#: A column index (or None: not recorded) per axis X, Y, Z.
Axes = tuple[int | None, int | None, int | None]


class Store(Protocol):
    """A recording's samples in float64, deg/s (``"rate"``) and g (``"accel"``)."""

    rows: int
    has_accel: bool

    def block(self, kind: str, lo: int, hi: int) -> FloatArray:
        """Samples lo:hi of the three axes, (hi − lo, 3); 0 on an axis not recorded."""
        ...

    def column(self, kind: str, axis: int, lo: int, hi: int) -> FloatArray:
        """Samples lo:hi of one axis, (hi − lo,); 0 where the axis is not recorded."""
        ...


class ArrayStore:
    """Samples held in memory, float64: a column per recorded axis (CSV, .npz, ULog).

    ``rate`` and ``accel`` are (n, 3) arrays, or three columns (n,) each, None where
    the axis is not recorded: only recorded axes are held; :meth:`block` puts zeros
    in a stretch's unrecorded columns, and the recording says which they are."""

    def __init__(self, rate: FloatArray | Sequence[FloatArray | None],
                 accel: FloatArray | Sequence[FloatArray | None] | None) -> None:
        rates = _columns(rate)
        self.arrays = {"rate": rates, "accel": None if accel is None else _columns(accel)}
        self.rows = next(int(c.shape[0]) for c in rates if c is not None)
        self.has_accel = accel is not None

    def block(self, kind: str, lo: int, hi: int) -> FloatArray:
        columns = self.arrays[kind]
        assert columns is not None
        out = np.zeros((hi - lo, 3))
        for axis, c in enumerate(columns):
            if c is not None:
                out[:, axis] = c[lo:hi]
        return out

    def column(self, kind: str, axis: int, lo: int, hi: int) -> FloatArray:
        columns = self.arrays[kind]
        assert columns is not None
        c = columns[axis]
        return np.zeros(hi - lo) if c is None else c[lo:hi]


def _columns(data: FloatArray | Sequence[FloatArray | None]) -> list[FloatArray | None]:
    """Three columns (None: not recorded) from an (n, 3) array or three columns."""
    if isinstance(data, np.ndarray):
        return [data[:, k] for k in range(3)]
    return [None if c is None else c.reshape(-1) for c in data]


class NpyStore:
    """Samples of a .npy file, read from the file a block of rows at a time."""

    def __init__(self, path: str, array: np.memmap, axes: dict[str, Axes | None],
                 scales: dict[str, float]) -> None:
        self.path, self.offset = path, int(array.offset)
        self.dtype, self.shape = array.dtype, tuple(int(s) for s in array.shape)
        self.fortran = bool(array.flags.f_contiguous and not array.flags.c_contiguous)
        self.axes, self.scales = axes, scales
        self.rows = self.shape[0]
        self.has_accel = axes.get("accel") is not None
        self.step = max(1, NPY_BLOCK // max(1, self.dtype.itemsize * self.shape[1]))

    def raw(self, lo: int, hi: int) -> NDArray[np.generic]:
        """Rows lo:hi of the file as stored (its dtype), (hi − lo, columns)."""
        width, size = self.shape[1], self.dtype.itemsize
        with open(self.path, "rb") as fh:
            if not self.fortran:
                fh.seek(self.offset + lo * width * size)
                return np.fromfile(fh, self.dtype, (hi - lo) * width).reshape(hi - lo, width)
            out = np.empty((hi - lo, width), self.dtype)
            for c in range(width):
                fh.seek(self.offset + (c * self.rows + lo) * size)
                out[:, c] = np.fromfile(fh, self.dtype, hi - lo)
            return out

    def block(self, kind: str, lo: int, hi: int) -> FloatArray:
        out = np.zeros((hi - lo, 3))
        for b in range(lo, hi, self.step):
            e = min(hi, b + self.step)
            self.convert(self.raw(b, e), kind, out[b - lo:e - lo])
        return out

    def column(self, kind: str, axis: int, lo: int, hi: int) -> FloatArray:
        out = np.zeros(hi - lo)
        axes = self.axes[kind]
        c = None if axes is None else axes[axis]
        if c is None:
            return out
        for b in range(lo, hi, self.step):
            e = min(hi, b + self.step)
            part = out[b - lo:e - lo]
            np.copyto(part, self.raw(b, e)[:, c], casting="unsafe")
            part *= self.scales[kind]
        return out

    def convert(self, raw: NDArray[np.generic], kind: str, out: FloatArray) -> None:
        """Rows as stored to float64 in deg/s or g: promoted first, then scaled."""
        axes = self.axes[kind]
        for axis, c in enumerate(axes or ()):
            if c is not None:
                np.copyto(out[:, axis], raw[:, c], casting="unsafe")
                out[:, axis] *= self.scales[kind]


def promote(column: NDArray[np.generic], scale: float, out: FloatArray) -> None:
    """``out[:] = float64(column) · scale``: promoted first, then scaled, in chunks."""
    for lo in range(0, column.shape[0], _CHUNK):
        part = out[lo:lo + _CHUNK]
        np.copyto(part, column[lo:lo + _CHUNK], casting="unsafe")
        part *= scale


# ----------------------------------------------------------------- the interface


class Columns:
    """A recording file as a table of named columns (the reader interface).

    Subclasses give ``rows`` and ``fill`` (or replace ``load``); ``warnings``
    are the damage the reader noticed in the file without refusing it (a log cut
    short, corrupt data, clipped samples: refused under ``strict``).
    """

    names: list[str]
    path: str
    time_scale: float = 1.0
    warnings: tuple[str, ...] = ()
    #: What a log library printed while reading (warnings, never damage in themselves).
    notes: tuple[str, ...] = ()
    #: The topic or message read and its instance, where the format has them.
    topic: str | None = None
    instance: int | None = None

    def time_index(self) -> int | None:
        """The time column, or None."""
        for i, name in enumerate(self.names):
            if name.strip().lower() in TIME_NAMES:
                return i
        return None

    def default_columns(self, rate: ColumnNames | None, accel: ColumnNames | None,
                        ) -> tuple[ColumnNames, ColumnNames | None]:
        """The rate and acceleration columns when not named: the first three other than time.

        Fewer than three are not placed by a rule (a lone ``gz`` is not X): the user
        places them, an axis not recorded being ``-`` (unknown, never 0)."""
        if rate is None:
            time_col = self.time_index()
            others = [i for i in range(len(self.names)) if i != time_col]
            if len(others) < 1:
                raise problem(self.path, "no rate column: name them with {rate_columns} X,Y,Z",
                              arguments=("rate_columns",))
            if len(others) < 3:
                raise unplaced(self.path, [self.names[i] for i in others])
            rate = tuple(others[:3])
        return rate, accel

    def index(self, column: str | int | None, argument: str) -> int | None:
        """A column named by ``argument`` (``rate_columns``, ``accel_columns``), as its
        index."""
        if column is None:
            return None
        if isinstance(column, int):
            if not 0 <= column < len(self.names):
                raise problem(self.path, f"{{{argument}}}: column {column} does not exist "
                                         f"(the file has {len(self.names)} columns, 0 to "
                                         f"{len(self.names) - 1})", arguments=(argument,))
            return column
        if column in self.names:
            return self.names.index(column)
        shown = ", ".join(self.names[:20]) + (" ..." if len(self.names) > 20 else "")
        raise problem(self.path, f"{{{argument}}}: no column named {literal(repr(column))} "
                                 f"(the columns are: {literal(shown)})", arguments=(argument,))

    def where(self, sample: int) -> tuple[int | None, int | None]:
        """Line and column of sample ``sample``'s time stamp in the file (None, None where
        the format has no lines)."""
        return None, None

    def rows(self) -> int:
        """Number of data rows."""
        raise NotImplementedError

    def fill(self, targets: list[tuple[int, FloatArray, int, float]],
             time: FloatArray | None, time_col: int | None) -> int:
        """Write column c · scale into array[:, axis] for each target; the rows written."""
        raise NotImplementedError

    def load(self, axes: dict[str, Axes | None], scales: dict[str, float],
             n: int) -> tuple[Store, FloatArray | None]:
        """The chosen columns as a store, and the time column (s, before ``time_scale``)."""
        time_col = self.time_index()
        # one (n, 1) array per recorded axis, written through fill's (array, axis 0):
        # an axis not recorded is never built
        built: dict[str, list[FloatArray | None] | None] = {"rate": None, "accel": None}
        time = np.empty(n) if time_col is not None else None
        targets: list[tuple[int, FloatArray, int, float]] = []
        for kind in ("rate", "accel"):
            if axes[kind] is None:
                continue
            columns: list[FloatArray | None] = [None, None, None]
            for axis, c in enumerate(axes[kind] or ()):
                if c is not None:
                    columns[axis] = np.empty((n, 1))
                    targets.append((c, columns[axis], 0, scales[kind]))  # type: ignore[arg-type]
            built[kind] = columns
        rows = self.fill(targets, time, time_col)
        rate, accel = ([None if c is None else c[:rows, 0] for c in cols] if cols else None
                       for cols in (built["rate"], built["accel"]))
        assert rate is not None
        store = ArrayStore(rate, accel)
        return store, None if time is None else time[:rows]


# ----------------------------------------------------------------- CSV


def open_csv(path: str, topic: str | None = None, instance: int | None = None) -> Columns:
    """A CSV with a header row."""
    try:
        with open(path, encoding="utf-8-sig", newline="") as fh:
            header = fh.readline()
    except UnicodeDecodeError:
        raise problem(path, "not a text file (a CSV recording is UTF-8 text)") from None
    except OSError as exc:
        raise problem(path, f"cannot read: {exc.strerror or exc}") from None
    names = [c.strip().strip('"') for c in header.rstrip("\r\n").split(",")]
    if not header.strip():
        raise problem(path, "empty file: a CSV recording starts with a header row", 1, 1)
    if all(_is_number(c) for c in names):
        raise problem(path, "the first row must be a header naming the columns", 1, 1)
    return CsvColumns(path, names, len(names))


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


class CsvColumns(Columns):
    """A CSV, parsed :data:`CSV_BLOCK` lines at a time (float64 from the text)."""

    def __init__(self, path: str, names: list[str], count: int) -> None:
        self.path, self.names, self.count = path, names, count

    def where(self, sample: int) -> tuple[int | None, int | None]:
        return csv_where(self.path, self.time_index(), sample)

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
            while lines := list(itertools.islice(fh, CSV_BLOCK)):
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
                                             dtype=np.float64, comments=None)
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
            if line.strip():  # blank lines are skipped, as the parser skips them
                self._check_line(line, cols, first_line + k)
        raise problem(self.path, "cannot parse the data block", first_line, 1)

    def _check_line(self, line: str, cols: list[int], line_no: int) -> None:
        cells = line.rstrip("\r\n").split(",")
        if len(cells) != self.count:
            raise problem(self.path, f"{len(cells)} cells where the header has "
                                     f"{self.count}", line_no, 1)
        for c in cols:
            cell = cells[c].strip()
            column = 1 + sum(len(x) + 1 for x in cells[:c])
            try:
                value = float(cell)
            except ValueError:
                raise problem(self.path, f"column {self.names[c]!r}: {cell!r} is not "
                                         "a number", line_no, column) from None
            if not np.isfinite(value):
                raise problem(self.path, f"column {self.names[c]!r}: {cell!r} is "
                                         "not a finite number", line_no, column)


# ----------------------------------------------------------------- arrays (.npz, ULog)


class ArrayColumns(Columns):
    """Columns that are arrays in memory (.npz, ULog), promoted to float64 on copy."""

    def __init__(self, path: str, names: list[str], columns: Sequence[NDArray[np.generic]],
                 time_scale: float = 1.0, warnings: tuple[str, ...] = ()) -> None:
        self.path, self.names, self.columns = path, names, list(columns)
        self.time_scale, self.warnings = time_scale, warnings

    def time_index(self) -> int | None:
        if self.time_scale != 1.0:  # ULog: "timestamp" in µs
            return self.names.index("timestamp")
        return super().time_index()

    def rows(self) -> int:
        if not hasattr(self, "count"):  # counted once: fill lets the columns go as it copies
            self.count = int(self.columns[0].shape[0]) if self.columns else 0
        return self.count

    def fill(self, targets: list[tuple[int, FloatArray, int, float]],
             time: FloatArray | None, time_col: int | None) -> int:
        n = self.rows()
        uses = {c: sum(1 for t in targets if t[0] == c) for c, *_ in targets}
        for c, array, axis, scale in targets:
            col = _numeric(self.path, self.names[c], self.columns[c])
            promote(col, scale, array[:n, axis])
            bad = np.flatnonzero(~np.isfinite(array[:n, axis]))
            if bad.size:
                raise problem(self.path, f"column {self.names[c]!r}, sample {int(bad[0])}: "
                                         "not a finite number")
            uses[c] -= 1
            if uses[c] == 0 and c != time_col:  # copied: the original can go now
                self.columns[c] = np.empty(0, col.dtype)
        if time is not None and time_col is not None:
            column = self.columns[time_col]
            if not np.issubdtype(column.dtype, np.number):
                raise problem(self.path, f"time column {self.names[time_col]!r} is not "
                                         f"numeric ({column.dtype})")
            time[:n] = column
        self.columns = []  # the float64 copies are made: let the originals go
        return n


def _numeric(path: str, name: str, column: NDArray[np.generic]) -> NDArray[np.generic]:
    if not np.issubdtype(column.dtype, np.number):
        raise problem(path, f"column {name!r} is not numeric ({column.dtype})")
    return column


# ----------------------------------------------------------------- NumPy


def _numpy_error(path: str, kind: str, exc: Exception) -> RecordingError:
    return problem(path, f"cannot read as NumPy {kind}: {exc}")


def open_npy(path: str, topic: str | None = None, instance: int | None = None) -> Columns:
    """A 2-D .npy: its header only (the samples stay in the file)."""
    check_magic(path, "npy")
    try:
        arr = np.load(path, mmap_mode="r", allow_pickle=False)
    except (OSError, ValueError, EOFError) as exc:
        raise _numpy_error(path, "npy", exc) from None
    if arr.ndim != 2:
        raise problem(path, f"a .npy recording is a 2-D array (samples × columns), "
                            f"not {arr.ndim}-D")
    return NpyColumns(path, arr)


class NpyColumns(Columns):
    """A .npy file's columns, named 0, 1, …; loaded as a :class:`NpyStore`."""

    def __init__(self, path: str, array: np.memmap) -> None:
        self.path, self.array = path, array
        self.names = [str(i) for i in range(array.shape[1])]

    def rows(self) -> int:
        return int(self.array.shape[0])

    def load(self, axes: dict[str, Axes | None], scales: dict[str, float],
             n: int) -> tuple[Store, FloatArray | None]:
        store = NpyStore(self.path, self.array, axes, scales)
        used = [(kind, axis, c) for kind in ("rate", "accel")
                for axis, c in enumerate(axes[kind] or ()) if c is not None]
        for _, _, c in used:
            _numeric(self.path, self.names[c], self.array[:0, c])
        first: dict[int, int] = {}  # column → its first sample that is not finite
        for lo in range(0, n, store.step):
            hi = min(n, lo + store.step)
            raw = store.raw(lo, hi)
            for kind in ("rate", "accel"):
                if axes[kind] is not None:
                    self._check_finite(store, raw, kind, lo, first)
        for _, _, c in used:
            if c in first:
                raise problem(self.path, f"column {self.names[c]!r}, sample {first[c]}: "
                                         "not a finite number")
        del self.array  # the header's map is not needed any more
        return store, None

    @staticmethod
    def _check_finite(store: NpyStore, raw: NDArray[np.generic], kind: str, lo: int,
                      first: dict[int, int]) -> None:
        out = np.zeros((raw.shape[0], 3))
        store.convert(raw, kind, out)
        axes = store.axes[kind] or ()
        for axis, c in enumerate(axes):
            if c is None or c in first:
                continue
            bad = np.flatnonzero(~np.isfinite(out[:, axis]))
            if bad.size:
                first[c] = lo + int(bad[0])


def open_npz(path: str, topic: str | None = None, instance: int | None = None) -> Columns:
    """An .npz: one 2-D array, or 1-D arrays of one length named as columns."""
    check_magic(path, "npz")
    try:
        with np.load(path, allow_pickle=False) as z:
            keys = list(z.keys())
            if len(keys) == 1 and z[keys[0]].ndim == 2:
                arr = z[keys[0]]
                return ArrayColumns(path, [str(i) for i in range(arr.shape[1])],
                                    [arr[:, i] for i in range(arr.shape[1])])
            cols = [np.asarray(z[k]) for k in keys]
    except (OSError, ValueError, EOFError) as exc:
        raise _numpy_error(path, "npz", exc) from None
    if any(c.ndim != 1 for c in cols) or len({c.shape[0] for c in cols}) != 1:
        raise problem(path, "an .npz recording holds one 2-D array, or 1-D arrays of one "
                            "length named as columns")
    return ArrayColumns(path, keys, cols)


__all__ = ["ArrayColumns", "ArrayStore", "Columns", "NpyStore", "RecordingError", "Store",
           "open_csv", "open_npy", "open_npz", "problem"]
