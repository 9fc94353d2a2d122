"""The ``gyrovib`` command.

Each command parses its options, makes one library call and hands the result
to a renderer. Heavy modules (numpy, pydantic, rich) are imported inside the
commands, so ``gyrovib --help`` stays instant. Every :class:`GyrovibError` is
caught here, once: one line per problem on standard error, exit status 2.

Exit status: 0 success; 1 ``select``'s requirement not met; 2 bad usage or bad
input; 3 an internal error (a bug in gyrovib, reported in one line asking for a
report; ``GYROVIB_DEBUG=1`` shows the traceback instead); 141 standard output
closed early (``gyrovib analyze | head``), as for a process killed by SIGPIPE.
"""

from __future__ import annotations

import os
import sys
import warnings
from typing import Any

import click

from gyrovib._version import __version__
from gyrovib.cli.common import Settings
from gyrovib.errors import GyrovibError

EXIT_OK, EXIT_NOT_MET, EXIT_BAD_INPUT, EXIT_INTERNAL = 0, 1, 2, 3
EXIT_BROKEN_PIPE = 128 + 13

_CLICK_FLOW = (click.exceptions.ClickException, click.exceptions.Exit, click.exceptions.Abort)


def _report(exc: GyrovibError, settings: Settings | None) -> None:
    if settings is not None and settings.github:
        from gyrovib.render.github import problems_to_github

        sys.stdout.write(problems_to_github(exc.problems))
        sys.stdout.flush()
    for problem in exc.problems:
        click.echo(f"gyrovib: error: {problem}" if problem.file is None else str(problem),
                   err=True)


class _Group(click.Group):
    """Catches the one error root and turns it into lines on stderr and exit 2.

    Anything else that escapes a command is a bug: it is reported in one line
    with exit status 3 (not 2, so that CI does not blame the input), unless
    ``GYROVIB_DEBUG`` is set, which lets the traceback through.
    """

    def invoke(self, ctx: click.Context) -> Any:
        try:
            with warnings.catch_warnings():
                # numpy overflow warnings: results are checked for finiteness instead.
                warnings.filterwarnings("ignore", category=RuntimeWarning,
                                        module=r"(gyrovib|numpy)(\..*)?$")
                return super().invoke(ctx)
        except GyrovibError as exc:
            _report(exc, ctx.find_object(Settings))
            ctx.exit(EXIT_BAD_INPUT)
        except _CLICK_FLOW:
            raise
        except MemoryError:
            click.echo("gyrovib: error: out of memory", err=True)
            ctx.exit(EXIT_BAD_INPUT)
        except BrokenPipeError:
            # The reader went away (`| head`): stop quietly, as a SIGPIPE would.
            try:
                devnull = os.open(os.devnull, os.O_WRONLY)
                os.dup2(devnull, sys.stdout.fileno())
            except (OSError, ValueError):
                pass
            ctx.exit(EXIT_BROKEN_PIPE)
        except Exception as exc:
            if os.environ.get("GYROVIB_DEBUG"):
                raise
            detail = str(exc).splitlines()[0][:300] if str(exc) else ""
            click.echo(
                f"gyrovib: internal error: {type(exc).__name__}"
                + (f": {detail}" if detail else "")
                + "; this is a bug in gyrovib, not in your input: please report it with the "
                "command and files used (GYROVIB_DEBUG=1 shows the traceback)",
                err=True,
            )
            ctx.exit(EXIT_INTERNAL)


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, "--version", "-V", prog_name="gyrovib")
@click.option(
    "--color", "color", type=click.Choice(["auto", "always", "never"]), default="auto",
    show_default=True,
    help="Colour in tables. auto: only on a terminal, off when NO_COLOR is set, "
    "on when FORCE_COLOR is set.",
)
@click.pass_context
def cli(ctx: click.Context, color: str) -> None:
    """Vibration error of angular-rate sensors (gyroscopes).

    Analyse how a sensor's nonlinearity, scale-factor asymmetry and cross-axis
    sensitivity rectify angular vibration into a systematic output error, and
    find which sensors of a catalogue meet an error budget.

    Without FILE arguments every command uses the catalogues bundled with
    gyrovib. Exit status: 0 success, 1 a `select` requirement not met,
    2 bad usage or bad input, 3 an internal error (please report it).
    """
    ctx.obj = Settings(color=color)


def _register() -> None:
    # Each command lives in its own module; they import only click at import time.
    from gyrovib.cli.analyze import analyze
    from gyrovib.cli.bounds import bounds
    from gyrovib.cli.report import report
    from gyrovib.cli.schema import schema
    from gyrovib.cli.select import select
    from gyrovib.cli.sweep import sweep
    from gyrovib.cli.validate import validate

    for command in (analyze, bounds, select, sweep, report, validate, schema):
        cli.add_command(command)


_register()


def main() -> None:
    """Console-script entry point."""
    sys.exit(cli.main(prog_name="gyrovib", standalone_mode=True) or 0)
