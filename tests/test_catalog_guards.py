"""Hostile catalogues at the library level: nesting refused alike by libyaml and
PyYAML's pure-Python parser, and duplicate ids located in linear time, capped,
and reported next to other errors."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

from gyrovib.catalog import dialect, loader
from gyrovib.catalog.loader import CatalogError, load_catalog, parse_catalog
from tests.conftest import VALID

HEADER = "gyrovib: 1\n"

#: (id, text, expected line or None for any): deeper than MAX_DEPTH in every shape
DEEP = [
    ("flow", HEADER + "x: " + "[" * 20000 + "]" * 20000 + "\n", 2),
    ("block", HEADER + "x:\n" + "".join("  " * i + "- \n" for i in range(1, 80))
     + "  " * 80 + "- 1\n", None),
    ("compact", HEADER + "x:\n  " + "- " * 5000 + "1\n", 3),
    # with an anchor the node tree is composed: the pure-Python composer recurses per level
    ("anchored-flow", HEADER + "x: &a " + "[" * 3000 + "]" * 3000 + "\n", 2),
    ("anchored-block", HEADER + "y: &b 1\nx:\n"
     + "".join("  " * i + "- \n" for i in range(1, 80)) + "  " * 80 + "- 1\n", None),
]


@pytest.mark.parametrize("pure", [False, True], ids=["libyaml", "pure-python"])
@pytest.mark.parametrize(("text", "line"), [c[1:] for c in DEEP], ids=[c[0] for c in DEEP])
def test_deep_nesting_one_message_for_both_parsers(monkeypatch: pytest.MonkeyPatch, pure: bool,
                                                   text: str, line: int | None) -> None:
    if pure:  # PyYAML's own parser, as on a machine without libyaml
        monkeypatch.setattr(dialect, "Loader", dialect.loader_class(yaml.SafeLoader))
    with pytest.raises(CatalogError) as info:
        parse_catalog(text, "cat.yaml")
    (problem,) = info.value.problems
    assert problem.message.startswith(f"values are nested more than {dialect.MAX_DEPTH} levels")
    assert problem.file == "cat.yaml" and problem.line is not None and problem.column
    if line is not None:
        assert problem.line == line


def test_duplicate_ids_reported_next_to_other_errors() -> None:
    text = HEADER + ("sensors:\n  - id: s\n    coefficients: {k2: abc}\n"
                     "  - id: s\n    coefficients: {}\n")
    with pytest.raises(CatalogError) as info:
        parse_catalog(text, "cat.yaml")
    assert [str(p) for p in info.value.problems] == [
        "cat.yaml:4:24: sensor 's': coefficients.k2: must be a number, not the text 'abc'",
        "cat.yaml:5:9: duplicate sensor id 's' (first at cat.yaml:3)",
    ]


def test_duplicate_ids_across_files_next_to_other_errors(tmp_path: Path) -> None:
    one = tmp_path / "one.yaml"
    one.write_text(VALID)  # fog-a on line 5, cruise on line 22
    two = tmp_path / "two.yaml"
    two.write_text(HEADER + "units: {rate: furlong}\nsensors:\n  - id: fog-a\n"
                   "    coefficients: {}\n  - id: fog-a\n    coefficients: {}\n"
                   "profiles:\n  - id: cruise\n")
    with pytest.raises(CatalogError) as info:
        load_catalog([one, two])
    lines = [str(p) for p in info.value.problems]
    assert lines[0].startswith(f"{two}:2:15: units.rate: unknown rate unit 'furlong'"), lines
    assert sorted(lines[1:]) == sorted([
        f"{two}:6:9: duplicate sensor id 'fog-a' (first at {two}:4)",
        f"{two}:4:9: duplicate sensor id 'fog-a' (first at {one}:5)",
        f"{two}:9:9: duplicate profile id 'cruise' (first at {one}:22)",
    ])  # each clash once


@pytest.mark.parametrize(("name", "text", "repeats"), [
    # 3,000 repeats of one id: each located through one index of the file, not a re-parse
    ("repeats", HEADER + "sensors:\n" + "  - id: s\n    coefficients: {}\n" * 3000, 2999),
    # an 80 KB file of 20,000 aliases of one sensor
    ("aliases", HEADER + "sensors:\n  - &a {id: s, coefficients: {}}\n" + "  - *a\n" * 20000,
     20000),
    # the same, next to an error elsewhere in the file (the raw-data path): one more problem
    ("aliases-and-error", HEADER + "units: {rate: furlong}\nsensors:\n"
     "  - &a {id: s, coefficients: {}}\n" + "  - *a\n" * 20000, 20001),
])
def test_many_duplicates_are_linear_and_capped(tmp_path: Path, name: str, text: str,
                                               repeats: int) -> None:
    path = tmp_path / "cat.yaml"
    path.write_text(text)
    with pytest.raises(CatalogError) as info:
        load_catalog([path])
    lines = [str(p) for p in info.value.problems]
    assert len(lines) == loader.MAX_PROBLEMS + 1, lines[-3:]
    summary = re.fullmatch(rf"{re.escape(str(path))}: \.\.\. and (\d+) more problems", lines[-1])
    assert summary is not None, lines[-1]
    # every problem is counted: the shown ones and the summary add up
    assert len(lines) - 1 + int(summary.group(1)) == repeats
    assert all(re.match(rf"{re.escape(str(path))}:\d+:\d+: ", x) for x in lines[:-1])
