"""The body of `gyrovib bounds` (declared in :mod:`gyrovib.cli.bounds`)."""

from __future__ import annotations

from gyrovib import api
from gyrovib.cli.common import load_catalog, page_width, plain_ascii, use_color
from gyrovib.cli.options import budget_arguments
from gyrovib.cli.output import write_output
from gyrovib.cli.placement import is_triad, run_placed, write_triad
from gyrovib.cli.spec_options import parse_range, parse_spec_weights
from gyrovib.render import bounds as render


def bounds(files: tuple[str, ...], profiles: tuple[str, ...], budget: str, method: str,
           rate: str | None, unit: str | None, allocation: str | None, range_: str | None,
           nl_fit: str, nl_measure: str, nl_of: str, spec_weights: str | None,
           placement: str | None, fmt: str, output: str | None) -> None:
    """See :func:`gyrovib.cli.bounds.bounds`."""
    catalog = load_catalog(files)  # validated whole; the bounds use the profiles only
    split = budget_arguments(budget, unit, rate, allocation)

    result = run_placed(api.bounds, catalog, placement, fmt, profiles=profiles, method=method,
                        **split, range_=parse_range(range_, split["unit"]), nl_fit=nl_fit,
                        nl_measure=nl_measure, nl_of=nl_of,
                        spec_weights=parse_spec_weights(spec_weights))

    def draw(one: api.BoundsResult) -> str:
        if fmt == "table":
            return render.to_table(one, color=use_color(output), width=page_width(output),
                                   ascii=plain_ascii(output))
        return {"json": render.to_json, "csv": render.to_csv,
                "markdown": render.to_markdown}[fmt](one)

    if is_triad(result):
        write_triad(result, draw, fmt, output)
        return
    write_output(draw(result), output)
