"""`gyrovib sweep`: the vibration error over a range of carrier rates Ω_K3."""

from __future__ import annotations

import click

from gyrovib import units
from gyrovib.cli.common import (
    load_catalog,
    note_slow_table,
    rendered,
    say,
)
from gyrovib.cli.options import (
    budget_unit_option,
    files_argument,
    format_option,
    output_option,
    parse_budget,
    peak_factor_option,
    placement_option,
    resolve_unit,
    selection_options,
)
from gyrovib.cli.output import write_binary, write_output
from gyrovib.cli.placement import is_triad, run_placed, write_triad
from gyrovib.errors import OptionError

DEFAULT_RANGE = "-200:200:401"


def parse_rate_range(text: str, unit: str) -> tuple[float, float, int]:
    """``START:STOP:COUNT`` with START, STOP in ``unit`` → (start, stop in deg/s, count)."""
    pieces = text.replace(" ", "").split(":")
    if len(pieces) != 3 or not all(pieces):
        raise OptionError(f"--rate-range {text!r}: write START:STOP:COUNT, e.g. {DEFAULT_RANGE}")
    try:
        start = units.quantity(pieces[0], unit)
        stop = units.quantity(pieces[1], unit)
    except OptionError as exc:
        raise OptionError(f"--rate-range: {exc.problems[0].message}") from None
    try:
        count = int(pieces[2])
    except ValueError:
        raise OptionError(f"--rate-range {text!r}: COUNT must be a whole number") from None
    if count < 1:
        raise OptionError(f"--rate-range {text!r}: COUNT must be at least 1")
    return start, stop, count


def envelope_path(plot: str) -> str:
    """``out.png`` → ``out-envelope.png``: where the envelope plot goes."""
    stem, dot, ext = plot.rpartition(".")
    return f"{stem}-envelope.{ext}" if dot and stem else f"{plot}-envelope.png"


@click.command()
@files_argument
@selection_options
@click.option("--rate-range", "rate_range", default=DEFAULT_RANGE, show_default=True,
              metavar="START:STOP:COUNT",
              help="Ω_K3 values: COUNT evenly spaced from START to STOP inclusive, each in "
                   "--unit unless it carries its own unit, which is converted "
                   "(-1deg/s:1deg/s:101 with --unit deg/h runs from -3600 to 3600 deg/h).")
@click.option("--budget", metavar="B",
              help="Δ*_V, drawn as a band on the plot (number in --unit, or e.g. 36deg/h).")
@click.option("--plot", "plot", metavar="FILE.png",
              help="Also draw Δ_V and Δ_V(RMS) against Ω_K3 into this PNG (needs "
                   "matplotlib: pip install 'gyrovib[plot]'); with datasheet sensors, "
                   "their worst polynomials against the NL envelope into FILE-envelope.png.")
@click.option("--log", "log_scale", is_flag=True,
              help="Plot on logarithmic (Δ_V(RMS)) and symmetric-log (Δ_V) axes.")
@budget_unit_option
@peak_factor_option
@placement_option
@format_option("table", "json", "csv")
@output_option
def sweep(files: tuple[str, ...], sensors: tuple[str, ...], profiles: tuple[str, ...],
          rate_range: str, budget: str | None, plot: str | None, log_scale: bool,
          unit: str | None, peak_factor: float, placement: str | None,
          fmt: str, output: str | None) -> None:
    """Δ_V and Δ_V(RMS) over a range of Ω_K3, exact and paper side by side.

    Each profile's Ω_K3 is replaced by every rate of --rate-range (Ω_K1, Ω_K2
    stay the profile's); a value at a rate equals `analyze --rate` at that
    rate. Where the paper's formulas do not cover a profile (several tones, or
    tones with random vibration) its paper columns are left empty.
    """
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib import api, units
    from gyrovib.render import sweep as render
    from gyrovib.render.plot import envelope_png, sweep_png

    unit = resolve_unit(unit, budget)
    start, stop, count = parse_rate_range(rate_range, unit)
    budget_value = parse_budget(budget, unit) / units.scale(unit) if budget is not None else None

    result = run_placed(api.sweep, load_catalog(files), placement, fmt,
                        rates=api.rate_range(start, stop, count), sensors=sensors,
                        profiles=profiles, unit=unit, peak_factor=peak_factor)
    if is_triad(result):
        if plot is not None:
            raise OptionError("--plot draws one placement: give --placement x1=..,x2=..,x3=..")
        write_triad(result, lambda r: rendered(render, r, fmt, output, budget_value), fmt,
                    output)
        return
    if result.paper_refused:
        by_reason: dict[str, list[str]] = {}  # one reason once, with every profile it has
        for p, why in result.paper_refused.items():
            by_reason.setdefault(why, []).append(p)
        listed = "; ".join(f"{', '.join(ps)} ({why})" for why, ps in by_reason.items())
        say(f"gyrovib: note: the paper's columns are empty for {listed}")
    if result.g2_unknown:
        under: dict[str, list[str]] = {}  # each sensor once, with every profile it has
        for sensor, profile in result.g2_unknown:
            under.setdefault(sensor, []).append(profile)
        pairs = "; ".join(f"{s} under {', '.join(ps)}" for s, ps in under.items())
        say(f"gyrovib: note: Δ_V and Δ_V(RMS) are unknown ('?', null) for {pairs}: the "
            "sensor gives no g² figure (g2_sensitivity or vre; a datasheet, no VRE) and the "
            "profile has linear vibration, so its g² term is unknown, not zero (`vre: 0` "
            "states a known zero)")
    if plot is not None:
        if plot == "-":
            raise OptionError("--plot writes a PNG file: give a file name, not '-'")

        write_binary(sweep_png(result, budget_value, log=log_scale), plot)
        envelope = envelope_png(result)
        if envelope is not None:  # datasheet sensors: their worst polynomials, a second PNG
            write_binary(envelope, envelope_path(plot))
    if fmt == "table":  # a table per sensor × profile, a row per rate
        note_slow_table(len(result.sensors) * len(result.profiles) * len(result.rates))
    write_output(rendered(render, result, fmt, output, budget_value), output)
