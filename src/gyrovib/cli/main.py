"""The ``gyrovib`` command.

Each command parses its options, makes one library call and hands the result
to a renderer. Heavy modules (numpy, yaml, rich) are imported inside the
commands, so ``gyrovib --help`` stays instant. Every :class:`GyrovibError` is
caught here, once: one line per problem on standard error, exit status 2.

Exit status is the contract docs/ci.md sets out: 0 success; 1 a requirement not met
(``select``, ``mission``, ``runup --require``); 2 bad usage or bad input; 3 an internal
error, in one line (``GYROVIB_DEBUG=1`` adds the traceback); 74 the output could not be
written; 129, 130, 143 hung up, interrupted, terminated (``--output`` left as it was, and
once it is in place a signal no longer interrupts); 141 standard output closed early.
A standard error that cannot be written (``2>/dev/full``) costs the messages, never the
status. Names in messages are written with their control characters escaped
(:func:`~gyrovib.cli.common.printable`).
"""

from __future__ import annotations

import importlib
import os
import signal
import sys
import warnings
from typing import TYPE_CHECKING, Any, NoReturn

import click

from gyrovib._version import __version__
from gyrovib.cli.early import early_exit
from gyrovib.cli.output import WriteFailure, output_in_place, silence_stdout, start_run

if TYPE_CHECKING:
    from gyrovib.cli.common import Settings
    from gyrovib.errors import GyrovibError

EXIT_OK, EXIT_NOT_MET, EXIT_BAD_INPUT, EXIT_INTERNAL = 0, 1, 2, 3
EXIT_WRITE_FAILED = 74  # EX_IOERR of sysexits.h
EXIT_INTERRUPTED = 128 + signal.SIGINT
EXIT_BROKEN_PIPE = 128 + 13

#: The signals turned into exceptions (so ``finally`` blocks clean up), and their words.
_SIGNALS = {signal.SIGINT: "interrupted", signal.SIGTERM: "terminated",
            signal.SIGHUP: "hung up"}

_CLICK_FLOW = (click.exceptions.Exit, click.exceptions.Abort)


class Terminated(KeyboardInterrupt):
    """Raised in the main thread on SIGTERM or SIGHUP, so ``finally`` blocks clean up."""

    def __init__(self, signum: int = signal.SIGTERM) -> None:
        super().__init__(signum)
        self.signum = signum


def _on_signal(signum: int, frame: Any) -> None:
    """SIGINT, SIGTERM, SIGHUP: an exception, unless the output is already in place, the
    outcome is decided, or a signal has already been received.

    Once the output has been renamed over ``--output`` the run has succeeded:
    a signal in its last moments must not report a failure the file contradicts.
    After the first signal the run is ending (its workers terminated, its temporary
    file removed): a second one must not cut that short with a traceback.
    """
    if output_in_place() or _decided or _received:
        return  # the outcome stands; a second signal must not interrupt the clean-up
    _received.append(signum)
    if signum == signal.SIGINT:
        raise KeyboardInterrupt
    raise Terminated(signum)


#: The signals received (:func:`_on_signal`): a library that catches the exception
#: a signal raised and raises another in its place (as pydantic may while it builds
#: a model) must not turn an interrupted run into an internal error.
_received: list[int] = []

#: Set once :func:`main` has decided its status: a signal then changes nothing.
_decided = False


def _interrupted_status() -> int | None:
    """128 + the first signal received, if any."""
    return 128 + _received[0] if _received else None


def _signal_status(exc: KeyboardInterrupt) -> int:
    """128 + the signal behind ``exc``: 130 for Ctrl-C, 143 SIGTERM, 129 SIGHUP."""
    return 128 + (exc.signum if isinstance(exc, Terminated) else signal.SIGINT)


def say(line: str) -> None:
    """:func:`gyrovib.cli.common.say`, its module imported when there is something to say
    (``gyrovib --help`` does without it)."""
    from gyrovib.cli.common import say as write

    write(line)


def silence_stderr() -> None:
    """:func:`gyrovib.cli.common.silence_stderr`, imported as :func:`say` is."""
    from gyrovib.cli.common import silence_stderr as silence

    silence()


def _debug() -> bool:
    """Whether ``GYROVIB_DEBUG`` asks for tracebacks: 1, true or yes, in any case."""
    return os.environ.get("GYROVIB_DEBUG", "").strip().lower() in ("1", "true", "yes")


def _traceback() -> None:
    if not _debug():
        return
    # lazy: only on an internal error
    import traceback

    try:
        traceback.print_exc(file=sys.stderr)
        sys.stderr.flush()
    except (OSError, ValueError, AttributeError):
        pass


def _report(exc: GyrovibError, settings: Settings | None) -> None:
    # The plain lines first: a reader that went away from standard output must
    # not cost the user the messages on standard error.
    for problem in exc.problems:
        say(f"gyrovib: error: {problem}" if problem.file is None else str(problem))
    if settings is not None and settings.github:
        from gyrovib.render.github import problems_to_github

        _annotate(problems_to_github(exc.problems))


def _annotate(text: str) -> None:
    """GitHub annotations on standard output; one that cannot be written is dropped (the
    verdict, exit 2, stands; the annotations are a courtesy)."""
    try:
        sys.stdout.write(text)
        sys.stdout.flush()
    except (OSError, AttributeError, ValueError):
        silence_stdout()


def _unexpected(exc: Exception) -> int:
    """Report an exception that is not the user's and return the status: the signal's, if
    one was received (a library may have raised another exception in its place); out of
    memory, 2; else an internal error, 3, in one line (``GYROVIB_DEBUG`` adds the
    traceback). A :class:`~gyrovib.errors.Crash` is placed at the file it met."""
    from gyrovib.errors import Crash

    signalled = _interrupted_status()
    if signalled is not None:
        _echo_interrupted(signalled)
        return signalled
    where, kind, detail = "gyrovib", type(exc).__name__, str(exc)
    if isinstance(exc, Crash):
        where, kind, detail = exc.file, exc.kind, exc.detail
        if kind == MemoryError.__name__:
            say(f"{where}: error: out of memory")
            return EXIT_BAD_INPUT
    _traceback()
    detail = detail.splitlines()[0][:300] if detail else ""
    say(f"{where}: internal error: {kind}" + (f": {detail}" if detail else "")
        + "; this is a bug in gyrovib, not in your input: please report it with the "
        "command and files used (GYROVIB_DEBUG=1 shows the traceback)")
    return EXIT_INTERNAL


def _wants_github(argv: list[str]) -> bool:
    """Whether the command line asks for ``--format github`` (read before it is parsed)."""
    return any(a == "--format=github" or (a == "--format" and argv[k + 1:k + 2] == ["github"])
               for k, a in enumerate(argv))


def _echo_interrupted(code: int) -> None:
    word = _SIGNALS.get(signal.Signals(code - 128), "terminated")
    try:
        sys.stderr.write(f"\ngyrovib: {word}\n")
        sys.stderr.flush()
    except (OSError, AttributeError, ValueError):
        silence_stderr()


class _Formatter(click.HelpFormatter):
    """click's help formatter, its width found as click finds it (``COLUMNS``, else the
    terminal's, at most 80, less 2, at least 50) without importing :mod:`shutil`, which
    with its compression modules is the largest part of ``gyrovib --help``'s cost."""

    def __init__(self, indent_increment: int = 2, width: int | None = None,
                 max_width: int | None = None) -> None:
        if width is None and click.formatting.FORCED_WIDTH is None:
            width = max(min(_columns(), 80 if max_width is None else max_width) - 2, 50)
        super().__init__(indent_increment, width, max_width)


def _columns() -> int:
    """The terminal's width as :func:`shutil.get_terminal_size` reads it: ``COLUMNS`` if
    a positive number, else standard output's terminal, else 80."""
    try:
        columns = int(os.environ.get("COLUMNS", "0"))
    except ValueError:
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns  # type: ignore[union-attr]
        except (AttributeError, ValueError, OSError):
            columns = 0
    return columns or 80


class _Context(click.Context):
    formatter_class = _Formatter


class _Group(click.Group):
    """Catches the one error root and turns it into lines on stderr and exit 2.

    Anything else that escapes a command is a bug: it is reported in one line
    with exit status 3 (not 2, so that CI does not blame the input);
    ``GYROVIB_DEBUG`` adds the traceback without changing the status.
    """

    _argv: list[str] | None = None
    context_class = _Context

    def list_commands(self, ctx: click.Context) -> list[str]:
        return list(COMMANDS)  # in the order registered, not sorted

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        """The command ``cmd_name``, its module (gyrovib/cli/NAME.py) imported now: only
        the command that runs declares its options."""
        if cmd_name not in COMMANDS:
            return None
        command: click.Command = getattr(importlib.import_module(f"gyrovib.cli.{cmd_name}"),
                                         cmd_name)
        return command

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """The listing of ``--help`` from :data:`COMMANDS`' help, as click shortens each
        command's own, without importing a command module."""
        limit = formatter.width - 6 - max(len(name) for name in COMMANDS)
        with formatter.section("Commands"):
            formatter.write_dl([(name, click.Command(name, help=text).get_short_help_str(limit))
                                for name, text in COMMANDS.items()])

    def main(self, args: Any = None, *rest: Any, **extra: Any) -> Any:
        self._argv = None if args is None else [str(a) for a in args]
        return super().main(args, *rest, **extra)

    def invoke(self, ctx: click.Context) -> Any:
        # lazy: --help needs neither the option declarations nor the progress display
        from gyrovib.cli.common import Settings
        from gyrovib.cli.options import as_option
        from gyrovib.cli.progress import terminal_progress
        from gyrovib.errors import GyrovibError

        start_run()
        try:
            with warnings.catch_warnings(), terminal_progress():
                # numpy overflow warnings: results are checked for finiteness instead.
                warnings.filterwarnings("ignore", category=RuntimeWarning,
                                        module=r"(gyrovib|numpy)(\..*)?$")
                return super().invoke(ctx)
        except GyrovibError as exc:
            _report(as_option(exc), ctx.find_object(Settings))
            ctx.exit(EXIT_BAD_INPUT)
        except click.exceptions.UsageError as exc:
            if _wants_github(sys.argv[1:] if self._argv is None else self._argv):
                from gyrovib.render.github import annotation

                _annotate(annotation(exc.format_message(), title="gyrovib usage") + "\n")
            raise
        except (click.exceptions.ClickException, *_CLICK_FLOW):
            raise
        except KeyboardInterrupt as exc:
            code = _signal_status(exc)
            _echo_interrupted(code)
            ctx.exit(code)
        except MemoryError:
            say("gyrovib: error: out of memory")
            ctx.exit(EXIT_BAD_INPUT)
        except BrokenPipeError:
            # The reader went away (`| head`): stop quietly, as a SIGPIPE would.
            silence_stdout()
            ctx.exit(EXIT_BROKEN_PIPE)
        except WriteFailure as exc:
            say(f"gyrovib: error: {exc}")
            ctx.exit(EXIT_WRITE_FAILED)
        except Exception as exc:
            ctx.exit(_unexpected(exc))


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
    gyrovib. Exit status: 0 success, 1 a `select`, `mission` or `runup` requirement
    not met, 2 bad usage or bad input, 3 an internal error (please report it),
    74 the output could not be written, 129 hung up, 130 interrupted,
    143 terminated, 141 standard output closed early.
    """
    from gyrovib.cli.common import Settings

    ctx.obj = Settings(color=color)


#: Every command, registered once, in the order ``gyrovib --help`` lists them: its name
#: (gyrovib/cli/NAME.py declares it, imported when it runs) and the first paragraph of its
#: help, which the listing shortens as click would (tests/test_cli_lazy.py holds each to
#: the command's own), so ``gyrovib --help`` imports no command module.
COMMANDS: dict[str, str] = {
    "analyze": "The direct problem: the vibration error of every sensor under every profile.",
    "bounds": "The inverse problem: the largest coefficients that keep the error within "
              "budget.",
    "select": "Check every sensor against a budget: a pass/fail table and a ranking.",
    "sweep": "Δ_V and Δ_V(RMS) over a range of Ω_K3, exact and paper side by side.",
    "report": "Write a trade-study report: one HTML file, charts inline, no network needed.",
    "validate": "Only parse and validate catalogue files (exit 0 if valid, 2 if not).",
    "schema": "Print the JSON Schema (draft-07) of the catalogue format.",
    "fit": "Fit rate-table data: each unit's coefficients with their uncertainty, and the lot.",
    "profile": "Fit a profile (and its carrier mission) to a RECORDING, or to the envelope of "
               "several.",
    "allan": "The Allan deviation of a static RECORDING and its noise model, with intervals.",
    "catalog": "The catalogues bundled with gyrovib (the public sensors, the example "
               "profiles).",
    "mission": "Each sensor over each mission: mean error, angle θ_V, mean RMS, worst "
               "segment, and the whole angle budget.",
    "runup": "The installed sensor's rectification, measured from a run-up test RECORDING.",
}


def main(args: list[str] | None = None) -> NoReturn:
    """Console-script entry point: runs the command and exits with its status.

    From the first signal handler installed to the status decided, everything runs
    inside one ``try``: a signal anywhere in it ends the run in one line with its
    status; after it, a signal changes nothing (:func:`_on_signal`)."""
    global _decided
    _decided = False
    _received.clear()
    caught: list[signal.Signals] = []
    try:
        _catch_signals(caught)
        code = _command(args)
        if code in (EXIT_OK, EXIT_NOT_MET):
            code = _flushed(code)
        _decided = True
    except KeyboardInterrupt as exc:  # a signal outside the command's own handling
        code = _signal_status(exc)
        _echo_interrupted(code)
    # The outcome is decided (and any output in place): the signals caught are now
    # ignored. Python's shutdown would otherwise put back their default action,
    # and a SIGTERM in its last milliseconds would kill a run that has succeeded.
    for signum in caught:
        signal.signal(signum, signal.SIG_IGN)
    sys.exit(code)


def _command(args: list[str] | None) -> int:
    """Run the command; its status, every exception but a signal's turned into one."""
    try:
        code = cli.main(args, prog_name="gyrovib", standalone_mode=False)
    except click.exceptions.Abort:  # a signal while click parsed (or imported) the command
        code = _interrupted_status() or EXIT_INTERRUPTED  # SIGTERM, SIGHUP: not Ctrl-C
        _echo_interrupted(code)
    except click.exceptions.ClickException as exc:
        try:
            exc.show()
        except (OSError, ValueError, AttributeError):
            silence_stderr()
        code = exc.exit_code
    except BrokenPipeError:
        silence_stdout()
        code = EXIT_BROKEN_PIPE
    except Exception as exc:  # outside a command (parsing the group, completion): still a bug
        signalled = _interrupted_status()
        if signalled is not None:
            code = signalled
            _echo_interrupted(code)
        else:
            _traceback()
            say(f"gyrovib: internal error: {type(exc).__name__}: "
                f"{str(exc)[:300]}; this is a bug in gyrovib: please report it")
            code = EXIT_INTERNAL
    return code if isinstance(code, int) else 0


def _flushed(code: int) -> int:
    """``code`` once standard output is flushed, or the status of its failure."""
    try:
        if sys.stdout is not None:
            sys.stdout.flush()
    except BrokenPipeError:
        silence_stdout()
        code = EXIT_BROKEN_PIPE
    except (OSError, ValueError) as exc:
        silence_stdout()
        say(f"gyrovib: error: cannot write standard output: {exc}")
        code = EXIT_WRITE_FAILED
    return code


def _catch_signals(caught: list[signal.Signals]) -> None:
    """SIGINT, SIGTERM and SIGHUP become exceptions (:func:`_on_signal`), each appended to
    ``caught`` as soon as it is; a signal the parent set to be ignored (``nohup``, a
    background job) stays ignored. The handler of the console script's start-up
    (:func:`gyrovib.cli.early.early_exit`) is replaced in one step, so there is no moment
    when the signal's default action would kill the process."""
    for signum in _SIGNALS:
        previous = signal.getsignal(signum)
        if previous in (signal.SIG_DFL, None, signal.default_int_handler, early_exit):
            caught.append(signum)
            signal.signal(signum, _on_signal)
