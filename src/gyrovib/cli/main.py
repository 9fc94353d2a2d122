"""The ``gyrovib`` command.

Each command parses its options, makes one library call and hands the result
to a renderer. Heavy modules (numpy, pydantic, rich) are imported inside the
commands, so ``gyrovib --help`` stays instant. Every :class:`GyrovibError` is
caught here, once: one line per problem on standard error, exit status 2.
"""

from __future__ import annotations

import sys
from typing import Any

import click

from gyrovib._version import __version__
from gyrovib.errors import GyrovibError

EXIT_OK, EXIT_NOT_MET, EXIT_BAD_INPUT = 0, 1, 2


class _Group(click.Group):
    """Catches the one error root and turns it into lines on stderr and exit 2."""

    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except GyrovibError as exc:
            for problem in exc.problems:
                click.echo(f"gyrovib: error: {problem}" if problem.file is None else str(problem),
                           err=True)
            ctx.exit(EXIT_BAD_INPUT)
        except MemoryError:
            click.echo("gyrovib: error: out of memory", err=True)
            ctx.exit(EXIT_BAD_INPUT)


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, "--version", "-V", prog_name="gyrovib")
def cli() -> None:
    """Vibration error of angular-rate sensors (gyroscopes).

    Analyse how a sensor's nonlinearity, scale-factor asymmetry and cross-axis
    sensitivity rectify angular vibration into a systematic output error, and
    find which sensors of a catalogue meet an error budget.

    Without FILE arguments every command uses the catalogues bundled with
    gyrovib. Exit status: 0 success, 1 a `select` requirement not met,
    2 bad usage or bad input.
    """


def _register() -> None:
    # Each command lives in its own module; they import only click at import time.
    from gyrovib.cli.analyze import analyze
    from gyrovib.cli.bounds import bounds
    from gyrovib.cli.select import select
    from gyrovib.cli.sweep import sweep
    from gyrovib.cli.validate import validate

    for command in (analyze, bounds, select, sweep, validate):
        cli.add_command(command)


_register()


def main() -> None:
    """Console-script entry point."""
    sys.exit(cli.main(prog_name="gyrovib", standalone_mode=True) or 0)
