"""`gyrovib select`: which sensors of a catalogue meet a budget."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import click

from gyrovib.cli.common import (
    github_errors,
    load_catalog,
    note_slow_table,
    rendered,
    say,
)
from gyrovib.cli.mission import coverage_option
from gyrovib.cli.options import (
    as_options,
    budget_arguments,
    budget_options,
    files_argument,
    format_option,
    output_option,
    peak_factor_option,
    placement_option,
    selection_options,
)
from gyrovib.cli.output import write_output
from gyrovib.cli.placement import is_triad, run_placed, write_triad
from gyrovib.cli.spec_options import (
    assume_unknown_option,
    parse_spec_weights,
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
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib import api
    from gyrovib.cli.mission import select_mission
    from gyrovib.render import select as render

    github_errors(fmt == "github")
    if mission is not None or angle_budget is not None:
        met = select_mission(files, mission, sensors, profiles, budget, angle_budget, unit,
                             placement, peak_factor, require, fmt, output,
                             assume_unknown=assume_unknown or "none", coverage=coverage)
        if not met:
            ctx.exit(1)
        return
    if budget is None:
        raise click.UsageError("Missing option '--budget'.", ctx)
    catalog = load_catalog(files)
    split = budget_arguments(budget, unit, rate, allocation)

    result = run_placed(api.select, catalog, placement, fmt, sensors=sensors,
                        profiles=profiles, method=method, **split, criterion=criterion,
                        require=require, spec_weights=parse_spec_weights(spec_weights),
                        peak_factor=peak_factor, assume_unknown=assume_unknown or "none",
                        yield_target=yield_target, seed=seed, draws=draws)
    result = as_options(result)  # its notes name the options, not the library's arguments
    if is_triad(result):  # table, json, csv or markdown, per axis, and the worst axes
        write_triad(result, lambda one: rendered(render, one, fmt, output), fmt, output)
        if not result.requirement_met:
            ctx.exit(1)
        return
    for note in result.notes:
        say(f"gyrovib: warning: {note}")
    text = _rendered(result, fmt, catalog, output)
    write_output(text, output)
    if not result.requirement_met:
        ctx.exit(1)


for _param in select.params:  # --budget is not needed with --mission --angle-budget
    if _param.name == "budget":
        _param.required = False


def _rendered(result: Any, fmt: str, catalog: Any, output: str | None) -> str | Iterator[str]:
    """The selection in ``fmt``; the JSON document is streamed (``to_json_chunks``), never
    whole at once."""
    # lazy: the library and the renderers load when it runs, not for --help
    from gyrovib import api
    from gyrovib.render import select as render
    from gyrovib.render import select_ci

    if fmt == "table":  # a matrix row per sensor, then its ranking or what limits it
        note_slow_table(2 * len(result.sensors))
    if fmt == "github":  # the CI formats
        return select_ci.to_github(result, api.sensor_locations(catalog, result.sensors))
    text: str | Iterator[str] = rendered(select_ci if fmt == "junit" else render, result,
                                         fmt, output)
    return text
