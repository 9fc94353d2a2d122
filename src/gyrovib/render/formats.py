"""The generic writers over a result's declared records (:mod:`gyrovib.records`): CSV now;
one writer for every result that declares its columns, so its header and cells cannot
drift from its DataFrame."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any, TypeVar

from gyrovib.records import Column, in_csv, names, records
from gyrovib.render.common import csv_text

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
