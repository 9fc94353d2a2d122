"""docs/linear-vibration.md shows gyrovib's own output: each ``$ gyrovib ...`` console
block is what the command prints at 100 columns (a block ending in ``...`` is the
beginning of it). When the bundled catalogues change, regenerate the page's blocks."""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGE = ROOT / "docs" / "linear-vibration.md"


def console_blocks() -> list[tuple[str, str]]:
    blocks = re.findall(r"```console\n\$ (gyrovib [^\n]*)\n(.*?)```",
                        PAGE.read_text(encoding="utf-8"), flags=re.S)
    return [(command, output) for command, output in blocks]


def test_the_page_has_its_examples() -> None:
    commands = [c for c, _ in console_blocks()]
    assert any(c.startswith("gyrovib analyze") for c in commands)
    assert any(c.startswith("gyrovib bounds") for c in commands)
    assert any(c.startswith("gyrovib select") for c in commands)


@pytest.mark.parametrize(("command", "shown"), console_blocks())
def test_console_block_is_the_output(command: str, shown: str) -> None:
    env = {**os.environ, "COLUMNS": "100", "NO_COLOR": "1"}
    env.pop("FORCE_COLOR", None)
    done = subprocess.run([sys.executable, "-m", "gyrovib", *shlex.split(command)[1:]],
                          cwd=ROOT, capture_output=True, text=True, env=env, timeout=120,
                          check=False)
    assert done.returncode in (0, 1), done.stderr
    if shown.endswith("...\n"):
        head = shown[: -len("...\n")]
        assert done.stdout.startswith(head), f"regenerate {PAGE.name}: {command}"
    else:
        assert done.stdout == shown, f"regenerate {PAGE.name}: {command}"
