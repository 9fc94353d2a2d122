"""The body of `gyrovib allan` (declared in :mod:`gyrovib.cli.allan`)."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.api.noise import allan as run
from gyrovib.api.noise import noise_yaml
from gyrovib.cli.common import page_width, plain_ascii, use_color
from gyrovib.cli.output import write_binary, write_output
from gyrovib.cli.run.recording import read
from gyrovib.render import allan as render


def allan(recording: str, unit: str, per_decade: int, plot: str | None, output: str | None,
          fmt: str, **options: Any) -> None:
    """See :func:`gyrovib.cli.allan.allan`."""

    result = run(read(recording, options), unit=unit, per_decade=per_decade)
    for warning in result.warnings:  # a log's damage, said as profile says it
        click.echo(f"gyrovib: warning: {warning}", err=True)
    if plot is not None:
        write_binary(render.plot(result), plot)
    if output is not None:
        write_output(noise_yaml(result), output)
        if output == "-":
            return
    if fmt == "json":
        text = render.to_json(result)
    else:
        text = render.to_table(result, color=use_color(), width=page_width(),
                               ascii=plain_ascii())
    write_output(text, None)
