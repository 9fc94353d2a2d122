"""Rewrite the ``$ gyrovib ...`` console blocks of docs pages from the commands.

    .venv/bin/python tools/regenerate_docs.py docs/linear-vibration.md [docs/missions.md ...]

Each block becomes what its command prints from the root of the tree at 100
columns without colour (as tests/docpages.py checks it). A block that ends in a
``...`` line keeps only as many lines as it shows now; a block with ``...`` in its
middle is left as it is and named on standard error (edit it by hand).
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BLOCK = re.compile(r"```console\n\$ (gyrovib [^\n]*)\n(.*?)```", flags=re.S)


def output(command: str) -> str:
    env = {**os.environ, "COLUMNS": "100", "NO_COLOR": "1"}
    env.pop("FORCE_COLOR", None)
    done = subprocess.run([sys.executable, "-m", "gyrovib", *shlex.split(command)[1:]],
                          cwd=ROOT, capture_output=True, text=True, env=env, timeout=600,
                          check=False)
    if done.returncode not in (0, 1):
        raise SystemExit(f"{command}: exit {done.returncode}\n{done.stderr}")
    return done.stdout


def regenerate(page: Path) -> None:
    def block(match: re.Match[str]) -> str:
        command, shown = match.group(1), match.group(2)
        lines = shown.splitlines(keepends=True)
        if "...\n" in lines[:-1]:
            print(f"{page}: left as it is (lines left out in its middle): {command}",
                  file=sys.stderr)
            return match.group(0)
        out = output(command)
        if lines and lines[-1] == "...\n":
            out = "".join(out.splitlines(keepends=True)[:len(lines) - 1]) + "...\n"
        return f"```console\n$ {command}\n{out}```"

    text = page.read_text(encoding="utf-8")
    page.write_text(BLOCK.sub(block, text), encoding="utf-8")


if __name__ == "__main__":
    for name in sys.argv[1:]:
        regenerate(Path(name))
