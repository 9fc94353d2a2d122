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
    if isinstance(value, tuple):
        return "; ".join(value)
    return value


def csv_of(columns: Sequence[Column[Row]], rows: Iterable[Row]) -> str:
    """CSV of the records: the columns' names as the header, one line per row (the
    frame-only columns left out)."""
    written = in_csv(columns)
    return csv_text(names(written), ([_cell(v) for v in values]
                                     for values in records(written, rows)))
