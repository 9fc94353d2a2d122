"""The command line: one module per command, registered once (gyrovib/cli/main.py,
COMMANDS) and imported only when it runs; a command imports the library and the
renderers inside its function, so that listing the commands (``--help``) loads no command
module, and a command's own ``--help`` its declarations only."""

from __future__ import annotations

import importlib
import pkgutil
import subprocess
import sys
from pathlib import Path

import click
import pytest

import gyrovib.cli
from gyrovib.cli.main import COMMANDS, cli


def _command(name: str) -> click.Command:
    command = cli.get_command(click.Context(cli), name)
    assert command is not None
    return command


def test_every_command_is_registered_once_from_its_own_module():
    names = list(COMMANDS)
    assert len(names) >= 12  # the probe works
    assert cli.list_commands(click.Context(cli)) == names  # --help lists them in this order
    for name in names:  # cli/NAME.py declares `gyrovib NAME`
        module = importlib.import_module(f"gyrovib.cli.{name}")
        assert getattr(module, name) is _command(name) and _command(name).name == name
    assert cli.get_command(click.Context(cli), "nosuch") is None


@pytest.mark.parametrize("limit", [20, 45, 70, 200])
def test_the_listing_shows_each_command_s_own_help(limit: int) -> None:
    # --help lists the commands from the registry without importing them: each entry must
    # read as click would shorten the command's own help, at any terminal width
    for name, text in COMMANDS.items():
        listed = click.Command(name, help=text).get_short_help_str(limit)
        assert listed == _command(name).get_short_help_str(limit), name


def test_no_command_is_declared_outside_the_registry():
    registered = {id(_command(name)) for name in COMMANDS}
    for info in pkgutil.iter_modules(gyrovib.cli.__path__):
        module = importlib.import_module(f"gyrovib.cli.{info.name}")
        for value in vars(module).values():
            if isinstance(value, click.Command) and value.__module__ == module.__name__:
                assert id(value) in registered or value.name in ("cli", "export"), \
                    f"{module.__name__}.{value.name} is not registered in COMMANDS"


def _modules_after_help(helps: list[list[str]], listed: str) -> str:
    """What a fresh interpreter prints of ``sorted(m for m in sys.modules if <listed>)``
    after ``gyrovib ARGS`` for each ARGS of ``helps``."""
    probe = ("import contextlib, io, sys\n"
             "from gyrovib.cli.main import cli\n"
             f"for args in {helps!r}:\n"
             "    with contextlib.redirect_stdout(io.StringIO()):\n"
             "        cli.main(args, prog_name='gyrovib', standalone_mode=False)\n"
             f"print(sorted(m for m in sys.modules if {listed}))\n")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                          check=True, timeout=60)
    return done.stdout.strip()


def test_help_loads_neither_the_library_nor_a_renderer():
    helps = [["--help"], ["analyze", "--help"], ["select", "--help"], ["profile", "--help"],
             ["catalog", "export", "--help"]]
    assert _modules_after_help(helps, "m.startswith(('gyrovib.api', 'gyrovib.render.', "
                               "'gyrovib.core', 'gyrovib.models', 'gyrovib.catalog')) "
                               "and m != 'gyrovib.render.github'") == "[]"


def test_the_top_level_help_imports_neither_the_error_module_nor_shutil():
    # The top-level listing's cost is click's own plus cli/main.py (docs/performance.md):
    # gyrovib.errors (with dataclasses) is imported only once a command runs, and the
    # help formatter reads the terminal's width without shutil and its compression modules.
    assert _modules_after_help([["--help"]], "m in ('gyrovib.errors', 'shutil', "
                               "'dataclasses')") == "[]"


@pytest.mark.parametrize("columns", ["40", "100", "", "x"])
def test_the_help_width_is_the_one_click_would_choose(columns: str) -> None:
    # click.HelpFormatter's own rule (COLUMNS, at most 80, less 2, at least 50) is the
    # reference; the listing is the same text with either formatter.
    import shutil

    from gyrovib.cli.main import _Formatter

    env = {"COLUMNS": columns}
    with pytest.MonkeyPatch.context() as mp:
        for key, value in env.items():
            mp.setenv(key, value)
        assert _Formatter().width == click.HelpFormatter().width
        assert _Formatter().width == max(min(shutil.get_terminal_size().columns, 80) - 2, 50)


def test_the_floor_program_reads_the_bundled_catalogues():
    # benchmarks/floor.py is what start-up is measured against (docs/performance.md): it
    # must keep validating the bundled files as they change
    floor = Path(__file__).resolve().parent.parent / "benchmarks" / "floor.py"
    done = subprocess.run([sys.executable, str(floor), "--sensor", "adxrs453"],
                          capture_output=True, text=True, check=False, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "adxrs453" in done.stdout
