"""The command line: one module per command, registered once (gyrovib/cli/main.py,
COMMANDS, with the line ``--help`` lists for each); a command's module is imported when it
runs or shows its own help, and imports the library and the renderers inside its
function, so that listing the commands loads none of them."""

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
    names = list(COMMANDS)
    assert len(names) >= 12  # the probe works
    ctx = click.Context(cli)
    assert cli.list_commands(ctx) == names  # --help lists them in this order
    for name in names:  # cli/NAME.py declares `gyrovib NAME`
        module = importlib.import_module(f"gyrovib.cli.{name}")
        command = cli.get_command(ctx, name)
        assert getattr(module, name) is command and command is not None
        assert command.name == name and command.short_help == COMMANDS[name]
    assert cli.get_command(ctx, "no-such-command") is None


def test_no_command_is_declared_outside_the_registry():
    for info in pkgutil.iter_modules(gyrovib.cli.__path__):
        module = importlib.import_module(f"gyrovib.cli.{info.name}")
        for value in vars(module).values():
            if isinstance(value, click.Command) and value.__module__ == module.__name__:
                assert value.name in COMMANDS or value.name in ("cli", "export"), \
                    f"{module.__name__}.{value.name} is not registered in COMMANDS"


def test_listing_the_commands_imports_none_of_them():
    # `gyrovib --help` reads each command's line from the registry: no command module,
    # no option declarations, no renderer
    probe = ("import contextlib, io, sys\n"
             "from gyrovib.cli.main import cli\n"
             "out = io.StringIO()\n"
             "with contextlib.redirect_stdout(out):\n"
             "    cli.main(['--help'], prog_name='gyrovib', standalone_mode=False)\n"
             "assert 'runup' in out.getvalue()\n"
             "print(sorted(m for m in sys.modules if m.startswith('gyrovib.')\n"
             "             and m not in ('gyrovib.cli', 'gyrovib.cli.main', 'gyrovib.cli.early',\n"
             "                           'gyrovib.cli.common', 'gyrovib.cli.output',\n"
             "                           'gyrovib.errors', 'gyrovib.frozen',\n"
             "                           'gyrovib._version')))\n")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                          check=True, timeout=60)
    assert done.stdout.strip() == "[]"


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
