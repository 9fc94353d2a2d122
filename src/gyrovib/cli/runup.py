"""`gyrovib runup`: a run-up test turned into the installed sensor's own rectification
(docs/model.md section 16)."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.cli.common import load_catalog, rendered, say
from gyrovib.cli.options import as_options, files_argument, format_option
from gyrovib.cli.output import write_binary, write_output
from gyrovib.cli.recording import reader_options, recording_of
from gyrovib.errors import OptionError


@click.command()
@click.argument("recording", metavar="RECORDING")
@files_argument
@click.option("--sensor", metavar="ID",
              help="Set each step's measured shift beside this catalogue sensor's prediction "
                   "(its recorded error on the step's samples, or its datasheet's worst case) "
                   "and the in-situ figures beside its own.")
@click.option("--steps", metavar="A:B,C:D,...",
              help="The steps, in s from the recording's first sample (default: found from "
                   "the running variance of x3 and of the accelerations).")
@click.option("--estimate", metavar="TERMS",
              help="Comma-separated terms to estimate: A1, k2, k4, m31, m32, vre, G11, G22, "
                   "G33, G12, G13, G23 (default: vre with accelerations, else k2).")
@click.option("--crossover", type=float, default=5.0, show_default=True, metavar="F",
              help="f_c, Hz: below it the carrier (the vehicle's motion), above it vibration.")
@click.option("--require", is_flag=True,
              help="Exit 1 when a step's measured shift lies outside its prediction's "
                   "interval (more than 2 standard uncertainties off; needs --sensor).")
@click.option("--plot", metavar="PNG",
              help="Write the shift against the vibration (measured with error bars, the fit "
                   "and the prediction) as PNG (matplotlib).")
@click.option("--output", "-o", metavar="FILE",
              help="Write a catalogue sensor entry with the in-situ figures and their "
                   "uncertainty (YAML; '-': standard output instead of the report).")
@reader_options
@format_option("table", "json", "csv", "markdown")
@click.pass_context
def runup(ctx: click.Context, /, recording: str, files: tuple[str, ...], sensor: str | None,
          steps: str | None, estimate: str | None, crossover: float, require: bool,
          plot: str | None, output: str | None, fmt: str, **options: Any) -> None:
    """The installed sensor's rectification, measured from a run-up test RECORDING.

    Hold the vehicle at rest and step its vibration (motors off, idle, higher
    settings, ideally down again): every change of the mean rate about x3
    between steps is then rectification, drift or noise (docs/runup.md). Per
    step: its duration, vibration level, the mean shift from the baseline
    (the quietest steps) with its uncertainty from the step's own Allan
    variance, the fit's shift and residual; then the in-situ coefficients by
    weighted least squares, with a drift term where the steps' order separates
    it, each said to be found, not significant, or not identifiable (and what
    step would separate it).

    RECORDING: as for `gyrovib profile` (CSV, .npy, .npz, PX4 .ulg, ArduPilot
    .bin) with the same column, unit, topic and sample-rate options; FILE...:
    catalogues for --sensor (default: the bundled ones).
    """
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib.api.runup import runup as run
    from gyrovib.api.runup import runup_yaml
    from gyrovib.render import runup as render

    if require and sensor is None:
        raise OptionError("--require compares each step with a sensor's prediction: give "
                          "--sensor ID")
    given = parse_steps(steps)
    terms = parse_terms(estimate)
    catalog = load_catalog(files) if sensor is not None or files else None
    result = as_options(run(recording_of(options).read(recording), catalog, sensor=sensor,
                            steps=given, estimate=terms,
                            crossover=crossover))  # notes name options
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
        write_output(rendered(render, result, fmt), None)
    if require and not result.requirement_met:
        ctx.exit(1)


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
