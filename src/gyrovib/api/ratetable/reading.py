"""Reading a rate-table CSV (docs/rate-table.md).

A header row names the columns: ``unit`` (optional: one unit if absent),
``rate`` (the applied Ω, in the rate unit), ``output`` (the mean output, in
the output unit), optional ``rate_x1``, ``rate_x2`` (applied cross rates, in
the rate unit). Repeated rows at one rate are separate observations. Blank
lines and lines starting with ``#`` (comments: provenance, how the numbers
were made) are skipped. A bad cell is reported as ``FILE:LINE:COL`` naming its
column; every bad cell of the file is reported in one run.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from gyrovib import units as rate_units
from gyrovib.core._types import FloatArray
from gyrovib.errors import GyrovibError, Problem, literal
from gyrovib.frozen import Frozen

COLUMNS: tuple[str, ...] = ("unit", "rate", "output", "rate_x1", "rate_x2")
REQUIRED: tuple[str, ...] = ("rate", "output")
#: The largest file read (a rate table is a few hundred lines; this is not one).
MAX_BYTES = 16 * 1024 * 1024
#: At most this many bad cells are reported, then a count of the rest.
MAX_PROBLEMS = 20
_ID = re.compile(r"^[A-Za-z0-9._-]{1,200}$")
STDIN = "-"
STDIN_NAME = "<stdin>"


class RateTableError(GyrovibError):
    """A rate table cannot be read: no such file, not CSV text, a bad header or cell."""


@dataclass(frozen=True, eq=False, repr=False)
class RateTable(Frozen):
    """A rate table, grouped by unit in order of first appearance.

    ``rate[i]``, ``output[i]`` (n_i,) and ``cross[i]`` ((n_i, len(cross_axes)) or
    None) are unit i's points, in the file's units (``rate_unit``; the output
    unit ``output_unit`` is a label, None when not given); ``lines[i]`` the file
    line of each point.
    """

    file: str
    rate_unit: str
    output_unit: str | None
    units: tuple[str, ...]
    rate: tuple[FloatArray, ...]
    output: tuple[FloatArray, ...]
    cross: tuple[FloatArray | None, ...]
    cross_axes: tuple[int, ...]
    lines: tuple[NDArray[np.int64], ...]
    unit_column: bool

    @property
    def points(self) -> int:
        """Rows in the table."""
        return sum(r.size for r in self.rate)


def output_unit_label(text: str | None) -> str | None:
    """``--output-unit``: a rate unit (canonical spelling) or any short label (mV, V,
    LSB, mA); None stays None (the output unit is not named)."""
    if text is None:
        return None
    label = text.strip()
    if not label or len(label) > 32 or not label.isprintable():
        raise RateTableError(Problem.naming(f"{{output_unit}} {literal(repr(text))}: give a "
                                            "short unit name such as mV, V, LSB or a rate unit",
                                            ("output_unit",)))
    try:
        return rate_units.canonical_unit(label)
    except GyrovibError:
        return label


def _fields(line: str) -> list[tuple[str, int]] | None:
    """The comma-separated cells of ``line`` with the 1-based column each starts at
    (double quotes as in CSV, ``""`` inside them a quote); None when a quote is not
    closed."""
    out: list[tuple[str, int]] = []
    k, n = 0, len(line)
    while True:
        while k < n and line[k] in " \t":
            k += 1
        start = k
        if k < n and line[k] == '"':
            k += 1
            text = []
            while True:
                if k >= n:
                    return None
                if line[k] == '"':
                    if k + 1 < n and line[k + 1] == '"':
                        text.append('"')
                        k += 2
                        continue
                    k += 1
                    break
                text.append(line[k])
                k += 1
            value = "".join(text)
            while k < n and line[k] != ",":
                k += 1
        else:
            end = line.find(",", k)
            end = n if end < 0 else end
            value = line[k:end].strip()
            k = end
        out.append((value, start + 1))
        if k >= n:
            return out
        k += 1  # the comma


def _decode(raw: bytes, name: str) -> str:
    if len(raw) > MAX_BYTES:
        raise RateTableError(Problem(f"the file is larger than {MAX_BYTES // 2**20} MiB; that "
                                     "is not a rate table", name))
    if b"\0" in raw:
        raise RateTableError(Problem("binary data (a NUL byte), not a CSV text file", name))
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        raise RateTableError(Problem(f"not UTF-8 text (byte 0x{raw[exc.start]:02x}); save the "
                                     "table as UTF-8 CSV", name, line, 1)) from None


def read_rate_table(path: str | Path, rate_unit: str = "deg/s",
                    output_unit: str | None = None) -> RateTable:
    """Read the rate table at ``path`` (see the module docstring); rates in
    ``rate_unit``, outputs in ``output_unit`` (a label)."""
    name = str(path)
    try:
        with open(path, "rb") as handle:
            raw = handle.read(MAX_BYTES + 1)
    except OSError as exc:
        raise RateTableError(Problem(f"cannot read the rate table: {exc.strerror or exc}",
                                     name)) from None
    text = _decode(raw, name)
    del raw  # the bytes are not needed while the text is parsed
    return parse_rate_table(text, name, rate_unit, output_unit)


def read_rate_table_bytes(raw: bytes, name: str, rate_unit: str = "deg/s",
                          output_unit: str | None = None) -> RateTable:
    """:func:`parse_rate_table` of raw bytes (standard input), checked as a file is."""
    return parse_rate_table(_decode(raw, name), name, rate_unit, output_unit)


def _unit_name(name: str) -> str:
    """The one unit of a table without a ``unit`` column: the file's stem as an id."""
    stem = Path(name).stem if name != STDIN_NAME else "unit"
    cleaned = re.sub(r"[^A-Za-z0-9._-]+", "-", stem).strip("-.") or "unit"
    return cleaned[:200]


class _Problems:
    """The problems of one file: the first :data:`MAX_PROBLEMS` listed, the rest counted."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.found: list[Problem] = []
        self.dropped = 0

    def add(self, message: str, line: int, column: int | None = None) -> None:
        if len(self.found) < MAX_PROBLEMS:
            self.found.append(Problem(message, self.name, line, column))
        else:
            self.dropped += 1

    def __bool__(self) -> bool:
        return bool(self.found)

    def check(self) -> None:
        """Raise :class:`RateTableError` with every problem found so far, if any."""
        if self.dropped:
            self.found.append(Problem(f"... and {self.dropped} more problem"
                                      f"{'s' if self.dropped > 1 else ''}", self.name))
            self.dropped = 0
        if self.found:
            raise RateTableError(self.found)


class _Header(NamedTuple):
    """The header row: its cells, its line, the index of each known column."""

    cells: list[tuple[str, int]]
    line: int
    columns: dict[str, int]

    @property
    def numeric(self) -> list[str]:
        """The number columns present, in :data:`COLUMNS` order."""
        return [c for c in COLUMNS[1:] if c in self.columns]


def _header(cells: list[tuple[str, int]], number: int, problems: _Problems) -> _Header:
    """The header row at line ``number``; raises with every problem of it at once (the
    rows cannot be read without it)."""
    columns: dict[str, int] = {}
    for k, (title, col) in enumerate(cells):
        key = title.strip().lower()
        if key in columns:
            problems.add(f"column {title!r} appears twice in the header", number, col)
        elif key not in COLUMNS:
            problems.add(f"unknown column {title!r}; the columns are "
                         f"{', '.join(COLUMNS)} (unit, rate_x1, rate_x2 optional)", number, col)
        else:
            columns[key] = k
    missing = [c for c in REQUIRED if c not in columns]
    if missing:
        problems.add(f"the header has no {' or '.join(repr(c) for c in missing)} column "
                     f"(found {', '.join(repr(t) for t, _ in cells)}); the first line "
                     "that is not a comment names the columns", number, 1)
    problems.check()
    return _Header(cells, number, columns)


def _number(key: str, cell: str, col: int, number: int, problems: _Problems) -> float | None:
    """The finite number in ``cell`` of column ``key``, or None (a problem recorded)."""
    try:
        value = float(cell)
    except ValueError:
        what = "empty" if not cell else f"{cell!r} is not a number"
        problems.add(f"{key}: {what}", number, col)
        return None
    if not math.isfinite(value):
        problems.add(f"{key}: {cell!r} is not a finite number", number, col)
        return None
    return value


def _unit_problem(who: str) -> str | None:
    """Why ``who`` is not a unit name, or None when it is one."""
    if _ID.match(who):
        return None
    return (f"unit: {who!r} is not a unit name (letters, digits, '.', '_', '-'; it becomes "
            "the sensor's id)" if who else "unit: empty")


class _Store:
    """Growing arrays of the rows read: each number column, the line numbers and each row's
    unit index, filled block by block (no Python object per row, no joining at the end)."""

    def __init__(self, keys: list[str], capacity: int) -> None:
        self.size = 0
        self.values = {k: np.empty(capacity) for k in keys}
        self.lines = np.empty(capacity, dtype=np.int64)
        self.who = np.empty(capacity, dtype=np.int32)

    def add(self, values: dict[str, FloatArray], lines: NDArray[np.int64],
            who: NDArray[np.int32]) -> None:
        start, stop = self.size, self.size + lines.size
        if stop > self.lines.size:  # more lines than newlines: other line breaks
            grow = max(stop, 2 * self.lines.size)
            self.values = {k: np.resize(v, grow) for k, v in self.values.items()}
            self.lines, self.who = np.resize(self.lines, grow), np.resize(self.who, grow)
        for key, column in values.items():
            self.values[key][start:stop] = column
        self.lines[start:stop] = lines
        self.who[start:stop] = who
        self.size = stop


def _even_rows(text: str, rows: int, commas: int) -> bool:
    """Whether each of the ``rows`` lines of ASCII ``text`` (joined by newlines) holds
    exactly ``commas`` commas (counted with numpy, not line by line)."""
    codes = np.frombuffer(text.encode("ascii"), dtype=np.uint8)
    ends = np.flatnonzero(codes == ord("\n"))
    at = np.searchsorted(ends, np.flatnonzero(codes == ord(",")))
    return bool(np.all(np.bincount(at, minlength=rows) == commas))


class _Table:
    """A rate table being read block by block (:func:`parse_rate_table`).

    The rows are kept in numpy arrays (:class:`_Store`), one per number column, the
    line numbers and each row's unit index: 8 bytes per cell, never a Python
    object per row.
    """

    def __init__(self, name: str, capacity: int) -> None:
        self.name = name
        self.problems = _Problems(name)
        self.header: _Header | None = None
        self.units: dict[str, int] = {}
        self.capacity = capacity
        self.store: _Store | None = None

    def add(self, values: dict[str, FloatArray], lines: NDArray[np.int64],
            who: NDArray[np.int32]) -> None:
        """Keep these rows (the header is known)."""
        if self.store is None:
            assert self.header is not None
            self.store = _Store(self.header.numeric, self.capacity)
        self.store.add(values, lines, who)

    def unit_index(self, who: str) -> int:
        return self.units.setdefault(who, len(self.units))

    def careful(self, lines: list[str], first: int) -> None:
        """Read ``lines`` (the first at line ``first``) one by one, every problem located."""
        values: dict[str, list[float]] = {}
        numbers: list[int] = []
        who: list[int] = []
        for number, line in enumerate(lines, start=first):
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            cells = _fields(line)
            if cells is None:
                self.problems.add("a quoted cell is not closed on its line", number, 1)
            elif self.header is None:
                self.header = _header(cells, number, self.problems)
            else:
                row = self._row(cells, number, self.header)
                if row is not None:
                    for key, value in zip(self.header.numeric, row[1], strict=True):
                        values.setdefault(key, []).append(value)
                    numbers.append(number)
                    who.append(self.unit_index(row[0]))
        if numbers:
            self.add({k: np.array(v) for k, v in values.items()},
                     np.array(numbers, dtype=np.int64), np.array(who, dtype=np.int32))

    def _row(self, cells: list[tuple[str, int]], number: int, header: _Header
             ) -> tuple[str, list[float]] | None:
        """One data row's unit and numbers, or None (its problems recorded)."""
        if len(cells) != len(header.cells):
            self.problems.add(f"{len(cells)} cell{'s' if len(cells) != 1 else ''} in this row, "
                              f"{len(header.cells)} columns in the header (line {header.line})",
                              number, 1)
            return None
        values = [_number(key, *cells[header.columns[key]], number, self.problems)
                  for key in header.numeric]
        who = _unit_name(self.name)
        bad = False
        if "unit" in header.columns:
            who, col = cells[header.columns["unit"]]
            message = _unit_problem(who)
            if message is not None:
                self.problems.add(message, number, col)
                bad = True
        if bad or any(v is None for v in values):
            return None
        return who, [float(v) for v in values if v is not None]

    def quick(self, text: str, lines: list[str], first: int) -> bool:
        """Read a block of plain rows at once (no quotes, comments or blank lines, every
        row as wide as the header, every number finite, every unit name valid); False,
        with nothing read, when one of them is not, for :meth:`careful` to report."""
        header = self.header
        if header is None or '"' in text or "#" in text or "" in lines:
            return False
        width = len(header.cells)
        joined = "\n".join(lines)
        if not joined.isascii() or not _even_rows(joined, len(lines), width - 1):
            return False
        cells = joined.replace("\n", ",").split(",")
        values: dict[str, FloatArray] = {}
        try:
            for key in header.numeric:
                column = cells[header.columns[key]::width]
                values[key] = np.fromiter(map(float, column), dtype=float, count=len(lines))
        except ValueError:
            return False
        if not all(np.all(np.isfinite(v)) for v in values.values()):
            return False
        who = self._quick_units(cells[header.columns["unit"]::width]
                                if "unit" in header.columns else None, len(lines))
        if who is None:
            return False
        self.add(values, np.arange(first, first + len(lines), dtype=np.int64), who)
        return True

    def _quick_units(self, column: list[str] | None, rows: int) -> NDArray[np.int32] | None:
        """Each row's unit index (the names checked, new ones registered in order of
        first appearance), or None when a name is not valid."""
        if column is None:
            return np.full(rows, self.unit_index(_unit_name(self.name)), dtype=np.int32)
        seen = dict.fromkeys(column)
        names = {raw: raw.strip() for raw in seen}
        if any(_unit_problem(who) is not None for who in names.values()):
            return None
        index = {raw: self.unit_index(who) for raw, who in names.items()}
        return np.fromiter(map(index.__getitem__, column), dtype=np.int32, count=rows)

    def finish(self) -> None:
        """Raise with every problem found; a table without a header or rows is one."""
        if self.header is None:
            self.problems.add("no header row: the table is empty (a header such as "
                              "'unit,rate,output' and one row per measurement)", 1, None)
        elif self.store is None and not self.problems:
            self.problems.add("no data rows after the header", self.header.line, None)
        self.problems.check()

    def grouped(self) -> tuple[list[NDArray[np.int64]], dict[str, list[FloatArray]]]:
        """Per unit (in order of first appearance): its line numbers and its values of each
        number column."""
        assert self.header is not None
        keys = self.header.numeric
        store = self.store
        assert store is not None
        n = store.size
        lines, who = store.lines[:n], store.who[:n]
        columns = {k: store.values[k][:n] for k in keys}
        self.store = None
        if len(self.units) == 1:
            return [lines], {k: [v] for k, v in columns.items()}
        return self._split(lines, columns, who)

    def _split(self, lines: NDArray[np.int64], columns: dict[str, FloatArray],
               who: NDArray[np.int32]) -> tuple[list[NDArray[np.int64]],
                                                dict[str, list[FloatArray]]]:
        """The rows grouped by unit (a stable sort: each unit's rows in file order)."""
        order = np.argsort(who, kind="stable")
        edges = np.cumsum(np.bincount(who, minlength=len(self.units)))[:-1]
        split_lines = np.split(lines[order], edges)
        return split_lines, {k: np.split(v[order], edges) for k, v in columns.items()}


#: Characters of text read as one block (a few hundred thousand cells as Python strings).
BLOCK_CHARS = 1 << 19


def _blocks(text: str) -> Iterator[tuple[int, str, list[str]]]:
    """The text in blocks of whole lines (cut after a newline): the first line's number,
    the block's text and its lines (``str.splitlines``, as the whole text would split).
    The first block is small: it holds the header, read line by line."""
    number, start, size = 1, 0, 1 << 12
    while start < len(text):
        cut = text.find("\n", start + size)
        end = len(text) if cut < 0 else cut + 1
        chunk = text[start:end]
        lines = chunk.splitlines()
        yield number, chunk, lines
        number += len(lines)
        start, size = end, BLOCK_CHARS


def parse_rate_table(text: str, name: str, rate_unit: str = "deg/s",
                     output_unit: str | None = None) -> RateTable:
    """Parse the text of a rate table named ``name`` (for messages), block by block: a block
    of plain rows at once, any other line by line; every bad cell reported, located."""
    unit = rate_units.canonical_unit(rate_unit)
    label = output_unit_label(output_unit)
    table = _Table(name, text.count("\n") + 1)
    for first, chunk, lines in _blocks(text):
        if not table.quick(chunk, lines, first):
            table.careful(lines, first)
    table.finish()
    header = table.header
    assert header is not None
    axes = tuple(i for i in (1, 2) if f"rate_x{i}" in header.columns)
    unit_lines, columns = table.grouped()  # per unit: its line numbers, its values
    cross = [np.stack([columns[f"rate_x{i}"][k] for i in axes], axis=1) if axes else None
             for k in range(len(unit_lines))]
    return RateTable(
        file=name,
        rate_unit=unit,
        output_unit=label,
        units=tuple(table.units),
        rate=tuple(columns["rate"]),
        output=tuple(columns["output"]),
        cross=tuple(cross),
        cross_axes=axes,
        lines=tuple(unit_lines),
        unit_column="unit" in header.columns,
    )
