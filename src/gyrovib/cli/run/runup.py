"""The body of `gyrovib runup` (declared in :mod:`gyrovib.cli.runup`)."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.api.runup import runup as run
from gyrovib.api.runup import runup_yaml
from gyrovib.cli.common import load_catalog, page_width, plain_ascii, say, use_color
from gyrovib.cli.output import write_binary, write_output
from gyrovib.cli.run.recording import read
from gyrovib.errors import OptionError
from gyrovib.render import runup as render


def parse_steps(text: str | None) -> list[tuple[float, float]] | None:
    """``--steps A:B,C:D,…`` in s; None when not given."""
    if text is None:
        return None
    out = []
    for part in text.split(","):
        bounds = part.strip().split(":")
        try:
            if len(bounds) != 2:
                raise ValueError
            out.append((float(bounds[0]), float(bounds[1])))
        except ValueError:
            raise OptionError(f"--steps {text!r}: give start:end pairs in s, comma-separated "
                              "(e.g. 0:60,65:125)") from None
    return out


def parse_terms(text: str | None) -> list[str] | None:
    """``--estimate A1,k2,…``; None when not given."""
    if text is None:
        return None
    return [t.strip() for t in text.split(",") if t.strip()]


def runup(ctx: click.Context, /, recording: str, files: tuple[str, ...], sensor: str | None,
          steps: str | None, estimate: str | None, crossover: float, require: bool,
          plot: str | None, output: str | None, fmt: str, **options: Any) -> None:
    """See :func:`gyrovib.cli.runup.runup`."""

    if require and sensor is None:
        raise OptionError("--require compares each step with a sensor's prediction: give "
                          "--sensor ID")
    given = parse_steps(steps)
    terms = parse_terms(estimate)
    catalog = load_catalog(files) if sensor is not None or files else None
    result = run(read(recording, options), catalog, sensor=sensor, steps=given,
                 estimate=terms, crossover=crossover)
    for warning in result.warnings:  # a log's damage, said as profile says it
        say(f"gyrovib: warning: {warning}")
    if fmt != "table":
        for note in result.notes:
            say(f"gyrovib: note: {note}")
    if plot is not None:
        write_binary(render.plot(result), plot)
    if output is not None:
        write_output(runup_yaml(result, catalog), output)
    if output != "-":
        if fmt == "table":
            text = render.to_table(result, color=use_color(), width=page_width(),
                                   ascii=plain_ascii())
        else:
            text = {"json": render.to_json, "csv": render.to_csv,
                    "markdown": render.to_markdown}[fmt](result)
        write_output(text, None)
    if require and not result.requirement_met:
        ctx.exit(1)
