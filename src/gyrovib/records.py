"""A result's records declared once: its columns in order, each with its unit and how to
read it from one row; and the pandas DataFrame of them (optional extra ``gyrovib[pandas]``).

A result that declares its columns (:class:`Column`) gets its CSV
(:func:`gyrovib.render.formats.csv_of`), its JSON entries
(:func:`gyrovib.render.formats.json_of`, :func:`~gyrovib.render.formats.json_text`) and
its DataFrame (:func:`frame_of`) from the same tuple, so a column added, removed or moved
changes them alike. pandas is imported only when a frame is built.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace
from typing import Any, Generic, TypeVar

from gyrovib._version import __version__
from gyrovib.errors import GyrovibError

MISSING_PANDAS = "DataFrames need pandas, which is not installed: pip install 'gyrovib[pandas]'"

Row = TypeVar("Row")


class MissingDependency(GyrovibError, ImportError):
    """An optional dependency is not installed (the message names the extra)."""


@dataclass(frozen=True)
class Column(Generic[Row]):
    """One column of a result's records: its ``name`` (the CSV header, the DataFrame
    column), its ``unit`` (``None``: a name, a count, a flag) and ``value``, how to read it
    from one row (``None``: unknown, written empty in CSV, kept as None in a frame).
    ``skip``: the outputs that leave it out, among ``csv``, ``frame`` and ``json`` (a list
    or a text the CSV's documented header does not carry; what only the JSON has, as a
    row's warnings). ``cell``: how the CSV
    writes the value, where it differs from the frame (:func:`known`: a non-finite number
    empty). ``key``: where the JSON keeps it, a path of keys joined by dots (a number
    part: the place in a list, ``rate.0``); None: under its name. ``only``: the rows
    whose JSON has the key (a spec-form row's envelope, a lot's ``lot_mean``); None:
    every row. The JSON writes NaN (unknown) as null, and an infinity too (an unbounded
    figure) unless ``finite``: then an infinity is an overflow, which the JSON refuses
    (ValueError) rather than write as a number it is not. ``blank``: the rows whose CSV
    cell is empty whatever the value (a check the CSV does not make on that row, where
    the frame and the JSON hold its figures); None: none. ``many``: every value of a list
    of rows at once, for the fast writers (:func:`columns_of`,
    :func:`gyrovib.render.formats.json_text`); it must read what ``value`` reads (made
    from the same data: a test compares them), and without it each row is read alone.
    A nested JSON (a mission row, a select sensor) is declared in its order:
    ``csv_after``, the column the CSV and the frame put this one after; ``json_value``,
    the JSON's own reading of the row (a 0-based index, a list the CSV joins); ``each``,
    the columns of the sub-records a value lists (a row's segments, a sensor's profiles;
    :func:`flattened`: their table)."""

    name: str
    unit: str | None
    value: Callable[[Row], Any]
    skip: tuple[str, ...] = ()
    cell: Callable[[Any], Any] | None = None
    key: str | None = None
    only: Callable[[Row], bool] | None = None
    finite: bool = False
    many: Callable[[Sequence[Row]], Sequence[Any]] | None = None
    blank: Callable[[Row], bool] | None = None
    csv_after: str | None = None
    json_value: Callable[[Row], Any] | None = None
    each: tuple[Column[Any], ...] | None = None


def known(value: float) -> float | None:
    """A finite number as it is, a non-finite one as None (unknown: an empty CSV cell)."""
    return value if math.isfinite(value) else None


def written(columns: Sequence[Column[Row]], output: str) -> tuple[Column[Row], ...]:
    """The columns ``output`` (``csv``, ``frame``, ``json``) has, in its order: the
    declaration's, but in the CSV and the frame a column with ``csv_after`` right after
    that column, several after one in the declaration's order; the target may itself be
    placed by its ``csv_after``, declared later (ValueError naming both where the output
    lacks that column)."""
    shown = [c for c in columns if output not in c.skip]
    if output == "json" or all(c.csv_after is None for c in shown):
        return tuple(shown)
    placed = [c for c in shown if c.csv_after is None]
    behind: dict[str, str] = {}  # a target → the last column placed behind it
    waiting = [c for c in shown if c.csv_after is not None]
    while waiting:  # a target itself placed by csv_after, later in the declaration: again
        left = []
        for c in waiting:
            target = str(c.csv_after)
            at = behind.get(target, target)
            if at not in names(placed):
                left.append(c)
                continue
            placed.insert(names(placed).index(at) + 1, c)
            behind[target] = c.name
        if len(left) == len(waiting):
            raise ValueError(f"column {left[0].name!r} is declared after "
                             f"{left[0].csv_after!r}, which the {output} does not have")
        waiting = left
    return tuple(placed)


def flattened(columns: Sequence[Column[Any]]) -> tuple[Column[Any], ...]:
    """The records of rows that list sub-records (a column with ``each``) as one table,
    a line per sub-record, whose row's first item is its parent's row: the parent's
    columns read there, the sub-records' in place of the listing column."""
    return tuple(sub for c in columns for sub in c.each or (_at_parent(c),))


def _at_parent(column: Column[Any]) -> Column[Any]:
    """The column read at a sub-record's row: at its first item, its parent's row."""
    return replace(column, value=lambda row: column.value(row[0]), many=None)


def names(columns: Sequence[Column[Any]]) -> tuple[str, ...]:
    """The columns' names, in order."""
    return tuple(c.name for c in columns)


def records(columns: Sequence[Column[Row]], rows: Iterable[Row]) -> list[list[Any]]:
    """Every row's values, in the columns' order."""
    return [[c.value(row) for c in columns] for row in rows]


def pandas() -> Any:
    """The pandas module, or :class:`MissingDependency` naming the extra to install."""
    try:
        # lazy: pandas is optional (pip install 'gyrovib[pandas]')
        import pandas
    except ImportError:
        raise MissingDependency(MISSING_PANDAS) from None
    return pandas


def dataframe(columns: dict[str, Any], attrs: dict[str, Any]) -> Any:
    """A DataFrame of ``columns`` (name → values, in order), with the tool, its version
    and ``attrs`` in ``frame.attrs``."""
    frame = pandas().DataFrame(columns)
    frame.attrs.update({"tool": "gyrovib", "version": __version__, **attrs})
    return frame


def values_of(column: Column[Row], rows: Sequence[Row]) -> Sequence[Any]:
    """The column's value at every row, in order (at once where it can: ``many``, which
    may give an array)."""
    return list(map(column.value, rows)) if column.many is None else column.many(rows)


def columns_of(columns: Sequence[Column[Row]],
               rows: Sequence[Row]) -> dict[str, Sequence[Any]]:
    """Every column's values over the rows, by name, in the columns' order."""
    return {c.name: values_of(c, rows) for c in columns}


def frame_of(columns: Sequence[Column[Row]], rows: Sequence[Row],
             attrs: dict[str, Any] | None = None) -> Any:
    """The DataFrame of the records: one row per row, the columns in order; with
    ``attrs`` (the document-level fields), :func:`dataframe`'s ``frame.attrs``."""
    shown = written(columns, "frame")
    if attrs is None:
        return pandas().DataFrame(columns_of(shown, rows))
    return dataframe(columns_of(shown, rows), attrs)
