"""Helpers shared by the commands."""

from __future__ import annotations

import importlib
import os
import shutil
import sys
import types
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import click

from gyrovib.cli.output import silence
from gyrovib.errors import CatalogError, OptionError, Problem


@dataclass
class Settings:
    """Global options, kept as the click context's ``obj``.

    ``color`` is the ``--color`` choice (auto, always, never); ``github`` is
    set by a command given ``--format github``, so errors are also printed as
    GitHub annotations.
    """

    color: str = "auto"
    github: bool = False


def resolve_color(mode: str, environ: Mapping[str, str], is_terminal: bool) -> bool:
    """Whether to colour.

    ``always`` and ``never`` win over every variable (no-color.org: an explicit
    flag overrides NO_COLOR). In ``auto`` a non-empty NO_COLOR turns colour
    off, then a non-empty FORCE_COLOR (other than ``0``) on; otherwise colour
    needs a terminal whose TERM is not ``dumb``.
    """
    if mode == "always":
        return True
    if mode == "never":
        return False
    if environ.get("NO_COLOR"):
        return False
    force = environ.get("FORCE_COLOR")
    if force and force != "0":
        return True
    return is_terminal and environ.get("TERM") != "dumb"


#: The characters escaped by :func:`printable`: C0 controls, DEL and C1 controls, the
#: Unicode line and paragraph separators (``str.splitlines`` breaks at them) and the
#: bidirectional embeddings, overrides and isolates (they reorder what a terminal shows).
_CONTROL = {c: f"\\x{c:02x}" for c in (*range(0x20), *range(0x7F, 0xA0))}
_CONTROL.update({ord("\n"): "\\n", ord("\r"): "\\r", ord("\t"): "\\t"})
_CONTROL.update({c: f"\\u{c:04x}" for c in (0x2028, 0x2029, *range(0x202A, 0x202F),
                                            *range(0x2066, 0x206A))})


def printable(text: str) -> str:
    """``text`` with control characters (newlines, ANSI escapes) shown as ``\\n``,
    ``\\x1b``…, so a hostile file name cannot forge lines or drive the terminal."""
    return text.translate(_CONTROL)


def say(line: str) -> None:
    """Write one line to standard error, its control characters escaped (:func:`printable`).

    A standard error that cannot be written (closed, ``2>/dev/full``) loses the
    line, never the exit status: it is pointed at the null device, so neither
    the next message nor Python's flush at exit fails again.
    """
    try:
        stream = sys.stderr
        stream.write(printable(line) + "\n")
        stream.flush()
    except (OSError, ValueError, AttributeError):
        silence_stderr()


def silence_stderr() -> None:
    """Point standard error at the null device (:func:`gyrovib.cli.output.silence`)."""
    silence(2, "stderr")


def _settings() -> Settings:
    ctx = click.get_current_context(silent=True)
    found = ctx.find_object(Settings) if ctx is not None else None
    return found if found is not None else Settings()


def use_color(output: str | None = None) -> bool:
    """Whether the current command should colour what it writes to ``output``.

    Output to a file (``--output PATH``) counts as not a terminal.
    """
    to_stdout = output is None or output == "-"
    try:
        tty = to_stdout and sys.stdout.isatty()
    except (AttributeError, ValueError):
        tty = False
    return resolve_color(_settings().color, os.environ, tty)


def plain_ascii(output: str | None = None) -> bool:
    """Whether standard output (when it is the output) cannot encode the tables' glyphs."""
    if output is not None and output != "-":
        return False
    encoding = getattr(sys.stdout, "encoding", None) or "utf-8"
    try:
        "Δ±✓✗⚠┃━".encode(encoding)
    except UnicodeEncodeError:
        return True
    except LookupError:
        return False
    return False


def page_width(output: str | None = None) -> int | None:
    """Columns a table may use: the terminal's width on a terminal, else ``COLUMNS``
    when set, else None (the renderers' default, 160)."""
    if output is None or output == "-":
        try:
            if sys.stdout.isatty():
                return max(shutil.get_terminal_size().columns, 40)
        except (AttributeError, ValueError, OSError):
            pass
    columns = os.environ.get("COLUMNS", "")
    return max(int(columns), 40) if columns.isdigit() else None


#: Table rows past which a table is slow to draw: rich lays out every cell (about a
#: millisecond a row, against microseconds a row for CSV or JSON).
SLOW_TABLE_ROWS = 2000


def note_slow_table(rows: int) -> None:
    """Say once, on standard error, that CSV and JSON are the fast path for a table
    of more than :data:`SLOW_TABLE_ROWS` rows (tables are for people)."""
    if rows > SLOW_TABLE_ROWS:
        say(f"gyrovib: note: {rows:,} table rows take a while to draw; "
            "--format csv or --format json is the fast path")


def github_errors(enabled: bool = True) -> None:
    """Also print errors raised from now on as GitHub annotations (on stdout)."""
    _settings().github = enabled


STDIN = "-"
STDIN_NAME = "<stdin>"


def _no_pydantic_plugins() -> None:
    """The command runs no pydantic plugin (observability hooks found through the
    installed packages' entry points): importing importlib.metadata and scanning the
    entry points costs ~20-40 ms of the first model built. Set
    PYDANTIC_DISABLE_PLUGINS yourself (e.g. to "") to have them.

    With plugins off, pydantic's plugin loader is stood in for by a module whose
    ``get_plugins`` finds none and which hands any other name to the real loader,
    imported then (so a pydantic that asks more of it still works)."""
    os.environ.setdefault("PYDANTIC_DISABLE_PLUGINS", "__all__")
    name = "pydantic.plugin._loader"
    if os.environ["PYDANTIC_DISABLE_PLUGINS"] != "__all__" or name in sys.modules:
        return
    stub = types.ModuleType(name)

    def real(attr: str) -> Any:
        if attr.startswith("__"):  # the import system's questions (__path__, ...)
            raise AttributeError(attr)
        del sys.modules[name]
        return getattr(importlib.import_module(name), attr)

    stub.get_plugins = lambda: ()  # type: ignore[attr-defined]
    stub.__getattr__ = real  # type: ignore[method-assign]
    sys.modules[name] = stub


def load_catalog(files: tuple[str, ...]) -> Any:
    """The merged catalogue of ``files``, or the bundled catalogues when none are given.

    The command's ``--bundled`` choice adds bundled catalogues to ``files``.
    ``-`` stands for standard input, named ``<stdin>`` in messages. Every file
    is validated whole, whatever the command uses of it: what ``validate``
    refuses, every command refuses at the same place.
    """
    # lazy: this module is loaded by --help, which must not load pydantic
    from gyrovib.api import load
    _no_pydantic_plugins()
    bundled = _bundled()
    if STDIN not in files:
        return load(files, bundled=bundled)
    if files.count(STDIN) > 1:
        raise OptionError("'-' (standard input) can be given only once")
    # lazy: this module is loaded by --help, which must not load pydantic
    from gyrovib.catalog.loader import Source

    # standard input is one more source, read through the loader every file goes through
    return load([Source.of_bytes(_read_stdin(), STDIN_NAME) if name == STDIN else name
                 for name in files], bundled=bundled)


def _bundled() -> str | None:
    """The command's ``--bundled`` choice (:func:`gyrovib.cli.options.bundled_option`)."""
    from gyrovib.cli.options import BUNDLED_KEY  # lazy: --help declares no options

    ctx = click.get_current_context(silent=True)
    found = None if ctx is None else ctx.meta.get(BUNDLED_KEY)
    return found if isinstance(found, str) else None


def _read_stdin() -> bytes:
    """Standard input's bytes, at most one more than a catalogue may have."""
    # lazy: this module is loaded by --help, which must not load pydantic
    from gyrovib.catalog.loader import MAX_FILE_BYTES
    stream = sys.stdin
    if stream is None:
        raise CatalogError(Problem("standard input is closed", STDIN_NAME))
    if hasattr(stream, "buffer"):
        raw: bytes = stream.buffer.read(MAX_FILE_BYTES + 1)
        return raw
    return str(stream.read(MAX_FILE_BYTES + 1)).encode("utf-8")


def rendered(render: Any, result: Any, fmt: str, output: str | None = None, *args: Any,
             **table: Any) -> Any:
    """The document of ``result`` in ``fmt`` from a renderer module's ``to_FORMAT``
    functions (``to_FORMAT_chunks`` where it streams the document in pieces), each given
    ``args`` after the result; a table is sized and coloured for where it goes
    (``output``) and given the ``table`` keywords."""
    if fmt == "table":
        return render.to_table(result, *args, color=use_color(output), width=page_width(output),
                               ascii=plain_ascii(output), **table)
    chunks = getattr(render, f"to_{fmt}_chunks", None)
    return (chunks or getattr(render, f"to_{fmt}"))(result, *args)
