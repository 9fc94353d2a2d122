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
    """Whether to colour: ``always``/``never`` win; in ``auto`` a non-empty
    NO_COLOR turns it off, then a non-empty FORCE_COLOR (other than ``0``) on,
    and otherwise colour follows whether the output is a terminal."""
    if mode == "always":
        return True
    if mode == "never":
        return False
    if environ.get("NO_COLOR"):
        return False
    force = environ.get("FORCE_COLOR")
    if force and force != "0":
        return True
    return is_terminal


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


def github_errors(enabled: bool = True) -> None:
    """Also print errors raised from now on as GitHub annotations (on stdout)."""
    _settings().github = enabled


def load_catalog(files: tuple[str, ...]) -> Any:
    """The merged catalogue of ``files``, or the bundled catalogues when none are given."""
    from gyrovib.api import load

    return load(files)

