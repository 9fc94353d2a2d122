"""The commands docs/ci.md shows run as shown, from the root of the source tree
(a clone or the unpacked sdist), and their globs match the bundled files."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
CI_MD = ROOT / "docs" / "ci.md"


def documented_commands() -> list[str]:
    blocks = re.findall(r"```sh\n(.*?)```", CI_MD.read_text(encoding="utf-8"), flags=re.S)
    commands = []
    for block in blocks:
        for line in block.splitlines():
            command = line.split("  #")[0].strip()
            if command.startswith("gyrovib ") and " > " not in command:
                commands.append(command)
    return commands


def test_docs_show_the_validate_commands() -> None:
    commands = documented_commands()
    assert any(c.startswith("gyrovib validate --format github") for c in commands)
    assert any(c.startswith("gyrovib validate - <") for c in commands)


@pytest.mark.parametrize("command", documented_commands())
def test_documented_command_runs(command: str) -> None:
    for word in shlex.split(command.replace("<", " ")):
        if "*" in word:  # a glob must match files of this tree, bundled ones included
            assert sorted(ROOT.glob(word)), f"{word} matches nothing"
    script = f'gyrovib() {{ "{sys.executable}" -m gyrovib "$@"; }}\n{command}\n'
    done = subprocess.run(["bash", "-c", script], cwd=ROOT, capture_output=True, text=True,
                          timeout=120, check=False)
    assert done.returncode == 0, done.stderr
    assert "valid:" in done.stderr
