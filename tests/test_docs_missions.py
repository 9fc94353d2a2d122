"""docs/missions.md shows gyrovib's own output: each ``$ gyrovib ...`` console block is
what the command prints (the conventions and the tool that regenerates the blocks:
tests/docpages.py)."""

from __future__ import annotations

import pytest

from tests.docpages import ROOT, assert_shows, console_blocks, run_shown

PAGE = ROOT / "docs" / "missions.md"


def test_the_page_has_its_examples() -> None:
    commands = [c for c, _ in console_blocks(PAGE)]
    assert any(c.startswith("gyrovib mission") and "--angle-budget" in c for c in commands)
    assert any(c.startswith("gyrovib select --mission") for c in commands)


@pytest.mark.parametrize(("command", "shown"), console_blocks(PAGE))
def test_console_block_is_the_output(command: str, shown: str) -> None:
    assert_shows(PAGE, command, shown, run_shown(command))


def test_the_segment_table_is_the_json() -> None:
    """The page's per-segment table for the SCH16T on Z, and its sum, from the JSON."""
    import json

    from tests.conftest import invoke

    doc = json.loads(invoke("mission", "--sensor", "sch16t", "--format", "json").stdout)
    (row,) = [r for r in doc["mission"] if r["axis"] == "Z"]
    text = PAGE.read_text(encoding="utf-8")
    for k, s in enumerate(row["segments"]):
        shown = f"| {k + 1} | {s['profile']} | {s['duration']:g} | "
        assert shown in text
        assert f"| {s['total']:.4g} | {s['duration'] * s['total']:.3f} |" in text  # deg/s × s
    summed = sum(s["duration"] * s["total"] for s in row["segments"])
    assert f"Their sum is {summed:.2f} deg" in text
    assert f"the worst angle is {row['angle']:.2f} deg" in text
