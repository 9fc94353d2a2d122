"""`gyrovib --help` and `--version` start fast: no heavy module is imported."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

HEAVY = ("numpy", "pydantic", "pydantic_core", "rich", "yaml", "scipy", "highspy")

#: Runs the command in a fresh interpreter, then prints the imported modules.
VIA_CLI = """
import contextlib, io, json, sys
from gyrovib.cli.main import cli
with contextlib.redirect_stdout(io.StringIO()) as out:
    code = cli.main({args!r}, prog_name="gyrovib", standalone_mode=False)
assert code in (None, 0), code
assert out.getvalue().strip(), "the command printed nothing"
print(json.dumps(sorted(sys.modules)))
"""

VIA_MODULE = """
import contextlib, io, json, runpy, sys
sys.argv = ["gyrovib", *{args!r}]
with contextlib.redirect_stdout(io.StringIO()) as out:
    try:
        runpy.run_module("gyrovib", run_name="__main__", alter_sys=True)
    except SystemExit as exc:
        assert exc.code in (None, 0), exc.code
assert out.getvalue().strip(), "the command printed nothing"
print(json.dumps(sorted(sys.modules)))
"""


def imported_modules(template: str, args: list[str]) -> list[str]:
    done = subprocess.run([sys.executable, "-c", template.format(args=args)],
                          capture_output=True, text=True, check=False, timeout=60)
    assert done.returncode == 0, done.stderr
    modules: list[str] = json.loads(done.stdout.strip().splitlines()[-1])
    return modules


@pytest.mark.parametrize("template", [VIA_CLI, VIA_MODULE], ids=["cli.main", "python -m"])
@pytest.mark.parametrize("args", [["--help"], ["--version"], ["analyze", "--help"],
                                  ["select", "--help"], ["report", "--help"]])
def test_help_and_version_import_no_heavy_module(template, args):
    modules = imported_modules(template, args)
    assert "click" in modules  # the probe works
    heavy = sorted(m for m in modules if m.split(".")[0] in HEAVY)
    assert heavy == [], f"gyrovib {' '.join(args)} imported {heavy}"
