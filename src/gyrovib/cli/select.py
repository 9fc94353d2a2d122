"""`gyrovib select`: which sensors of a catalogue meet a budget."""

from __future__ import annotations

import click

from gyrovib.cli.lazy import runs
from gyrovib.cli.mission import coverage_option
from gyrovib.cli.options import (
    budget_options,
    files_argument,
    format_option,
    output_option,
    peak_factor_option,
    placement_option,
    selection_options,
)
from gyrovib.cli.spec_options import (
    assume_unknown_option,
    spec_weights_option,
)
from gyrovib.cli.yield_options import yield_options


@click.command()
@files_argument
@selection_options
@budget_options
@peak_factor_option
@placement_option
@click.option("--mission", "mission", metavar="ID",
              help="Select on this mission instead of profiles (docs/model.md section 12): "
                   "--budget on the mean RMS Δ̄_RMS, or --angle-budget on |θ_V|.")
@click.option("--angle-budget", "angle_budget", metavar="A",
              help="With --mission: θ* on the budget total (|θ_V| plus the noise terms; "
                   "sensors ranked on it), with an angle unit (0.5deg, '2 mrad'); --budget "
                   "is then not needed.")
@coverage_option
@click.option("--criterion", type=click.Choice(["bounds", "rms", "worst", "both"]),
              default="bounds", show_default=True,
              help="What a pass means: bounds: every coefficient within its bound (the "
                   "paper's synthesis; a datasheet sensor: its NL and VRE within their spec "
                   "bounds) -- sufficient, not necessary: a sensor outside a bound may still "
                   "meet the budget; rms: Δ_V(RMS) ≤ budget (eq. 17), the direct test; "
                   "worst: |Δ_V| ≤ budget (a datasheet sensor over its envelope); both: "
                   "bounds and rms. A saturating sensor fails whatever the criterion.")
@spec_weights_option
@assume_unknown_option
@click.option("--require", type=click.Choice(["any", "all"]), default="any", show_default=True,
              help="Exit 1 unless at least one (any) or every (all) sensor passes under "
                   "every chosen profile.")
@yield_options
@format_option("table", "json", "csv", "markdown", "junit", "github")
@output_option
@click.pass_context
@runs("select")
def select(ctx: click.Context, files: tuple[str, ...], sensors: tuple[str, ...],
           placement: str | None, mission: str | None, angle_budget: str | None,
           profiles: tuple[str, ...], budget: str | None, method: str, rate: str | None,
           unit: str | None, allocation: str | None, peak_factor: float, criterion: str,
           spec_weights: str | None, assume_unknown: str | None, require: str,
           yield_target: float | None, seed: int, draws: int, fmt: str,
           output: str | None, coverage: float) -> None:
    """Check every sensor against a budget: a pass/fail table and a ranking.

    Each sensor's bounds include its frequency response where it acts at its
    input (`response: {at: input, ...}`; an output filter earns no credit);
    its |coefficients| are checked against them and its RMS error against the
    budget (eq. 17). A datasheet (spec-form) sensor is checked by its
    nonlinearity and VRE against the allowable figures for its range, and its
    margin is that of its worst case. A sensor that saturates under a profile
    fails there. A datasheet part whose verdict hangs on a figure its datasheet
    does not publish (the VRE under linear vibration, m31/m32 under cross-axis
    vibration) is unverified, and does not count as passing.
    With --yield Y a production lot (`lot:`) passes a profile when the
    probability that a part drawn from it passes is at least Y (docs/model.md section 14).
    Exit status 1 when the --require condition is not met.
    """


for _param in select.params:  # --budget is not needed with --mission --angle-budget
    if _param.name == "budget":
        _param.required = False
