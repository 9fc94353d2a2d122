"""Reading a rate-table CSV (INTERFACE.md, "Rate-table input").

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
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from gyrovib import units as rate_units
from gyrovib.core.transmissibility import FloatArray
from gyrovib.errors import GyrovibError, Problem
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
        raise RateTableError(f"--output-unit {text!r}: give a short unit name such as mV, "
                             "V, LSB or a rate unit")
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
    return parse_rate_table(_decode(raw, name), name, rate_unit, output_unit)


def read_rate_table_bytes(raw: bytes, name: str, rate_unit: str = "deg/s",
                          output_unit: str | None = None) -> RateTable:
    """:func:`parse_rate_table` of raw bytes (standard input), checked as a file is."""
    return parse_rate_table(_decode(raw, name), name, rate_unit, output_unit)


def _unit_name(name: str) -> str:
    """The one unit of a table without a ``unit`` column: the file's stem as an id."""
    stem = Path(name).stem if name != STDIN_NAME else "unit"
    cleaned = re.sub(r"[^A-Za-z0-9._-]+", "-", stem).strip("-.") or "unit"
    return cleaned[:200]


def parse_rate_table(text: str, name: str, rate_unit: str = "deg/s",
                     output_unit: str | None = None) -> RateTable:
    """Parse the text of a rate table named ``name`` (for messages)."""
    unit = rate_units.canonical_unit(rate_unit)
    label = output_unit_label(output_unit)
    problems: list[Problem] = []
    header: list[tuple[str, int]] | None = None
    header_line = 0
    columns: dict[str, int] = {}
    rows: dict[str, list[tuple[int, list[float]]]] = {}
    dropped = 0

    def problem(message: str, line: int, column: int | None = None) -> None:
        nonlocal dropped
        if len(problems) < MAX_PROBLEMS:
            problems.append(Problem(message, name, line, column))
        else:
            dropped += 1

    numeric: list[str] = []
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        cells = _fields(line)
        if cells is None:
            problem("a quoted cell is not closed on its line", number, 1)
            continue
        if header is None:
            header, header_line = cells, number
            for k, (title, col) in enumerate(cells):
                key = title.strip().lower()
                if key in columns:
                    problem(f"column {title!r} appears twice in the header", number, col)
                elif key not in COLUMNS:
                    problem(f"unknown column {title!r}; the columns are "
                            f"{', '.join(COLUMNS)} (unit, rate_x1, rate_x2 optional)",
                            number, col)
                else:
                    columns[key] = k
            missing = [c for c in REQUIRED if c not in columns]
            if missing:
                problem(f"the header has no {' or '.join(repr(c) for c in missing)} column "
                        f"(found {', '.join(repr(t) for t, _ in cells)}); the first line "
                        "that is not a comment names the columns", number, 1)
            if problems:
                raise RateTableError(problems)
            numeric = [c for c in COLUMNS[1:] if c in columns]
            continue
        if len(cells) != len(header):
            problem(f"{len(cells)} cell{'s' if len(cells) != 1 else ''} in this row, "
                    f"{len(header)} columns in the header (line {header_line})", number, 1)
            continue
        values: list[float] = []
        ok = True
        for key in numeric:
            cell, col = cells[columns[key]]
            try:
                value = float(cell)
            except ValueError:
                what = "empty" if not cell else f"{cell!r} is not a number"
                problem(f"{key}: {what}", number, col)
                ok = False
                continue
            if not math.isfinite(value):
                problem(f"{key}: {cell!r} is not a finite number", number, col)
                ok = False
                continue
            values.append(value)
        if "unit" in columns:
            who, col = cells[columns["unit"]]
            if not _ID.match(who):
                problem(f"unit: {who!r} is not a unit name (letters, digits, '.', '_', '-'; "
                        "it becomes the sensor's id)" if who else "unit: empty", number, col)
                ok = False
        else:
            who = _unit_name(name)
        if ok:
            rows.setdefault(who, []).append((number, values))
    if header is None:
        problem("no header row: the table is empty (a header such as 'unit,rate,output' "
                "and one row per measurement)", 1, None)
    elif not rows and not problems:
        problem("no data rows after the header", header_line, None)
    if dropped:
        problems.append(Problem(f"... and {dropped} more problem{'s' if dropped > 1 else ''}",
                                name))
    if problems:
        raise RateTableError(problems)
    axes = tuple(i for i in (1, 2) if f"rate_x{i}" in columns)
    at = {key: k for k, key in enumerate(numeric)}
    grouped = [(np.array([n for n, _ in r], dtype=np.int64), np.array([v for _, v in r]))
               for r in rows.values()]
    return RateTable(
        file=name,
        rate_unit=unit,
        output_unit=label,
        units=tuple(rows),
        rate=tuple(v[:, at["rate"]] for _, v in grouped),
        output=tuple(v[:, at["output"]] for _, v in grouped),
        cross=tuple(v[:, [at[f"rate_x{i}"] for i in axes]] if axes else None
                    for _, v in grouped),
        cross_axes=axes,
        lines=tuple(n for n, _ in grouped),
        unit_column="unit" in columns,
    )
