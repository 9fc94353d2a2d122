"""The command line's one lazy boundary (gyrovib/cli/lazy.py): each command is declared
in a light module and runs a body of the same name and signature from gyrovib.cli.run."""

from __future__ import annotations

import importlib
import inspect
import subprocess
import sys
from pathlib import Path

import pytest

from gyrovib.cli.lazy import BODIES
from gyrovib.cli.main import _COMMANDS, cli


def _is_lazy(command: object) -> bool:
    return hasattr(getattr(command, "callback", None), "body_module") or any(
        _is_lazy(c) for c in getattr(command, "commands", {}).values())


#: The declarations whose bodies live in gyrovib.cli.run, by command path.
LAZY = {name: command for name in _COMMANDS
        if (command := cli.get_command(None, name)) is not None  # type: ignore[arg-type]
        and _is_lazy(command)}


def _declarations() -> list[tuple[str, object]]:
    found = []
    for name, command in LAZY.items():
        if _is_lazy(command) and hasattr(command.callback, "body_module"):
            found.append((name, command))
        for sub, child in getattr(command, "commands", {}).items():
            if hasattr(child.callback, "body_module"):
                found.append((f"{name} {sub}", child))
    return found


def test_the_commands_of_this_package_are_declared_lazily():
    assert {"analyze", "bounds", "select", "sweep", "report", "schema", "catalog", "allan", "fit",
            "mission", "profile", "runup"} <= set(LAZY)


@pytest.mark.parametrize("path, command", _declarations(), ids=lambda x: str(x)[:20])
def test_each_body_has_the_declarations_name_and_signature(path, command):
    declared = command.callback.__wrapped__
    body = getattr(importlib.import_module(command.callback.body_module), declared.__name__)
    assert inspect.signature(body) == inspect.signature(declared)
    assert command.callback.__doc__ == declared.__doc__  # the help is the declaration's


def test_help_loads_no_body():
    probe = ("import contextlib, io, sys\n"
             "from gyrovib.cli.main import cli\n"
             "for args in (['--help'], ['analyze', '--help'], ['select', '--help']):\n"
             "    with contextlib.redirect_stdout(io.StringIO()):\n"
             "        cli.main(args, prog_name='gyrovib', standalone_mode=False)\n"
             # the bodies' package and its modules (gyrovib.cli.runup is a declaration)
             f"print(sorted(m for m in sys.modules if m == {BODIES!r} "
             f"or m.startswith({BODIES + '.'!r})))\n")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                          check=True, timeout=60)
    assert done.stdout.strip() == "[]"


def test_the_floor_program_reads_the_bundled_catalogues():
    # benchmarks/floor.py is what start-up is measured against (docs/performance.md): it
    # must keep validating the bundled files as they change
    floor = Path(__file__).resolve().parent.parent / "benchmarks" / "floor.py"
    done = subprocess.run([sys.executable, str(floor), "--sensor", "adxrs453"],
                          capture_output=True, text=True, check=False, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "adxrs453" in done.stdout
