"""Docs pages that show gyrovib's own output.

A ``$ gyrovib ...`` console block of a page is what that command prints at 100
columns without colour, run from the root of the tree. A block may leave lines
out: a line ``...`` stands for lines left out (the pieces between must appear in
that order, the first at the start and the last at the end), so a block ending
in ``...`` is the beginning of the output. ``tools/regenerate_docs.py PAGE``
rewrites a page's blocks from the commands.
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BLOCK = re.compile(r"```console\n\$ (gyrovib [^\n]*)\n(.*?)```", flags=re.S)


def console_blocks(page: Path) -> list[tuple[str, str]]:
    """``(command, shown)`` of every console block of ``page``."""
    return [(c, shown) for c, shown in BLOCK.findall(page.read_text(encoding="utf-8"))]


def run_shown(command: str, codes: tuple[int, ...] = (0, 1)) -> str:
    """What ``command`` prints on standard output as the pages show it (100 columns,
    no colour, from the root of the tree); its exit status must be one of ``codes``."""
    env = {**os.environ, "COLUMNS": "100", "NO_COLOR": "1"}
    env.pop("FORCE_COLOR", None)
    done = subprocess.run([sys.executable, "-m", "gyrovib", *shlex.split(command)[1:]],
                          cwd=ROOT, capture_output=True, text=True, env=env, timeout=120,
                          check=False)
    assert done.returncode in codes, done.stderr
    return done.stdout


def assert_shows(page: Path, command: str, shown: str, out: str) -> None:
    """``shown`` (a block of ``page``) is ``out``, with its ``...`` lines left out."""
    where = f"regenerate {page.name}: {command}"
    pieces = ("\n" + shown).split("\n...\n")
    if len(pieces) == 1:
        assert out == shown, where
        return
    assert out.startswith(pieces[0].lstrip("\n")), where
    assert out.endswith(pieces[-1]), where
    at = 0
    for piece in pieces:
        found = out.find(piece.strip("\n"), at)
        assert found >= 0, f"{where}: {piece[:80]!r}"
        at = found + len(piece.strip("\n"))
