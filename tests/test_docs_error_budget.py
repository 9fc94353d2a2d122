"""docs/error-budget.md shows gyrovib's own output: each ``$ gyrovib ...`` console block is
what the command prints (conventions and the regenerating tool: tests/docpages.py), on the
synthetic static log that tools/make_static_log.py writes."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.docpages import ROOT, assert_shows, console_blocks, run_shown

PAGE = ROOT / "docs" / "error-budget.md"


def test_the_page_has_its_examples() -> None:
    commands = [c for c, _ in console_blocks(PAGE)]
    assert any(c.startswith("gyrovib allan") for c in commands)
    assert any(c.startswith("gyrovib mission") and "--coverage" in c for c in commands)


@pytest.mark.parametrize(("command", "shown"), console_blocks(PAGE))
def test_console_block_is_the_output(command: str, shown: str) -> None:
    assert_shows(PAGE, command, shown, run_shown(command))


def test_the_static_log_is_the_scripts() -> None:
    done = subprocess.run([sys.executable, str(ROOT / "tools" / "make_static_log.py"),
                           "--check"], check=False)
    assert done.returncode == 0, "regenerate: python tools/make_static_log.py"
