"""The body of `gyrovib fit` (declared in :mod:`gyrovib.cli.fit`)."""

from __future__ import annotations

import sys

from gyrovib import api
from gyrovib.api.ratetable.reading import MAX_BYTES, STDIN, STDIN_NAME, read_rate_table_bytes
from gyrovib.api.ratetable.yaml import fit_catalog
from gyrovib.cli.common import page_width, plain_ascii, say, use_color
from gyrovib.cli.output import write_binary, write_output
from gyrovib.render import fit as render


def fit(table: str, output: str | None, order: int, rate_unit: str, output_unit: str | None,
        plot: str | None, fmt: str) -> None:
    """See :func:`gyrovib.cli.fit.fit`."""

    if table == STDIN:

        raw = sys.stdin.buffer.read(MAX_BYTES + 1) if sys.stdin is not None else b""
        data = read_rate_table_bytes(raw, STDIN_NAME, rate_unit, output_unit)
    else:
        data = api.read_rate_table(table, rate_unit, output_unit)
    result = api.fit(data, order)
    for warning in result.warnings:
        say(f"gyrovib: warning: {warning}")
    if plot is not None:
        write_binary(render.residuals_png(result), plot)
    if output is not None:
        write_output(fit_catalog(result), output)
        if output == "-":
            return
    if fmt == "table":
        text = render.to_table(result, color=use_color(), width=page_width(),
                               ascii=plain_ascii())
    else:
        text = {"json": render.to_json, "csv": render.to_csv,
                "markdown": render.to_markdown}[fmt](result)
    write_output(text, None)
