"""The ``gyrovib`` command.

Each command parses its options, makes one library call and hands the result
to a renderer. Heavy modules (numpy, yaml, rich) are imported inside the
commands, so ``gyrovib --help`` stays instant. Every :class:`GyrovibError` is
caught here, once: one line per problem on standard error, exit status 2.

Exit status (the contract; no environment variable changes it):

* 0 success; 1 ``select``'s requirement not met; 2 bad usage or bad input;
* 3 an internal error (a bug in gyrovib), reported in one line asking for a
  report; ``GYROVIB_DEBUG=1`` adds the traceback, the status stays 3;
* 74 (``EX_IOERR``) the output could not be written (standard output closed or
  on a full disk, ``--output`` on a failing device): one line naming it;
* 130 interrupted (Ctrl-C, SIGINT), 143 terminated (SIGTERM): one line, and
  ``--output`` is left as it was;
* 141 standard output closed before everything was written (``| head``), as
  for a process killed by SIGPIPE; nothing is printed.
"""

from __future__ import annotations

import os
import signal
import sys
import warnings
from typing import Any, NoReturn

import click

from gyrovib._version import __version__
from gyrovib.cli.common import Settings, printable
from gyrovib.cli.output import WriteFailure, silence_stdout
from gyrovib.errors import GyrovibError

EXIT_OK, EXIT_NOT_MET, EXIT_BAD_INPUT, EXIT_INTERNAL = 0, 1, 2, 3
EXIT_WRITE_FAILED = 74  # EX_IOERR of sysexits.h
EXIT_INTERRUPTED = 128 + signal.SIGINT
EXIT_BROKEN_PIPE = 128 + 13
EXIT_TERMINATED = 128 + signal.SIGTERM

_CLICK_FLOW = (click.exceptions.Exit, click.exceptions.Abort)


class Terminated(KeyboardInterrupt):
    """Raised in the main thread on SIGTERM, so ``finally`` blocks clean up."""


def _on_sigterm(signum: int, frame: Any) -> None:
    raise Terminated


def _report(exc: GyrovibError, settings: Settings | None) -> None:
    # The plain lines first: a reader that went away from standard output must
    # not cost the user the messages on standard error.
    for problem in exc.problems:
        click.echo(printable(f"gyrovib: error: {problem}" if problem.file is None
                             else str(problem)), err=True)
    if settings is not None and settings.github:
        from gyrovib.render.github import problems_to_github

        try:
            sys.stdout.write(problems_to_github(exc.problems))
            sys.stdout.flush()
        except (OSError, AttributeError, ValueError):
            silence_stdout()  # the verdict (exit 2) stands; the annotations are a courtesy


def _wants_github(argv: list[str]) -> bool:
    """Whether the command line asks for ``--format github`` (read before it is parsed)."""
    return any(a == "--format=github" or (a == "--format" and argv[k + 1:k + 2] == ["github"])
               for k, a in enumerate(argv))


def _echo_interrupted(code: int) -> None:
    word = "interrupted" if code == EXIT_INTERRUPTED else "terminated"
    try:
        sys.stderr.write(f"\ngyrovib: {word}\n")
        sys.stderr.flush()
    except (OSError, AttributeError, ValueError):
        pass


#: Each command lives in its own module, imported only when that command runs
#: (or ``--help`` lists them all).
_COMMANDS = {name: f"gyrovib.cli.{name}"
             for name in ("analyze", "bounds", "select", "sweep", "report", "validate", "schema",
                          "catalog")}


class _Group(click.Group):
    """Catches the one error root and turns it into lines on stderr and exit 2.

    Anything else that escapes a command is a bug: it is reported in one line
    with exit status 3 (not 2, so that CI does not blame the input);
    ``GYROVIB_DEBUG`` adds the traceback without changing the status.
    """

    _argv: list[str] | None = None

    def list_commands(self, ctx: click.Context) -> list[str]:
        return list(_COMMANDS)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in self.commands and cmd_name in _COMMANDS:
            import importlib

            module = importlib.import_module(_COMMANDS[cmd_name])
            self.add_command(getattr(module, cmd_name))
        return self.commands.get(cmd_name)

    def main(self, args: Any = None, *rest: Any, **extra: Any) -> Any:
        self._argv = None if args is None else [str(a) for a in args]
        return super().main(args, *rest, **extra)

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
        except click.exceptions.UsageError as exc:
            if _wants_github(sys.argv[1:] if self._argv is None else self._argv):
                from gyrovib.render.github import annotation

                try:
                    sys.stdout.write(annotation(exc.format_message(), title="gyrovib usage")
                                     + "\n")
                    sys.stdout.flush()
                except (OSError, AttributeError, ValueError):
                    silence_stdout()
            raise
        except (click.exceptions.ClickException, *_CLICK_FLOW):
            raise
        except KeyboardInterrupt as exc:
            code = EXIT_TERMINATED if isinstance(exc, Terminated) else EXIT_INTERRUPTED
            _echo_interrupted(code)
            ctx.exit(code)
        except MemoryError:
            click.echo("gyrovib: error: out of memory", err=True)
            ctx.exit(EXIT_BAD_INPUT)
        except BrokenPipeError:
            # The reader went away (`| head`): stop quietly, as a SIGPIPE would.
            silence_stdout()
            ctx.exit(EXIT_BROKEN_PIPE)
        except WriteFailure as exc:
            click.echo(f"gyrovib: error: {printable(str(exc))}", err=True)
            ctx.exit(EXIT_WRITE_FAILED)
        except Exception as exc:
            if os.environ.get("GYROVIB_DEBUG"):
                import traceback

                traceback.print_exc(file=sys.stderr)
            detail = str(exc).splitlines()[0][:300] if str(exc) else ""
            click.echo(
                f"gyrovib: internal error: {type(exc).__name__}"
                + (f": {printable(detail)}" if detail else "")
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
    help="Colour in tables. always/never override NO_COLOR and FORCE_COLOR; auto: only "
    "on a terminal whose TERM is not 'dumb', off when NO_COLOR is set, on when "
    "FORCE_COLOR is set.",
)
@click.pass_context
def cli(ctx: click.Context, color: str) -> None:
    """Vibration error of angular-rate sensors (gyroscopes).

    Analyse how a sensor's nonlinearity, scale-factor asymmetry and cross-axis
    sensitivity rectify angular vibration into a systematic output error, and
    find which sensors of a catalogue meet an error budget.

    Without FILE arguments every command uses the catalogues bundled with
    gyrovib. Exit status: 0 success, 1 a `select` requirement not met,
    2 bad usage or bad input, 3 an internal error (please report it),
    74 the output could not be written, 130 interrupted, 141 standard output
    closed early.
    """
    ctx.obj = Settings(color=color)


def main(args: list[str] | None = None) -> NoReturn:
    """Console-script entry point: runs the command and exits with its status."""
    previous = signal.getsignal(signal.SIGTERM)
    if previous in (signal.SIG_DFL, None):
        signal.signal(signal.SIGTERM, _on_sigterm)
    try:
        code = cli.main(args, prog_name="gyrovib", standalone_mode=False)
    except click.exceptions.Abort:  # a KeyboardInterrupt while click parsed the group
        _echo_interrupted(EXIT_INTERRUPTED)
        code = EXIT_INTERRUPTED
    except click.exceptions.ClickException as exc:
        exc.show()
        code = exc.exit_code
    except KeyboardInterrupt as exc:
        code = EXIT_TERMINATED if isinstance(exc, Terminated) else EXIT_INTERRUPTED
        _echo_interrupted(code)
    except BrokenPipeError:
        silence_stdout()
        code = EXIT_BROKEN_PIPE
    except Exception as exc:  # outside a command (parsing the group, completion): still a bug
        if os.environ.get("GYROVIB_DEBUG"):
            import traceback

            traceback.print_exc(file=sys.stderr)
        click.echo(f"gyrovib: internal error: {type(exc).__name__}: "
                   f"{printable(str(exc))[:300]}; this is a bug in gyrovib: please report it",
                   err=True)
        code = EXIT_INTERNAL
    code = code if isinstance(code, int) else 0
    if code in (EXIT_OK, EXIT_NOT_MET):
        try:
            if sys.stdout is not None:
                sys.stdout.flush()
        except BrokenPipeError:
            silence_stdout()
            code = EXIT_BROKEN_PIPE
        except (OSError, ValueError) as exc:
            silence_stdout()
            click.echo(f"gyrovib: error: cannot write standard output: {exc}", err=True)
            code = EXIT_WRITE_FAILED
    sys.exit(code)
