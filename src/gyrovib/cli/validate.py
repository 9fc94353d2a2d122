"""`gyrovib validate`: parse and validate only."""

from __future__ import annotations

import click

from gyrovib.cli.common import load_catalog


@click.command()
@click.argument("files", nargs=-1, required=True, metavar="FILE...")
def validate(files: tuple[str, ...]) -> None:
    """Only parse and validate catalogue files (exit 0 if valid, 2 if not)."""
    catalog = load_catalog(files)
    click.echo(f"{len(files)} file(s) valid: {len(catalog.sensors)} sensor(s), "
               f"{len(catalog.profiles)} profile(s)", err=True)
