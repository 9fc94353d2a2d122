"""`gyrovib catalog`: the bundled catalogues, written out for editing."""

from __future__ import annotations

import click

from gyrovib.cli.lazy import runs


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
@runs("catalog")
def export(directory: str, which: str, force: bool) -> None:
    """Write the bundled catalogues into DIR (created if missing), to edit as your own.

    Each file keeps its name (sensors.gyrovib.yaml, profiles.gyrovib.yaml) and
    its comments, the sources of every figure. Give the copies to any command
    in place of the bundled ones.
    """
