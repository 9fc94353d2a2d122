"""`gyrovib allan`: the overlapping Allan deviation of a static recording and the noise
figures read from it (docs/model.md section 15)."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.cli.lazy import runs
from gyrovib.cli.options import format_option
from gyrovib.cli.recording import reader_options


@click.command()
@click.argument("recording", metavar="RECORDING")
@reader_options
@click.option("--unit", default="deg/h", show_default=True, metavar="UNIT",
              help="Rate unit of the Allan deviation: deg/s, deg/h, rad/s, rpm (the figures "
                   "are always in deg/sqrt(h), deg/h and deg/h/sqrt(h)).")
@click.option("--per-decade", type=click.IntRange(min=1), default=None, metavar="P",
              help="Points of the τ grid per decade (fewer where there are not as many "
                   "cluster sizes); default 10, and for a record of more than 4 M samples "
                   "(read a block at a time) the octave grid τ0·2^j.")
@click.option("--plot", metavar="PNG",
              help="Write the Allan deviation per axis, log-log, with its error bars, each "
                   "term's line and the fitted model (matplotlib).")
@click.option("--output", "-o", metavar="FILE",
              help="Write the figures as a noise: block (YAML) to paste into a sensor "
                   "('-': standard output instead of the table).")
@click.option("--confidence", default="68%", show_default=True, metavar="LEVEL",
              help="Confidence of the intervals on σ(τ) and on the terms (68%, 95%, 0.9…); "
                   "bounds are always at 95 %.")
@format_option("table", "json", "kalibr")
@runs("allan")
def allan(recording: str, unit: str, per_decade: int | None, plot: str | None, output: str | None,
          confidence: str, fmt: str, **options: Any) -> None:
    """The Allan deviation of a static RECORDING and its noise model, with intervals.

    Per recorded axis: the overlapping Allan deviation (IEEE Std 952) on a log
    grid of τ from 1/fs to a third of the record, each point with its
    confidence interval, and the five terms fitted jointly to it: quantization
    Q (deg), angle random walk N (deg/sqrt(h)), bias instability B (deg/h), rate
    random walk K (deg/h/sqrt(h)) and rate ramp R (deg/h^2), with a
    Gauss–Markov term where the curve shows one. Each term is a value with its
    interval or, where the record does not resolve it, an upper bound at 95 %
    (docs/error-budget.md). The sensor must be at rest; a record with gaps is
    analysed on its longest contiguous segment. --format kalibr writes Kalibr's
    imu.yaml.

    RECORDING: as for `gyrovib profile` (CSV with a header row, .npy, .npz,
    PX4 .ulg), with the same column, unit and sample-rate options.
    """
