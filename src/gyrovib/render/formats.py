"""The generic writers over a result's declared records (:mod:`gyrovib.records`): CSV and
the JSON entries; one writer for every result that declares its columns, so its header,
cells and JSON keys cannot drift from its DataFrame."""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Sequence
from typing import Any, TypeVar

from gyrovib.records import Column, in_csv, names, records, written
from gyrovib.render.common import csv_text, number

Row = TypeVar("Row")


def _cell(value: Any) -> Any:
    """A value as a CSV cell: empty for unknown, ``true``/``false`` for a flag, a tuple of
    texts (a row's warnings) joined by ``; `` (floats are written with full precision by
    :func:`~gyrovib.render.common.csv_text`)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return _joined(value)


def _joined(value: Any) -> Any:
    """A tuple of texts joined by ``; ``; any other value as it is."""
    if isinstance(value, tuple):
        return "; ".join(value)
    return value


def csv_of(columns: Sequence[Column[Row]], rows: Iterable[Row], *,
           title_flags: bool = False) -> str:
    """CSV of the records: the columns' names as the header, one line per row (the
    frame-only columns left out). A flag is ``true``/``false``, or with ``title_flags``
    ``True``/``False`` (as ``bounds``, ``select`` and ``sweep`` have always written it)."""
    written = in_csv(columns)
    default = _joined if title_flags else _cell
    cells = [default if c.cell is None else c.cell for c in written]
    return csv_text(names(written), ([cell(v) for cell, v in zip(cells, values, strict=True)]
                                     for values in records(written, rows)))


def _json_value(value: Any) -> Any:
    """A value as JSON writes it: a float that is not finite (unbounded, unknown) as null."""
    return number(value) if isinstance(value, float) else value


def json_of(columns: Sequence[Column[Row]], rows: Iterable[Row]) -> list[dict[str, Any]]:
    """One JSON object per row: each column's value at its key path (:attr:`Column.key`,
    else its name; a column that skips ``json`` left out), nested objects and lists made
    in the columns' order."""
    shown = written(columns, "json")
    paths = [(c.key or c.name).split(".") for c in shown]
    out = []
    for values in records(shown, rows):
        entry: dict[str, Any] = {}
        for path, value in zip(paths, values, strict=True):
            node: Any = entry
            for part, after in itertools.pairwise(path):
                node = node.setdefault(part, [] if after.isdigit() else {})
            if path[-1].isdigit():
                node.append(_json_value(value))
            else:
                node[path[-1]] = _json_value(value)
        out.append(entry)
    return out
