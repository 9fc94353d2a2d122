"""The body of `gyrovib schema` (declared in :mod:`gyrovib.cli.schema`)."""

from __future__ import annotations

from gyrovib.cli.output import write_output
from gyrovib.models.schema import schema_text


def schema(output: str | None) -> None:
    """See :func:`gyrovib.cli.schema.schema`."""
    write_output(schema_text(), output)
