"""`gyrovib mission`: every sensor over every mission (docs/model.md section 12)."""

from __future__ import annotations

import click

from gyrovib.cli.lazy import runs
from gyrovib.cli.options import (
    files_argument,
    format_option,
    output_option,
    peak_factor_option,
    placement_option,
)
from gyrovib.cli.spec_options import assume_unknown_option

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
@click.option("--plot", metavar="PNG", default=None,
              help="Also draw θ(t) per sensor to PNG: the vibration angle segment by "
                   "segment inside the ±k·σ(t) noise cone, and the angle budget "
                   "(matplotlib).")
@click.pass_context
@runs("mission")
def mission(ctx: click.Context, files: tuple[str, ...], missions: tuple[str, ...],
            sensors: tuple[str, ...], budget: str | None, angle_budget: str | None,
            unit: str | None, placement: str | None, peak_factor: float,
            assume_unknown: str | None, require: str, fmt: str, output: str | None,
            coverage: float, plot: str | None) -> None:
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
