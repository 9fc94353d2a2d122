"""The body of `gyrovib mission` (declared in :mod:`gyrovib.cli.mission`), and the mission
parts of `select --mission` and `report --mission`."""

from __future__ import annotations

import click

from gyrovib import api, units
from gyrovib.api.missions import MissionResult
from gyrovib.api.noise import ranked
from gyrovib.cli.common import load_catalog, page_width, plain_ascii, say, use_color
from gyrovib.cli.options import (
    parse_angle_budget,
    parse_budget,
    parse_placement,
    parse_unit,
)
from gyrovib.cli.output import write_binary, write_output
from gyrovib.errors import OptionError
from gyrovib.render import mission as render
from gyrovib.render.mission_answer import answer_line
from gyrovib.render.mission_plot import theta_png
from gyrovib.render.report_mission import mission_section as section


def mission(ctx: click.Context, files: tuple[str, ...], missions: tuple[str, ...],
            sensors: tuple[str, ...], budget: str | None, angle_budget: str | None,
            unit: str | None, placement: str | None, peak_factor: float,
            assume_unknown: str | None, require: str, fmt: str, output: str | None,
            coverage: float, plot: str | None) -> None:
    """See :func:`gyrovib.cli.mission.mission`."""

    if budget is not None and angle_budget is not None:
        raise OptionError("give --budget (on the mean RMS) or --angle-budget (on the angle), "
                          "not both")
    if unit is not None:
        unit = parse_unit(unit)
    else:
        unit = (units.quantity_unit(budget) if budget is not None else None) or "deg/s"
    catalog = load_catalog(files)
    result = api.mission(
        catalog, missions=missions, sensors=sensors,
        budget=None if budget is None else parse_budget(budget, unit),
        angle_budget=None if angle_budget is None else parse_angle_budget(angle_budget),
        unit=unit, require=require, placement=parse_placement(placement),
        peak_factor=peak_factor, assume_unknown=assume_unknown or "none", coverage=coverage)
    _show(result, fmt, output)
    if plot is not None:
        write_binary(theta_png(result), plot)
    if not result.requirement_met:
        ctx.exit(1)


def _show(result: MissionResult, fmt: str, output: str | None) -> None:
    """The result's notes on standard error, then the result in ``fmt`` (table, json, csv,
    markdown or junit) to standard output or ``output``."""
    for note in result.notes:
        say(f"gyrovib: warning: {note}")
    answer = answer_line(result)
    if answer is not None:  # the answer first, on standard error: the data stay clean
        say(f"gyrovib: {answer}")
    if fmt == "table":
        text = render.to_table(result, color=use_color(output), width=page_width(output),
                               ascii=plain_ascii(output))
    else:
        text = {"json": render.to_json, "csv": render.to_csv, "markdown": render.to_markdown,
                "junit": render.to_junit}[fmt](result)
    write_output(text, output)


def select_mission(files: tuple[str, ...], mission_id: str | None, sensors: tuple[str, ...],
                   profiles: tuple[str, ...], budget: str | None, angle_budget: str | None,
                   unit: str | None, placement: str | None, peak_factor: float,
                   require: str, fmt: str, output: str | None,
                   assume_unknown: str = "none", coverage: float = 1.0) -> bool:
    """``select --mission ID``: the mission's verdicts in select's formats, the sensors
    ranked on their budget total; returns whether the --require condition is met."""

    if mission_id is None:
        raise OptionError("--angle-budget needs --mission ID (select on a mission)")
    if profiles:
        raise OptionError("--mission selects on the mission's own profiles: drop --profile")
    if (budget is None) == (angle_budget is None):
        raise OptionError("with --mission give --budget (on the mean RMS) or --angle-budget "
                          "(on the angle), one of them")
    if fmt == "github":
        raise OptionError("--mission: use --format table, json, csv, markdown or junit")
    unit = parse_unit(unit) if unit is not None else (
        (units.quantity_unit(budget) if budget is not None else None) or "deg/s")

    result = ranked(api.mission(
        load_catalog(files), missions=(mission_id,), sensors=sensors,
        budget=None if budget is None else parse_budget(budget, unit),
        angle_budget=None if angle_budget is None else parse_angle_budget(angle_budget),
        unit=unit, require=require, placement=parse_placement(placement),
        peak_factor=peak_factor, assume_unknown=assume_unknown, coverage=coverage))
    _show(result, fmt, output)
    return result.requirement_met


def mission_section(catalog: object, missions: tuple[str, ...], sensors: tuple[str, ...],
                    angle_budget: str | None, unit: str, peak_factor: float,
                    assume_unknown: str = "none", coverage: float = 1.0,
                    placement: str | None = None) -> str:
    """``report --mission``: the HTML of the mission section (``placement``: replacing
    each mission's own)."""

    result = api.mission(
        catalog, missions=missions, sensors=sensors,  # type: ignore[arg-type]
        angle_budget=None if angle_budget is None else parse_angle_budget(angle_budget),
        unit=unit, peak_factor=peak_factor, assume_unknown=assume_unknown, coverage=coverage,
        placement=parse_placement(placement))
    noise = {e.sensor.id: ({} if e.sensor.noise is None else e.sensor.noise.figures())
             for e in catalog.sensors if e.sensor.id in result.sensors}  # type: ignore[attr-defined]
    return section(result, noise)
