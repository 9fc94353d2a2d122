"""`gyrovib select`: which sensors of a catalogue meet a budget."""

from __future__ import annotations

from collections.abc import Iterator

import click

from gyrovib.cli.common import github_errors, load_catalog, page_width, plain_ascii, use_color
from gyrovib.cli.options import (
    allocation_option,
    budget_option,
    files_argument,
    format_option,
    method_option,
    output_option,
    parse_allocation,
    parse_budget,
    parse_rate_option,
    parse_unit,
    rate_option,
    selection_options,
    unit_option,
)


@click.command()
@files_argument
@selection_options
@budget_option
@method_option
@rate_option
@unit_option
@allocation_option
@click.option("--criterion", type=click.Choice(["bounds", "rms", "both"]), default="bounds",
              show_default=True,
              help="What a pass means: every coefficient within its bound (the paper's "
                   "synthesis), Δ_V(RMS) ≤ budget (eq. 17), or both.")
@click.option("--require", type=click.Choice(["any", "all"]), default="any", show_default=True,
              help="Exit 1 unless at least one (any) or every (all) sensor passes under "
                   "every chosen profile.")
@format_option("table", "json", "csv", "markdown", "junit", "github")
@output_option
@click.pass_context
def select(ctx: click.Context, files: tuple[str, ...], sensors: tuple[str, ...],
           profiles: tuple[str, ...], budget: str, method: str, rate: str | None, unit: str,
           allocation: str | None, criterion: str, require: str, fmt: str,
           output: str | None) -> None:
    """Check every sensor against a budget: a pass/fail table and a ranking.

    Each sensor's bounds include its own frequency response; its |coefficients|
    are checked against them and its RMS error against the budget (eq. 17).
    Exit status 1 when the --require condition is not met.
    """
    from gyrovib import api
    from gyrovib.cli.output import write_output
    from gyrovib.render import select as render

    text: str | Iterator[str]  # the JSON document is streamed
    github_errors(fmt == "github")
    unit = parse_unit(unit)
    catalog = load_catalog(files)
    result = api.select(catalog, sensors=sensors, profiles=profiles, method=method,
                        rate=parse_rate_option(rate, unit), budget=parse_budget(budget, unit),
                        unit=unit, criterion=criterion, require=require,
                        allocation=parse_allocation(allocation))
    if fmt == "table":
        text = render.to_table(result, color=use_color(output), width=page_width(output),
                               ascii=plain_ascii(output))
    elif fmt == "github":
        text = render.to_github(result, api.sensor_locations(catalog, result.sensors))
    elif fmt == "json":
        text = render.to_json_chunks(result)  # streamed: never the whole document at once
    else:
        text = {"csv": render.to_csv, "markdown": render.to_markdown,
                "junit": render.to_junit}[fmt](result)
    write_output(text, output)
    if not result.requirement_met:
        ctx.exit(1)
