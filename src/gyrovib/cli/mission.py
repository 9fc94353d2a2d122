"""`gyrovib mission`: every sensor over every mission (docs/model.md section 12)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import click

from gyrovib.cli.common import (
    load_catalog,
    page_width,
    plain_ascii,
    rendered,
    say,
    use_color,
)
from gyrovib.cli.options import (
    files_argument,
    format_option,
    output_option,
    parse_angle_budget,
    parse_budget,
    parse_placement,
    peak_factor_option,
    placement_option,
    resolve_unit,
)
from gyrovib.cli.output import write_binary, write_output
from gyrovib.cli.spec_options import assume_unknown_option
from gyrovib.errors import OptionError

if TYPE_CHECKING:
    from gyrovib.api.missions import MissionResult

#: ``--coverage K`` of ``mission`` and ``select --mission`` (docs/model.md section 15).
coverage_option = click.option(
    "--coverage", type=float, default=1.0, show_default=True, metavar="K",
    help="Coverage factor k of the noise terms in each row's angle budget: total = |θ_V| + "
         "k·√(θ_ARW² + θ_B² + θ_RRW² + θ_R²) (1: one standard deviation; 2: about 95 %).")


@click.command()
@files_argument
@click.option("--mission", "missions", multiple=True, metavar="ID",
              help="Only this mission (repeatable).")
@click.option("--sensor", "sensors", multiple=True, metavar="ID",
              help="Only this sensor (repeatable).")
@click.option("--budget", metavar="B",
              help="Δ* on the mean RMS error Δ̄_RMS: a number in --unit, or with a unit "
                   "(36deg/h).")
@click.option("--angle-budget", "angle_budget", metavar="A",
              help="θ* on each row's budget total (|θ_V| plus the noise terms, "
                   "--coverage), with an angle unit: 0.5deg, '2 mrad', 30arcmin.")
@coverage_option
@click.option("--unit", default=None, metavar="UNIT",
              help="Rate unit of every output rate (deg/s, deg/h, rad/s, rpm); default: "
                   "the unit --budget is written in, else deg/s. The angle is in deg for "
                   "deg/s and deg/h, rad for rad/s, rev for rpm.")
@placement_option
@peak_factor_option
@assume_unknown_option
@click.option("--require", type=click.Choice(["any", "all"]), default="any", show_default=True,
              help="Exit 1 unless at least one (any) or every (all) sensor passes every "
                   "chosen mission (on every axis of a triad).")
@format_option("table", "json", "csv", "markdown", "junit")
@output_option
@click.option("--segments", is_flag=True,
              help="Also the budget segment by segment: each segment's Δ_V and, at its end, "
                   "θ_V summed so far, the noise terms over the time flown and the total "
                   "(a second table, also in markdown; with --format csv, one row per "
                   "segment instead of one "
                   "per sensor; JSON always has them).")
@click.option("--plot", metavar="PNG", default=None,
              help="Also draw θ(t) per sensor to PNG: the vibration angle segment by "
                   "segment inside the ±k·σ(t) noise cone, and the angle budget "
                   "(matplotlib).")
@click.pass_context
def mission(ctx: click.Context, files: tuple[str, ...], missions: tuple[str, ...],
            sensors: tuple[str, ...], budget: str | None, angle_budget: str | None,
            unit: str | None, placement: str | None, peak_factor: float,
            assume_unknown: str | None, require: str, fmt: str, output: str | None,
            coverage: float, segments: bool, plot: str | None) -> None:
    """Each sensor over each mission: mean error, angle θ_V, mean RMS, worst segment,
    and the whole angle budget.

    A mission is an ordered list of segments (profile, duration, optional
    carrier rate) in the catalogue's `missions:`. A sensor passes when no
    segment saturates it and its budget total ≤ --angle-budget (or Δ̄_RMS ≤
    --budget). The budget adds to |θ_V| the noise over the mission's duration T
    (docs/model.md section 15): N·√T, B·T, K·T^1.5/√3 and R·T from the
    sensor's noise: block, in quadrature, times --coverage; a figure not given
    is unknown ('?'), the total a lower bound. A datasheet sensor is taken at
    the worst conversion function over the whole mission; one that passes on
    its published figures while an unpublished one (VRE, m31, m32, a noise
    figure) can decide it is 'unverified', not passing (--assume-unknown zero takes them as 0). Exit
    status 1 when the
    --require condition is not met.
    """
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib import api
    from gyrovib.render.mission_plot import theta_png

    if budget is not None and angle_budget is not None:
        raise OptionError("give --budget (on the mean RMS) or --angle-budget (on the angle), "
                          "not both")
    unit = resolve_unit(unit, budget)
    catalog = load_catalog(files)
    result = api.mission(
        catalog, missions=missions, sensors=sensors,
        budget=None if budget is None else parse_budget(budget, unit),
        angle_budget=None if angle_budget is None else parse_angle_budget(angle_budget),
        unit=unit, require=require, placement=parse_placement(placement),
        peak_factor=peak_factor, assume_unknown=assume_unknown or "none", coverage=coverage)
    if segments and fmt not in ("table", "csv", "json", "markdown"):
        raise OptionError("--segments: use --format table, markdown, csv or json (JSON "
                          "always has the segments)")
    _show(result, fmt, output, segments=segments)
    if plot is not None:
        write_binary(theta_png(result), plot)
    if not result.requirement_met:
        ctx.exit(1)


def _show(result: MissionResult, fmt: str, output: str | None, segments: bool = False) -> None:
    """The result's notes on standard error, then the result in ``fmt`` (table, json, csv,
    markdown or junit) to standard output or ``output``; ``segments``: the budget segment
    by segment too (table, markdown, csv)."""
    # lazy: the library and the renderers load when it runs, not for --help
    from gyrovib.render import mission as render
    from gyrovib.render.mission_answer import answer_line

    for note in result.notes:
        say(f"gyrovib: warning: {note}")
    answer = answer_line(result)
    if answer is not None:  # the answer first, on standard error: the data stay clean
        say(f"gyrovib: {answer}")
    if segments and fmt == "table":
        document = render.to_table(result, color=use_color(output),
                                   width=page_width(output), ascii=plain_ascii(output),
                                   segments=True)
    elif segments and fmt in ("csv", "markdown"):
        document = getattr(render, f"to_{fmt}")(result, segments=True)
    else:
        document = rendered(render, result, fmt, output)
    write_output(document, output)


def select_mission(files: tuple[str, ...], mission_id: str | None, sensors: tuple[str, ...],
                   profiles: tuple[str, ...], budget: str | None, angle_budget: str | None,
                   unit: str | None, placement: str | None, peak_factor: float,
                   require: str, fmt: str, output: str | None,
                   assume_unknown: str = "none", coverage: float = 1.0) -> bool:
    """``select --mission ID``: the mission's verdicts in select's formats, the sensors
    ranked on their budget total; returns whether the --require condition is met."""
    # lazy: the library and the renderers load when it runs, not for --help
    from gyrovib import api
    from gyrovib.api.noise import ranked

    if mission_id is None:
        raise OptionError("--angle-budget needs --mission ID (select on a mission)")
    if profiles:
        raise OptionError("--mission selects on the mission's own profiles: drop --profile")
    if (budget is None) == (angle_budget is None):
        raise OptionError("with --mission give --budget (on the mean RMS) or --angle-budget "
                          "(on the angle), one of them")
    if fmt == "github":
        raise OptionError("--mission: use --format table, json, csv, markdown or junit")
    unit = resolve_unit(unit, budget)

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
    # lazy: the library and the renderers load when it runs, not for --help
    from gyrovib import api
    from gyrovib.render.report_mission import mission_section as section

    result = api.mission(
        catalog, missions=missions, sensors=sensors,  # type: ignore[arg-type]
        angle_budget=None if angle_budget is None else parse_angle_budget(angle_budget),
        unit=unit, peak_factor=peak_factor, assume_unknown=assume_unknown, coverage=coverage,
        placement=parse_placement(placement))
    noise = {e.sensor.id: ({} if e.sensor.noise is None else e.sensor.noise.figures())
             for e in catalog.sensors if e.sensor.id in result.sensors}  # type: ignore[attr-defined]
    rate_units = {e.mission.id: e.unit for e in catalog.missions}  # type: ignore[attr-defined]
    return section(result, noise, rate_units)
