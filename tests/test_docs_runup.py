"""docs/runup.md shows gyrovib's own output: each ``$ gyrovib ...`` console block is what
the command prints (conventions and the regenerating tool: tests/docpages.py), on the
synthetic run-up that tools/make_runup_log.py writes; and the page's step durations are
its formula's."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.docpages import ROOT, assert_shows, console_blocks, run_shown

PAGE = ROOT / "docs" / "runup.md"


def test_the_page_has_its_examples() -> None:
    commands = [c for c, _ in console_blocks(PAGE)]
    assert any(c.startswith("gyrovib runup") and "--sensor" in c for c in commands)
    assert any(c.startswith("gyrovib runup") and "-o -" in c for c in commands)


@pytest.mark.parametrize(("command", "shown"), console_blocks(PAGE))
def test_console_block_is_the_output(command: str, shown: str) -> None:
    assert_shows(PAGE, command, shown, run_shown(command))


def test_the_example_run_up_is_the_scripts() -> None:
    done = subprocess.run([sys.executable, str(ROOT / "tools" / "make_runup_log.py"),
                           "--check"], check=False)
    assert done.returncode == 0, "regenerate: python tools/make_runup_log.py"


@pytest.mark.parametrize(("arw", "shift", "shown"), [
    (0.1, 0.001, 50), (0.1, 0.003, 6), (0.3, 0.001, 450), (0.3, 0.003, 50), (0.3, 0.01, 5),
    (1.0, 0.001, 5000), (1.0, 0.003, 560), (1.0, 0.01, 50)])
def test_the_step_durations_are_the_formulas(arw: float, shift: float, shown: int) -> None:
    # T = 2·(k·N/Δ)² at k = 3, N in deg/√s = deg/√h / 60; the page rounds to 2 digits
    t = 2 * (3 * arw / 60 / shift) ** 2
    assert shown == pytest.approx(t, rel=0.12)
    assert f"{shown} s" in PAGE.read_text(encoding="utf-8")
