"""The generic writers over a result's declared records (:mod:`gyrovib.records`): CSV and
the JSON entries; one writer for every result that declares its columns, so its header,
cells and JSON keys cannot drift from its DataFrame. The human tables likewise: a
result's Markdown and terminal table come from one declaration of their cells
(:class:`Cell`), and JUnit XML from its verdict rows (:func:`junit_of`)."""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from gyrovib.records import Column, names, records, values_of, written
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
    in_csv = written(columns, "csv")
    default = _joined if title_flags else _cell
    cells = [default if c.cell is None else c.cell for c in in_csv]
    shown = [c if c.blank is None else _blanked(c) for c in in_csv]
    return csv_text(names(in_csv), ([cell(v) for cell, v in zip(cells, values, strict=True)]
                                     for values in records(shown, rows)))


def _blanked(column: Column[Row]) -> Column[Row]:
    """The column as the CSV reads it: None (an empty cell) on its ``blank`` rows."""
    blank, read = column.blank, column.value
    assert blank is not None
    return replace(column, value=lambda row: None if blank(row) else read(row))


def _json_value(value: Any, finite: bool) -> Any:
    """A value as JSON writes it: a float that is not finite (unknown, unbounded) as null;
    with ``finite`` an infinity stays, for the JSON encoder to refuse (an overflow)."""
    if not isinstance(value, float) or (finite and value == value):
        return value
    return number(value)


def json_of(columns: Sequence[Column[Any]], rows: Iterable[Any]) -> list[dict[str, Any]]:
    """One JSON object per row: each column's value at its key path (:attr:`Column.key`,
    else its name; a column that skips ``json`` left out, and one with ``only`` on the
    rows it does not hold for), nested objects and lists made in the columns' order; the
    value read by ``json_value`` where the column has one, a list of sub-records
    (``each``) written as their objects."""
    shown = written(columns, "json")
    paths = [(c.key or c.name).split(".") for c in shown]
    out = []
    for row in rows:
        entry: dict[str, Any] = {}
        for c, path in zip(shown, paths, strict=True):
            if c.only is not None and not c.only(row):
                continue
            node: Any = entry
            for part, after in itertools.pairwise(path):
                node = node.setdefault(part, [] if after.isdigit() else {})
            value = (c.value if c.json_value is None else c.json_value)(row)
            value = _json_value(value, c.finite) if c.each is None else json_of(c.each, value)
            if path[-1].isdigit():
                node.append(value)
            else:
                node[path[-1]] = value
        out.append(entry)
    return out


# ------------------------------------------------------------------ the fast JSON text

#: Rows encoded at a time by :func:`json_text`: bounds the memory of the encoded cells.
_BLOCK = 4096

#: A key of the entries: its name, its columns (in the order its text writes them) and
#: the text of its value (``%s`` for each column).
_Key = tuple[str, list[int], str]


def json_text(columns: Sequence[Column[Row]], rows: Sequence[Row]) -> str:
    """The text ``json.dumps(json_of(columns, rows), allow_nan=False)`` writes, without a
    dict per row: each column is encoded at once (``float.__repr__`` is what the json
    encoder writes for a float), the rows filled into one template made from the key
    paths, a block of rows at a time. A key on some rows only (``only``) fills a slot of
    its own with its text, or nothing; every column under one key shares it, and the
    first key is on every row. A nested document (``json_value``, ``each``) is written
    from :func:`json_of`."""
    shown = written(columns, "json")
    if any(c.json_value is not None or c.each is not None for c in shown):
        import json  # a nested document: one dict per row

        return json.dumps(json_of(columns, rows), allow_nan=False)
    keys = _keys(shown)
    template = "{" + "".join(("%s" if shown[found[0]].only is not None
                              else (", " if k else "") + _key_text(name, text))
                             for k, (name, found, text) in enumerate(keys)) + "}"
    blocks = []
    seen: dict[Any, str] = {}
    for start in range(0, len(rows), _BLOCK):
        block = rows[start:start + _BLOCK]
        cells: list[list[str]] = []
        for name, found, text in keys:
            held = [shown[k] for k in found]
            if held[0].only is None:
                cells += [_encoded(values_of(c, block), c.finite, seen) for c in held]
            else:
                cells.append(_slot(", " + _key_text(name, text), held, block, seen))
        blocks.append(", ".join(map(template.__mod__, zip(*cells, strict=True))))
    return "[" + ", ".join(blocks) + "]"


def _key_text(name: str, text: str) -> str:
    """``"name": text``, the key as json writes it, a ``%`` in it doubled."""
    import json  # not at import time: the tables do without it

    return json.dumps(name).replace("%", "%%") + ": " + text


def _keys(shown: Sequence[Column[Row]]) -> list[_Key]:
    """The entries' keys in order, each with its columns and its text (``%s`` for a
    column); raises ValueError where a key is on some rows only but not all its columns
    say so alike, or where the first key is."""
    tree: dict[str, Any] = {}
    for k, c in enumerate(shown):
        path = (c.key or c.name).split(".")
        node = tree
        for part in path[:-1]:
            node = node.setdefault(part, {})
        node[path[-1]] = k
    keys: list[_Key] = []
    for name, node in tree.items():
        found: list[int] = []
        text = _node_text(node, found)
        if len({id(shown[k].only) for k in found}) != 1 or (
                not keys and shown[found[0]].only is not None):
            raise ValueError(f"JSON key {name!r}: its columns disagree on the rows it is on,"
                             " or the first key is not on every row")
        keys.append((name, found, text))
    return keys


def _node_text(node: Any, found: list[int]) -> str:
    """The text of a value of the entries: ``%s`` for a column (its index appended to
    ``found``), an object, or a list where the keys are numbers."""
    if isinstance(node, int):
        found.append(node)
        return "%s"
    parts = [_node_text(child, found) for child in node.values()]
    if all(key.isdigit() for key in node):
        return "[" + ", ".join(parts) + "]"
    return "{" + ", ".join(_key_text(key, part) for key, part in
                           zip(node, parts, strict=True)) + "}"


def _slot(text: str, held: Sequence[Column[Row]], block: Sequence[Row],
          seen: dict[Any, str]) -> list[str]:
    """The text of a key on some rows only (``text``: ``, "key": …``), per row: filled
    where its ``only`` holds, else empty."""
    only = held[0].only
    assert only is not None
    at = [k for k, row in enumerate(block) if only(row)]
    out = [""] * len(block)
    if at:
        chosen = [block[k] for k in at]
        values = zip(*(_encoded(values_of(c, chosen), c.finite, seen) for c in held),
                     strict=True)
        for k, cells in zip(at, values, strict=True):
            out[k] = text % cells
    return out


def _encoded(values: Any, finite: bool, seen: dict[Any, str]) -> list[str]:
    """Each value as the json encoder writes it (``allow_nan=False``): a float as its repr
    (what the encoder writes), NaN as null and an infinity as null, or refused with
    ``finite``. A column of floats is encoded at once (a column of +0.0, a term a
    catalogue's profiles do not excite, as one text); ``seen``: the texts of the names
    already encoded (:func:`_encoded_any`)."""
    import numpy as np  # not at import time: the tables do without it

    if isinstance(values, np.ndarray) and values.dtype == np.float64:
        array = values
    elif isinstance(values, np.ndarray):
        return _encoded(values.tolist(), finite, seen)
    elif set(map(type, values)) == {float}:
        array = np.array(values, dtype=float)
    else:
        return _encoded_any(values, finite, seen)
    if not array.any() and not np.signbit(array).any():
        return ["0.0"] * len(array)  # all +0.0 (-0.0 is written apart)
    bits = array.view(np.int64)
    if len(np.unique(bits[:_SAMPLE])) * 2 <= min(len(bits), _SAMPLE):
        # a column that repeats its values (a profile's rate, a term many sensors lack):
        # each distinct value written once, told apart by its bits (0.0 from -0.0)
        distinct, inverse = np.unique(bits, return_inverse=True)
        texts = _floats_text(distinct.view(np.float64), finite)
        return list(np.array(texts, dtype=object)[inverse.ravel()].tolist())
    return _floats_text(array, finite)


#: The values of a column :func:`_encoded` looks at to tell whether it repeats them.
_SAMPLE = 256


def _floats_text(array: Any, finite: bool) -> list[str]:
    """Each float of ``array`` as the json encoder writes it (:func:`_float_text`)."""
    import numpy as np  # not at import time: the tables do without it

    if np.isfinite(array).all():
        return list(map(float.__repr__, array.tolist()))
    return [_float_text(v, finite) for v in array.tolist()]


def _float_text(value: float, finite: bool) -> str:
    if value != value:
        return "null"
    if math.isinf(value):
        if finite:
            raise ValueError("Out of range float values are not JSON compliant")
        return "null"
    return float.__repr__(value)


#: The kinds of value :func:`_encoded_any` encodes once per distinct value.
_NAMES = {str, bool, type(None), tuple}


def _encoded_any(values: list[Any], finite: bool, seen: dict[Any, str]) -> list[str]:
    """:func:`_encoded` of a column that is not all floats. A column of texts, flags and
    tuples of texts (a row's warnings) is encoded a distinct value at a time, kept in
    ``seen`` for the next block of rows (none of these equals another kind's value, as 1
    would equal True)."""
    import json  # not at import time: the tables do without it

    import numpy as np

    if set(map(type, values)) <= _NAMES:
        try:
            distinct = set(values)
        except TypeError:  # a tuple that holds a list or a dict: encoded one by one
            distinct = set()
        if distinct and all(type(x) is str for v in distinct if type(v) is tuple
                            for x in v):
            seen.update((v, json.dumps(v)) for v in distinct if v not in seen)
            return list(map(seen.__getitem__, values))
    # a float of any kind (numpy's scalars too) as the column of floats writes it: NaN
    # null, an infinity null or refused, never json.dumps' refusal of NaN
    return [_float_text(float(v), finite) if isinstance(v, (float, np.floating))
            else json.dumps(v, allow_nan=False) for v in values]


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
