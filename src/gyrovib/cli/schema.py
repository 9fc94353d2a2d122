"""`gyrovib schema`: the JSON Schema of the catalogue format."""

from __future__ import annotations

import click

from gyrovib.cli.lazy import runs
from gyrovib.cli.options import output_option


@click.command()
@output_option
@runs("schema")
def schema(output: str | None) -> None:
    """Print the JSON Schema (draft-07) of the catalogue format.

    Save it and point your editor at it, e.g. with yaml-language-server put
    this first line in a catalogue:

    \b
        # yaml-language-server: $schema=./gyrovib.schema.json
    """
