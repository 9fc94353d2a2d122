"""The command line: one module per command, registered once (gyrovib/cli/main.py,
COMMANDS); a command imports the library and the renderers inside its function, so that
listing the commands (``--help``) loads click's declarations only."""

from __future__ import annotations

import importlib
import pkgutil
import subprocess
import sys
from pathlib import Path

import click

import gyrovib.cli
from gyrovib.cli.main import COMMANDS, cli


def test_every_command_is_registered_once_from_its_own_module():
    names = [c.name for c in COMMANDS]
    assert len(names) == len(set(names)) and len(names) >= 12  # the probe works
    assert list(cli.commands) == names  # --help lists them in this order
    for command in COMMANDS:  # cli/NAME.py declares `gyrovib NAME`
        module = importlib.import_module(f"gyrovib.cli.{command.name}")
        assert getattr(module, command.name) is command


def test_no_command_is_declared_outside_the_registry():
    registered = {id(c) for c in COMMANDS}
    for info in pkgutil.iter_modules(gyrovib.cli.__path__):
        module = importlib.import_module(f"gyrovib.cli.{info.name}")
        for value in vars(module).values():
            if isinstance(value, click.Command) and value.__module__ == module.__name__:
                assert id(value) in registered or value.name in ("cli", "export"), \
                    f"{module.__name__}.{value.name} is not registered in COMMANDS"


def test_help_loads_neither_the_library_nor_a_renderer():
    probe = ("import contextlib, io, sys\n"
             "from gyrovib.cli.main import cli\n"
             "for args in (['--help'], ['analyze', '--help'], ['select', '--help'],\n"
             "             ['profile', '--help'], ['catalog', 'export', '--help']):\n"
             "    with contextlib.redirect_stdout(io.StringIO()):\n"
             "        cli.main(args, prog_name='gyrovib', standalone_mode=False)\n"
             "print(sorted(m for m in sys.modules if m.startswith(('gyrovib.api', "
             "'gyrovib.render.', 'gyrovib.core', 'gyrovib.models', 'gyrovib.catalog'))\n"
             "             and m != 'gyrovib.render.github'))\n")
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
