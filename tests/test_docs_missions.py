"""docs/missions.md shows gyrovib's own output: each ``$ gyrovib ...`` console block is
what the command prints at 100 columns. When the bundled catalogues change, regenerate
the page's blocks."""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGE = ROOT / "docs" / "missions.md"


def console_blocks() -> list[tuple[str, str]]:
    return re.findall(r"```console\n\$ (gyrovib [^\n]*)\n(.*?)```",
                      PAGE.read_text(encoding="utf-8"), flags=re.S)


def test_the_page_has_its_examples() -> None:
    commands = [c for c, _ in console_blocks()]
    assert any(c.startswith("gyrovib mission") and "--angle-budget" in c for c in commands)
    assert any(c.startswith("gyrovib select --mission") for c in commands)


@pytest.mark.parametrize(("command", "shown"), console_blocks())
def test_console_block_is_the_output(command: str, shown: str) -> None:
    env = {**os.environ, "COLUMNS": "100", "NO_COLOR": "1"}
    env.pop("FORCE_COLOR", None)
    done = subprocess.run([sys.executable, "-m", "gyrovib", *shlex.split(command)[1:]],
                          cwd=ROOT, capture_output=True, text=True, env=env, timeout=120,
                          check=False)
    assert done.returncode in (0, 1), done.stderr
    assert done.stdout == shown, f"regenerate {PAGE.name}: {command}"


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
