"""`gyrovib analyze`: the direct problem."""

from __future__ import annotations

import click

from gyrovib.cli.common import load_catalog, use_color
from gyrovib.cli.options import (
    files_argument,
    format_option,
    output_option,
    parse_rate_option,
    parse_unit,
    rate_option,
    selection_options,
    unit_option,
)


@click.command()
@files_argument
@selection_options
@click.option("--method", type=click.Choice(["exact", "paper"]), default="exact",
              show_default=True,
              help="exact: exact moments; paper: the paper's printed formulas.")
@rate_option
@unit_option
@format_option("table", "json", "csv", "markdown")
@output_option
def analyze(files: tuple[str, ...], sensors: tuple[str, ...], profiles: tuple[str, ...],
            method: str, rate: str | None, unit: str, fmt: str, output: str | None) -> None:
    """The direct problem: the vibration error of every sensor under every profile.

    Computes the additive terms Δ0 (eq. 14/15), Δ_VA, Δ_VM, the total Δ_V
    (eq. 13) and the RMS error Δ_V(RMS) (eq. 16).
    """
    from gyrovib import api
    from gyrovib.cli.output import write_output
    from gyrovib.render import analysis as render

    unit = parse_unit(unit)
    result = api.analyze(load_catalog(files), sensors=sensors, profiles=profiles, method=method,
                         rate=parse_rate_option(rate, unit), unit=unit)
    if fmt == "table":
        write_output(render.to_table(result, color=use_color(output)), output)
        return
    renderers = {"json": render.to_json, "csv": render.to_csv, "markdown": render.to_markdown}
    write_output(renderers[fmt](result), output)
