"""`gyrovib runup`: a run-up test turned into the installed sensor's own rectification
(docs/model.md section 16)."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.cli.lazy import runs
from gyrovib.cli.options import files_argument, format_option
from gyrovib.cli.recording import reader_options


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
@runs("runup")
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
