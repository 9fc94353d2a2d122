"""`gyrovib validate`: parse and validate only."""

from __future__ import annotations

import click

from gyrovib.cli.common import github_errors, load_catalog, say


@click.command()
@click.argument("files", nargs=-1, required=True, metavar="FILE...")
@click.option("--format", "fmt", type=click.Choice(["text", "github"]), default="text",
              show_default=True,
              help="text: FILE:LINE:COL: message on standard error; github: also "
              "::error annotations on standard output, for GitHub Actions.")
def validate(files: tuple[str, ...], fmt: str) -> None:
    """Only parse and validate catalogue files (exit 0 if valid, 2 if not).

    Every file is checked, and every problem of every file reported, one line
    each: FILE:LINE:COL: message. Ids must also be unique across the files.
    """
    github_errors(fmt == "github")
    catalog = load_catalog(files)
    say(f"{len(files)} file(s) valid: {len(catalog.sensors)} sensor(s), "
        f"{len(catalog.profiles)} profile(s)")
