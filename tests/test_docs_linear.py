"""docs/linear-vibration.md shows gyrovib's own output: each ``$ gyrovib ...`` console
block is what the command prints (the conventions and the tool that regenerates the
blocks: tests/docpages.py)."""

from __future__ import annotations

import pytest

from tests.docpages import ROOT, assert_shows, console_blocks, run_shown

PAGE = ROOT / "docs" / "linear-vibration.md"


def test_the_page_has_its_examples() -> None:
    commands = [c for c, _ in console_blocks(PAGE)]
    assert any(c.startswith("gyrovib analyze") for c in commands)
    assert any(c.startswith("gyrovib bounds") for c in commands)
    assert any(c.startswith("gyrovib select") for c in commands)


@pytest.mark.parametrize(("command", "shown"), console_blocks(PAGE))
def test_console_block_is_the_output(command: str, shown: str) -> None:
    assert_shows(PAGE, command, shown, run_shown(command))
