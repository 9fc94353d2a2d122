"""The body of `gyrovib select` (declared in :mod:`gyrovib.cli.select`)."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import click

from gyrovib import api
from gyrovib.cli.common import (
    github_errors,
    load_catalog,
    note_slow_table,
    page_width,
    plain_ascii,
    say,
    use_color,
)
from gyrovib.cli.options import budget_arguments
from gyrovib.cli.output import write_output
from gyrovib.cli.placement import is_triad, run_placed, write_triad
from gyrovib.cli.run.mission import select_mission
from gyrovib.cli.spec_options import parse_spec_weights
from gyrovib.render import select as render
from gyrovib.render import select_ci


def select(ctx: click.Context, files: tuple[str, ...], sensors: tuple[str, ...],
           placement: str | None, mission: str | None, angle_budget: str | None,
           profiles: tuple[str, ...], budget: str | None, method: str, rate: str | None,
           unit: str | None, allocation: str | None, peak_factor: float, criterion: str,
           spec_weights: str | None, assume_unknown: str | None, require: str,
           yield_target: float | None, seed: int, draws: int, fmt: str,
           output: str | None, coverage: float) -> None:
    """See :func:`gyrovib.cli.select.select`."""
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
    if is_triad(result):  # table, json, csv or markdown, per axis, and the worst axes
        write_triad(result, lambda one: render.to_table(
            one, color=use_color(output), width=page_width(output), ascii=plain_ascii(output))
            if fmt == "table" else {"json": render.to_json, "csv": render.to_csv,
                                    "markdown": render.to_markdown}[fmt](one), fmt, output)
        if not result.requirement_met:
            ctx.exit(1)
        return
    for note in result.notes:
        say(f"gyrovib: warning: {note}")
    text = _rendered(result, fmt, catalog, output)
    write_output(text, output)
    if not result.requirement_met:
        ctx.exit(1)


def _rendered(result: Any, fmt: str, catalog: Any, output: str | None) -> str | Iterator[str]:
    """The selection in ``fmt``; the JSON document is streamed, never whole at once."""
    if fmt == "table":  # a matrix row per sensor, then its ranking or what limits it
        note_slow_table(2 * len(result.sensors))
        return render.to_table(result, color=use_color(output), width=page_width(output),
                               ascii=plain_ascii(output))
    if fmt in ("github", "junit"):  # the CI formats
        return (select_ci.to_github(result, api.sensor_locations(catalog, result.sensors))
                if fmt == "github" else select_ci.to_junit(result))
    if fmt == "json":
        return render.to_json_chunks(result)
    return {"csv": render.to_csv, "markdown": render.to_markdown}[fmt](result)
