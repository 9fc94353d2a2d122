"""docs/recordings.md: every `$ gyrovib ...` console command runs from the source tree
and prints the lines the page shows (as tests/test_docs_commands.py runs docs/ci.md)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGE = ROOT / "docs" / "recordings.md"


def console_blocks() -> list[tuple[str, list[str]]]:
    out = []
    for block in re.findall(r"```console\n(.*?)```", PAGE.read_text(encoding="utf-8"),
                            flags=re.S):
        lines = block.splitlines()
        assert lines[0].startswith("$ gyrovib ")
        out.append((lines[0][2:], [ln for ln in lines[1:] if ln.strip()]))
    return out


#: Where the page's synthetic logs are (section 6: written by tests/logwriters.py).
LOGS = Path("/tmp/gyrovib-logs")


@pytest.fixture(scope="module")
def synthetic_logs() -> None:
    """The page's synthetic logs, written as the page says (each file replaced whole, so
    parallel workers never see one half written)."""
    pytest.importorskip("pymavlink", reason="the page's DataFlash log needs gyrovib[ardupilot]")
    subprocess.run([sys.executable, "-m", "tests.logwriters", str(LOGS)], cwd=ROOT,
                   check=True, timeout=300)


@pytest.mark.parametrize(("command", "shown"), console_blocks())
def test_console_block_runs_as_shown(command: str, shown: list[str],
                                     synthetic_logs: None) -> None:
    pytest.importorskip("pyulog", reason="the page's log needs the extra gyrovib[ulog]")
    script = f'gyrovib() {{ "{sys.executable}" -m gyrovib "$@"; }}\n{command}\n'
    done = subprocess.run(["bash", "-c", script], cwd=ROOT, capture_output=True, text=True,
                          timeout=300, check=False)
    # select exits 1 when no sensor passes: the verdict the page shows
    assert done.returncode == (1 if command.startswith("gyrovib select") else 0), done.stderr
    printed = [ln.rstrip() for ln in (done.stdout + done.stderr).splitlines()]
    for line in shown:
        assert line.rstrip() in printed, f"{line!r} not printed by {command}"


def test_page_has_both_steps() -> None:
    commands = [c for c, _ in console_blocks()]
    assert any(c.startswith("gyrovib profile") for c in commands)
    assert any(c.startswith("gyrovib analyze --recording") for c in commands)
    assert any(c.startswith("gyrovib mission /tmp/px4.gyrovib.yaml") for c in commands)
