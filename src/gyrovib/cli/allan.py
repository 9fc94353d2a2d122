"""`gyrovib allan`: the overlapping Allan deviation of a static recording and the noise
figures read from it (docs/model.md section 15)."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.cli.common import page_width, plain_ascii, use_color
from gyrovib.cli.options import format_option
from gyrovib.cli.output import write_binary, write_output
from gyrovib.cli.recording import reader_options


@click.command()
@click.argument("recording", metavar="RECORDING")
@reader_options
@click.option("--unit", default="deg/h", show_default=True, metavar="UNIT",
              help="Rate unit of the Allan deviation: deg/s, deg/h, rad/s, rpm (the figures "
                   "are always in deg/sqrt(h), deg/h and deg/h/sqrt(h)).")
@click.option("--per-decade", type=click.IntRange(min=1), default=10, show_default=True,
              metavar="P", help="Points of the τ grid per decade (fewer where there are "
                                "not as many cluster sizes).")
@click.option("--plot", metavar="PNG",
              help="Write the Allan deviation per axis, log-log, with the slope lines of N "
                   "and K, the B floor and the fitted model (matplotlib).")
@click.option("--output", "-o", metavar="FILE",
              help="Write the figures as a noise: block (YAML) to paste into a sensor "
                   "('-': standard output instead of the table).")
@format_option("table", "json")
def allan(recording: str, unit: str, per_decade: int, plot: str | None, output: str | None,
          fmt: str, **options: Any) -> None:
    """The Allan deviation of a static RECORDING and N, B, K with their uncertainties.

    Per recorded axis: the overlapping Allan deviation (IEEE Std 952) on a log
    grid of τ from 1/fs to a third of the record, and read from it the angle
    random walk N (deg/sqrt(h)), the bias instability B = σ_min/0.664 (deg/h)
    and the rate random walk K (deg/h/sqrt(h)), each with a standard
    uncertainty (docs/error-budget.md). The sensor must be at rest; a record
    with gaps is analysed on its longest contiguous segment.

    RECORDING: as for `gyrovib profile` (CSV with a header row, .npy, .npz,
    PX4 .ulg), with the same column, unit and sample-rate options.
    """
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib.api.noise import allan as run
    from gyrovib.api.noise import noise_yaml
    from gyrovib.cli.recording import read
    from gyrovib.render import allan as render

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
