"""The body of `gyrovib catalog export` (declared in :mod:`gyrovib.cli.catalog`)."""

from __future__ import annotations

import os
import shutil

import click

from gyrovib.api.study.entries import bundled_choice
from gyrovib.errors import OptionError


def export(directory: str, which: str, force: bool) -> None:
    """See :func:`gyrovib.cli.catalog.export`."""
    sources = bundled_choice(which)
    targets = [os.path.join(directory, os.path.basename(s)) for s in sources]
    if os.path.exists(directory) and not os.path.isdir(directory):
        raise OptionError(f"{directory}: not a directory")
    clash = [t for t in targets if os.path.exists(t)]
    if clash and not force:
        raise OptionError(f"{clash[0]} exists; --force replaces it")
    try:
        os.makedirs(directory, exist_ok=True)
        for source, target in zip(sources, targets, strict=True):
            shutil.copyfile(source, target)
            click.echo(f"gyrovib: wrote {target}", err=True)
    except OSError as exc:
        raise OptionError(f"{directory}: cannot write ({exc.strerror or exc})") from None
