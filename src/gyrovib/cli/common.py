"""Helpers shared by the commands."""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import click


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


#: The characters escaped by :func:`printable`: C0 controls, DEL and C1 controls.
_CONTROL = {c: f"\\x{c:02x}" for c in (*range(0x20), *range(0x7F, 0xA0))}
_CONTROL.update({ord("\n"): "\\n", ord("\r"): "\\r", ord("\t"): "\\t"})


def printable(text: str) -> str:
    """``text`` with control characters (newlines, ANSI escapes) shown as ``\\n``,
    ``\\x1b``…, so a hostile file name cannot forge lines or drive the terminal."""
    return text.translate(_CONTROL)


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
                import shutil

                return max(shutil.get_terminal_size().columns, 40)
        except (AttributeError, ValueError, OSError):
            pass
    columns = os.environ.get("COLUMNS", "")
    return max(int(columns), 40) if columns.isdigit() else None


def github_errors(enabled: bool = True) -> None:
    """Also print errors raised from now on as GitHub annotations (on stdout)."""
    _settings().github = enabled


STDIN = "-"
STDIN_NAME = "<stdin>"


def load_catalog(files: tuple[str, ...], sensors: bool = True) -> Any:
    """The merged catalogue of ``files``, or the bundled catalogues when none are given.

    The command's ``--bundled`` choice adds bundled catalogues to ``files``.
    ``-`` stands for standard input, named ``<stdin>`` in messages.
    ``sensors=False``: profiles only, sensors neither loaded nor validated.
    """
    from gyrovib.api import load

    bundled = _bundled()
    if STDIN not in files:
        return load(files, sensors=sensors, bundled=bundled)
    if bundled is not None:
        from gyrovib.api.entries import bundled_choice

        files = (*files, *bundled_choice(bundled))
    return _load_with_stdin(files, sensors)


def _bundled() -> str | None:
    """The command's ``--bundled`` choice (:func:`gyrovib.cli.options.bundled_option`)."""
    from gyrovib.cli.options import BUNDLED_KEY

    ctx = click.get_current_context(silent=True)
    found = None if ctx is None else ctx.meta.get(BUNDLED_KEY)
    return found if isinstance(found, str) else None


def _read_stdin() -> str:
    from gyrovib.catalog.loader import MAX_FILE_BYTES
    from gyrovib.errors import CatalogError, Problem

    stream = sys.stdin
    if stream is None:
        raise CatalogError(Problem("standard input is closed", STDIN_NAME))
    raw = stream.buffer.read(MAX_FILE_BYTES + 1) if hasattr(stream, "buffer") else (
        stream.read(MAX_FILE_BYTES + 1).encode("utf-8"))
    if len(raw) > MAX_FILE_BYTES:
        raise CatalogError(Problem(f"the input is larger than {MAX_FILE_BYTES // 2**20} MiB; "
                                   "that is not a catalogue", STDIN_NAME))
    if b"\0" in raw:
        raise CatalogError(Problem("binary data (a NUL byte), not a YAML text file",
                                   STDIN_NAME))
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        raise CatalogError(Problem(f"not UTF-8 text (byte 0x{raw[exc.start]:02x}); give the "
                                   "catalogue as UTF-8", STDIN_NAME, line, 1)) from None


def _load_with_stdin(files: tuple[str, ...], sensors: bool = True) -> Any:
    """Like :func:`gyrovib.api.load`, standard input read once for ``-``."""
    from gyrovib.catalog.loader import CatalogSource, merge, parse_catalog, read_catalog
    from gyrovib.errors import CatalogError, OptionError, Problem

    if files.count(STDIN) > 1:
        raise OptionError("'-' (standard input) can be given only once")
    problems: list[Problem] = []
    sources: list[CatalogSource] = []
    for name in files:
        try:
            skip = () if sensors else ("sensors",)
            sources.append(parse_catalog(_read_stdin(), STDIN_NAME, skip) if name == STDIN
                           else read_catalog(name, skip))
        except CatalogError as exc:
            problems.extend(exc.problems)
    if problems:
        try:  # the files that did parse may still clash: report that too
            merge(sources)
        except CatalogError as exc:
            problems.extend(exc.problems)
        raise CatalogError(problems)
    return merge(sources)
