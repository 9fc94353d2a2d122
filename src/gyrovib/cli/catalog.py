"""`gyrovib catalog`: the bundled catalogues, written out for editing."""

from __future__ import annotations

import os
import shutil

import click

from gyrovib.errors import OptionError


@click.group()
def catalog() -> None:
    """The catalogues bundled with gyrovib (the public sensors, the example profiles)."""


@catalog.command()
@click.argument("directory", metavar="DIR")
@click.option("--bundled", "which", type=click.Choice(["sensors", "profiles", "all"]),
              default="all", show_default=True, help="Which bundled catalogues to write.")
@click.option("--force", is_flag=True,
              help="Replace files of the same name in DIR (by default they are kept and "
                   "the command fails).")
def export(directory: str, which: str, force: bool) -> None:
    """Write the bundled catalogues into DIR (created if missing), to edit as your own.

    Each file keeps its name (sensors.gyrovib.yaml, profiles.gyrovib.yaml) and
    its comments, the sources of every figure. Give the copies to any command
    in place of the bundled ones.
    """
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib.api.study.entries import bundled_choice

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
