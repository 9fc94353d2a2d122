"""`gyrovib fit`: rate-table data to coefficient-form sensors (docs/model.md section 14)."""

from __future__ import annotations

import sys

import click

from gyrovib.cli.common import rendered, say
from gyrovib.cli.options import as_options, format_option
from gyrovib.cli.output import write_binary, write_output


@click.command()
@click.argument("table", metavar="TABLE")
@click.option("--output", "-o", metavar="FILE",
              help="Write the catalogue (YAML): one coefficient-form sensor per unit with its "
                   "uncertainty, and the lot entry with two or more units. '-': the catalogue "
                   "on standard output instead of the report.")
@click.option("--order", type=click.IntRange(1, 5), default=5, show_default=True, metavar="N",
              help="Highest power of the rate in eq. (1), 1 to 5.")
@click.option("--rate-unit", "rate_unit", default="deg/s", show_default=True, metavar="UNIT",
              help="Unit of the rate, rate_x1 and rate_x2 columns: deg/s, deg/h, rad/s, rpm. "
                   "The coefficients are written in it.")
@click.option("--output-unit", "output_unit", default=None, metavar="UNIT",
              help="Unit of the output column (a label: mV, V, LSB, or a rate unit); the "
                   "eq. (2) coefficients do not depend on it.")
@click.option("--plot", metavar="PNG",
              help="Write the residuals against the rate, one panel per unit (matplotlib).")
@format_option("table", "json", "csv", "markdown")
def fit(table: str, output: str | None, order: int, rate_unit: str, output_unit: str | None,
        plot: str | None, fmt: str) -> None:
    """Fit rate-table data: each unit's coefficients with their uncertainty, and the lot.

    Per unit, the least-squares fit of eq. (1) and the coefficients of eq. (2)
    with their standard uncertainties, correlations and t values, the residual
    rms and the fitted curve's nonlinearity (%FS); with two or more units, the
    lot's mean and spread (docs/model.md section 14).

    TABLE is a CSV file of at most 16 MiB ('-': standard input) with a header
    row: unit (optional), rate, output, and optionally rate_x1, rate_x2 (cross
    rates). Lines starting with '#' are comments. Each unit needs rates of both
    signs, enough distinct |rate| levels for --order, and more points than
    parameters. A lot whose spread is not measured (no more units than
    coefficients, identical units, a singular covariance) is written with a
    warning naming it: select --yield calls it unverified.
    """
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib import api
    from gyrovib.api.ratetable.reading import MAX_BYTES, STDIN, STDIN_NAME, read_rate_table_bytes
    from gyrovib.api.ratetable.yaml import fit_catalog
    from gyrovib.render import fit as render

    if table == STDIN:

        raw = sys.stdin.buffer.read(MAX_BYTES + 1) if sys.stdin is not None else b""
        data = read_rate_table_bytes(raw, STDIN_NAME, rate_unit, output_unit)
    else:
        data = api.read_rate_table(table, rate_unit, output_unit)
    result = as_options(api.fit(data, order))  # its warnings name the options
    for warning in result.warnings:
        say(f"gyrovib: warning: {warning}")
    if plot is not None:
        write_binary(render.residuals_png(result), plot)
    if output is not None:
        write_output(fit_catalog(result), output)
        if output == "-":
            return
    write_output(rendered(render, result, fmt), None)
