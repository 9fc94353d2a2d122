"""docs/rate-table.md shows gyrovib's own output.

Each ``$ gyrovib ...`` console block is what the command prints at 100 columns;
a line ``...`` in a block stands for lines left out (the pieces between must
appear in that order, the first at the start and the last at the end). The
``>>>`` examples run as doctests from the root of the tree, and the ``text``
block is the head of the bundled table. When the example data change,
regenerate the page's blocks.
"""

from __future__ import annotations

import doctest
import os
import re
import subprocess
import sys

import pytest

from tests.docpages import ROOT, assert_shows, console_blocks, run_shown

PAGE = ROOT / "docs" / "rate-table.md"


def test_the_page_has_its_examples() -> None:
    commands = [c for c, _ in console_blocks(PAGE)]
    assert any(c.startswith("gyrovib fit") and "-o -" not in c for c in commands)
    assert any(c.startswith("gyrovib fit") and c.endswith("-o -") for c in commands)
    # the page ends with the purchase decision: the lot judged by its yield
    assert any(c.startswith("gyrovib select") and "--yield" in c for c in commands)


def test_the_quoted_rms_yield_is_the_output() -> None:
    """Section 4 quotes the lot's RMS-test yield from `--format json`."""
    import json

    env = {**os.environ, "NO_COLOR": "1"}
    done = subprocess.run(
        [sys.executable, "-m", "gyrovib", "select", "docs/examples/rate-table-gx100.gyrovib.yaml",
         "docs/examples/rotor-tone.gyrovib.yaml", "--budget", "36deg/h", "--criterion", "rms",
         "--yield", "0.99", "--format", "json"],
        cwd=ROOT, capture_output=True, text=True, env=env, timeout=120, check=False)
    entry = next(s for s in json.loads(done.stdout)["sensors"]
                 if s["sensor"] == "lot-rate-table-gx100")["profiles"][0]["yield"]
    text = " ".join(PAGE.read_text(encoding="utf-8").split())
    low, high = (f"{v:.4f}" for v in entry["interval"])
    assert (f'"yield": {{"value": {entry["value"]}, "method": "monte-carlo", "interval": '
            f'[{low}…, {high}…], "draws": 100000}}') in text


@pytest.mark.parametrize(("command", "shown"), console_blocks(PAGE))
def test_console_block_is_the_output(command: str, shown: str) -> None:
    assert_shows(PAGE, command, shown, run_shown(command, codes=(0,)))


def test_python_examples_run(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(ROOT)
    failed, attempted = doctest.testfile(str(PAGE), module_relative=False, verbose=False,
                                         optionflags=doctest.NORMALIZE_WHITESPACE)
    assert attempted >= 10
    assert failed == 0


def test_the_table_head_is_the_file() -> None:
    block = re.search(r"```text\n(.*?)\.\.\.\n```", PAGE.read_text(encoding="utf-8"), re.S)
    assert block
    shown = block.group(1)
    data = (ROOT / "docs" / "examples" / "rate-table-gx100.csv").read_text(encoding="utf-8")
    assert data.startswith(shown)
