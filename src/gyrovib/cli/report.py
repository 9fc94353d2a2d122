"""`gyrovib report`: a self-contained HTML trade-study report of a selection."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.cli.common import load_catalog, say
from gyrovib.cli.mission import coverage_option
from gyrovib.cli.options import (
    budget_arguments,
    budget_options,
    files_argument,
    peak_factor_option,
    selection_options,
)
from gyrovib.cli.output import write_output
from gyrovib.cli.recording import recording_options
from gyrovib.cli.spec_options import assume_unknown_option
from gyrovib.cli.sweep import parse_rate_range
from gyrovib.cli.yield_options import yield_options

DEFAULT_OUTPUT = "report.html"


@click.command()
@files_argument
@selection_options
@budget_options
@peak_factor_option
@click.option("--criterion", type=click.Choice(["bounds", "rms", "worst", "both"]),
              default="bounds", show_default=True,
              help="What a pass means: every coefficient within its bound, Δ_V(RMS) ≤ budget "
                   "(eq. 17), |Δ_V| ≤ budget (worst), or bounds and rms (both).")
@assume_unknown_option
@click.option("--require", type=click.Choice(["any", "all"]), default="any", show_default=True,
              help="The requirement the report states as met or not: at least one (any) or "
                   "every (all) sensor passes under every chosen profile.")
@click.option("--rate-range", "rate_range", metavar="START:STOP:COUNT",
              help="Ω_K3 values of the sweep charts, in --unit. Default: 241 rates over "
                   "±1.5 × the largest |Ω_K3| + vibration peak of the chosen profiles.")
@yield_options
@click.option("--output", "-o", default=DEFAULT_OUTPUT, show_default=True, metavar="PATH",
              help="Write the HTML here (atomically); '-' for standard output.")
@click.option("--recording", metavar="RECORDING",
              help="Add a recording (docs/model.md section 13): its PSD against the fitted "
                   "profile, the honesty of the fit, Δ_V,rec beside the closed form; the "
                   "fitted profile joins the study's profiles.")
@click.option("--mission", "missions", multiple=True, metavar="ID",
              help="Add a mission section (repeatable): per sensor the angle θ_V against "
                   "--angle-budget, the whole angle budget as a stacked bar and the "
                   "per-segment breakdown (docs/model.md sections 12 and 15).")
@click.option("--angle-budget", "angle_budget", metavar="A",
              help="θ* of the mission section, on each sensor's budget total, with an angle "
                   "unit (0.5deg, '2 mrad').")
@coverage_option
@click.option("--placement", metavar="P",
              help="The mission section's placement, replacing each mission's own: "
                   "x1=+Y,x2=+Z,x3=+X (a rotation), or triad (docs/model.md section 12).")
@recording_options
def report(files: tuple[str, ...], sensors: tuple[str, ...], profiles: tuple[str, ...],
           missions: tuple[str, ...], angle_budget: str | None,
           budget: str, method: str, rate: str | None, unit: str | None, allocation: str | None,
           peak_factor: float, criterion: str, assume_unknown: str | None, require: str,
           rate_range: str | None, yield_target: float | None, seed: int, draws: int,
           output: str, recording: str | None, coverage: float, placement: str | None = None,
           **rec: Any) -> None:
    """Write a trade-study report: one HTML file, charts inline, no network needed.

    It holds the inputs (files with their SHA-256, budget, method, criterion,
    allocation, version, date), the pass/fail matrix with margins, the passing
    sensors ranked, what limits each failing one, and per profile charts: the
    RMS error against the budget, its breakdown by term, the error over the
    rate envelope and the profile's spectrum. Prints cleanly to PDF. Unlike
    `select`, the exit status is 0 whether or not the requirement is met.
    """
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib import api
    from gyrovib.api.report import views as studies
    from gyrovib.cli.mission import mission_section
    from gyrovib.cli.recording import recording_of, report_recording
    from gyrovib.render.report import to_html

    split = budget_arguments(budget, unit, rate, allocation)
    sweep_rates = None
    if rate_range is not None:
        sweep_rates = api.rate_range(*parse_rate_range(rate_range, split["unit"]))
    catalog = load_catalog(files)
    section = ""
    if recording is not None:
        catalog, profiles, section = report_recording(recording, catalog, sensors, profiles,
                                                      split["unit"], recording_of(rec))
    if missions:  # after the recording's section, before the profiles
        section += mission_section(catalog, missions, sensors, angle_budget, split["unit"],
                                   peak_factor, assume_unknown=assume_unknown or "none",
                                   coverage=coverage, placement=placement)
    result = studies.trade_study(
        catalog, sensors=sensors, profiles=profiles, method=method, **split,
        criterion=criterion, require=require, sweep_rates=sweep_rates, peak_factor=peak_factor,
        assume_unknown=assume_unknown or "none", yield_target=yield_target, seed=seed,
        draws=draws)
    write_output(to_html(result, section), output)
    if output not in ("-", ""):
        say(f"gyrovib: wrote {output}")
