"""`gyrovib allan`: the overlapping Allan deviation of a static recording and the noise
figures read from it (docs/model.md section 15)."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.cli.common import rendered, say
from gyrovib.cli.options import as_options, format_option
from gyrovib.cli.output import write_binary, write_output
from gyrovib.cli.recording import reader_options, recording_of
from gyrovib.errors import OptionError


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
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib.api.noise import allan as run
    from gyrovib.api.noise import noise_yaml
    from gyrovib.render import allan as render
    from gyrovib.render.kalibr import to_kalibr

    result = as_options(run(recording_of(options).read(recording), unit=unit, per_decade=per_decade,
                            confidence=parse_confidence(confidence)))  # notes name options
    for warning in result.warnings:  # a log's damage, said as profile says it; the fit's
        say(f"gyrovib: warning: {warning}")
    if plot is not None:
        write_binary(render.plot(result), plot)
    if output is not None:
        write_output(noise_yaml(result), output)
        if output == "-":
            return
    write_output(to_kalibr(result) if fmt == "kalibr" else rendered(render, result, fmt), None)


def parse_confidence(text: str) -> float:
    """``68%``, ``68`` or ``0.68`` → 0.68."""
    raw = text.strip()
    try:
        value = float(raw.rstrip("%").strip())
    except ValueError:
        raise OptionError(f"--confidence {text!r}: give a level such as 68% or 0.95") from None
    if raw.endswith("%") or value > 1.0:
        value /= 100.0
    if not 0.0 < value < 1.0:
        raise OptionError(f"--confidence {text!r}: give a level between 0 and 100 %")
    return value
