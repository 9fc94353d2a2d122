"""The generic writers over a result's declared records (:mod:`gyrovib.records`): CSV and
the JSON entries; one writer for every result that declares its columns, so its header,
cells and JSON keys cannot drift from its DataFrame. The human tables likewise: a
result's Markdown and terminal table come from one declaration of their cells
(:class:`Cell`), and JUnit XML from its verdict rows (:func:`junit_of`)."""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from gyrovib.records import Column, in_csv, names, records, written
from gyrovib.render.common import csv_text, fmt, markdown_table, number

if TYPE_CHECKING:  # at run time rich is imported by table_of
    from rich.console import JustifyMethod
    from rich.table import Table

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


# ------------------------------------------------------------------ the human tables


@dataclass(frozen=True)
class Cell(Generic[Row]):
    """One column of a result's human table, declared once for its Markdown and its
    terminal table: the heading ``title``, how one row's cell is written (``text``) and
    how the terminal table draws it (``justify``, ``no_wrap``, ``style``). ``of``: the
    name of the record (:class:`~gyrovib.records.Column`) the cell shows; without
    ``text``, the cell is that record's value as :func:`known` writes it (a test checks
    such cells against the records)."""

    title: str
    text: Callable[[Row], str] | None = None
    justify: JustifyMethod = "left"
    of: str | None = None
    no_wrap: bool = True
    style: str | None = None


def known(value: Any) -> str:
    """A value as the tables write it: a text as it is, a number as
    :func:`~gyrovib.render.common.fmt` writes it, '?' where it is unknown (None or NaN:
    never shown as 0)."""
    if isinstance(value, str):
        return value
    return "?" if value is None or value != value else fmt(value)


def cell_texts(cells: Sequence[Cell[Row]], rows: Iterable[Row],
               records: Sequence[Column[Row]] = ()) -> Iterator[list[str]]:
    """Every row's cells, in the cells' order; a cell without ``text`` writes its
    record's value (``of``, looked up in ``records``) with :func:`known`."""
    by_name = {c.name: c.value for c in records}
    writers = [c.text or _record_text(by_name[c.of or ""]) for c in cells]
    return ([text(row) for text in writers] for row in rows)


def _record_text(read: Callable[[Row], Any]) -> Callable[[Row], str]:
    """A record's value as the tables write it (:func:`known`)."""
    return lambda row: known(read(row))


def markdown_of(cells: Sequence[Cell[Row]], rows: Iterable[Row],
                records: Sequence[Column[Row]] = ()) -> str:
    """A GitHub-flavoured Markdown table: the cells' titles as its header, one line per
    row (:func:`cell_texts`)."""
    return markdown_table([c.title for c in cells], cell_texts(cells, rows, records))


def table_of(cells: Sequence[Cell[Row]], rows: Iterable[Row],
             records: Sequence[Column[Row]] = (), **table: Any) -> Table:
    """The terminal table (rich) of the same cells: their titles, alignments and texts;
    ``table``: the rich ``Table``'s keywords (title, …), a bold header unless given."""
    # lazy: rich only draws tables; csv and json output never load it
    from rich.table import Table

    out = Table(**{"header_style": "bold", **table})
    for c in cells:
        out.add_column(c.title, justify=c.justify, no_wrap=c.no_wrap, style=c.style)
    for texts in cell_texts(cells, rows, records):
        out.add_row(*texts)
    return out


# ------------------------------------------------------------------ JUnit


#: One JUnit test case: its class name (the sensor), its name, the text of its
#: ``system-out``, and its failure (type, message, text) or None when it passes.
Case = tuple[str, str, str, tuple[str, str, str] | None]


def junit_of(name: str, title: str, cases: Sequence[Case]) -> str:
    """JUnit XML of verdict rows: one ``testsuite`` named ``title`` in ``testsuites``
    named ``name``, one ``testcase`` per case, its ``failure`` (if any) first."""
    # lazy: only the JUnit format
    import xml.etree.ElementTree as ET

    n_fail = str(sum(1 for case in cases if case[3] is not None))
    suites = ET.Element("testsuites", name=name, tests=str(len(cases)), failures=n_fail,
                        errors="0")
    suite = ET.SubElement(suites, "testsuite", name=title, tests=str(len(cases)),
                          failures=n_fail, errors="0", skipped="0")
    for classname, case_name, out, failed in cases:
        case = ET.SubElement(suite, "testcase", classname=classname, name=case_name, time="0")
        if failed is not None:
            kind, message, text = failed
            ET.SubElement(case, "failure", message=message, type=kind).text = text
        ET.SubElement(case, "system-out").text = out
    ET.indent(suites)
    return ET.tostring(suites, encoding="unicode", xml_declaration=True) + "\n"
