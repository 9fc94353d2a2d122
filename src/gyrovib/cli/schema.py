"""`gyrovib schema`: the JSON Schema of the catalogue format."""

from __future__ import annotations

import click

from gyrovib.cli.options import output_option
from gyrovib.cli.output import write_output


@click.command()
@output_option
def schema(output: str | None) -> None:
    """Print the JSON Schema (draft-07) of the catalogue format.

    Save it and point your editor at it, e.g. with yaml-language-server put
    this first line in a catalogue:

    \b
        # yaml-language-server: $schema=./gyrovib.schema.json
    """
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib.models.schema import schema_text

    write_output(schema_text(), output)
