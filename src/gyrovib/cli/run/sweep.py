"""The body of `gyrovib sweep` (declared in :mod:`gyrovib.cli.sweep`)."""

from __future__ import annotations

from gyrovib import api, units
from gyrovib.cli.common import (
    load_catalog,
    note_slow_table,
    page_width,
    plain_ascii,
    say,
    use_color,
)
from gyrovib.cli.options import parse_budget, resolve_unit
from gyrovib.cli.output import write_binary, write_output
from gyrovib.cli.placement import is_triad, run_placed, write_triad
from gyrovib.cli.sweep import envelope_path, parse_rate_range
from gyrovib.errors import OptionError
from gyrovib.render import sweep as render
from gyrovib.render.plot import envelope_png, sweep_png


def sweep(files: tuple[str, ...], sensors: tuple[str, ...], profiles: tuple[str, ...],
          rate_range: str, budget: str | None, plot: str | None, log_scale: bool,
          unit: str | None, peak_factor: float, placement: str | None,
          fmt: str, output: str | None) -> None:
    """See :func:`gyrovib.cli.sweep.sweep`."""
    unit = resolve_unit(unit, budget or "")
    start, stop, count = parse_rate_range(rate_range, unit)
    budget_value = parse_budget(budget, unit) / units.scale(unit) if budget is not None else None

    result = run_placed(api.sweep, load_catalog(files), placement, fmt,
                        rates=api.rate_range(start, stop, count), sensors=sensors,
                        profiles=profiles, unit=unit, peak_factor=peak_factor)
    if is_triad(result):
        if plot is not None:
            raise OptionError("--plot draws one placement: give --placement x1=..,x2=..,x3=..")
        write_triad(result, lambda r: render.to_table(r, budget_value, width=page_width(output),
                                                      color=use_color(output),
                                                      ascii=plain_ascii(output))
                    if fmt == "table" else {"json": render.to_json,
                                            "csv": render.to_csv_chunks}[fmt](r, budget_value),
                    fmt, output)
        return
    if result.paper_refused:
        listed = "; ".join(f"{p} ({why})" for p, why in result.paper_refused.items())
        say(f"gyrovib: note: the paper's columns are empty for {listed}")
    if plot is not None:
        if plot == "-":
            raise OptionError("--plot writes a PNG file: give a file name, not '-'")

        write_binary(sweep_png(result, budget_value, log=log_scale), plot)
        envelope = envelope_png(result)
        if envelope is not None:  # datasheet sensors: their worst polynomials, a second PNG
            write_binary(envelope, envelope_path(plot))
    if fmt == "table":  # a table per sensor × profile, a row per rate
        note_slow_table(len(result.sensors) * len(result.profiles) * len(result.rates))
        write_output(render.to_table(result, budget_value, width=page_width(output),
                                     color=use_color(output),
                                     ascii=plain_ascii(output)), output)
        return
    renderers = {"json": render.to_json, "csv": render.to_csv_chunks}
    write_output(renderers[fmt](result, budget_value), output)
