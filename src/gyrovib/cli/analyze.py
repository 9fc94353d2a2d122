"""`gyrovib analyze`: the direct problem."""

from __future__ import annotations

from typing import Any

import click

from gyrovib import units
from gyrovib.cli.common import (
    load_catalog,
    note_slow_table,
    rendered,
    say,
)
from gyrovib.cli.options import (
    as_options,
    files_argument,
    format_option,
    output_option,
    parse_rate_option,
    peak_factor_option,
    placement_option,
    rate_option,
    selection_options,
    unit_option,
)
from gyrovib.cli.output import write_output
from gyrovib.cli.placement import is_triad, run_placed, write_triad
from gyrovib.cli.progress import progress_bar
from gyrovib.cli.recording import (
    analyze_recording,
    jobs_option,
    recording_of,
    recording_options,
    refuse_with_recording,
)
from gyrovib.errors import OptionError
from gyrovib.limits import MAX_SAMPLES, MIN_SAMPLES


@click.command()
@files_argument
@selection_options
@click.option("--method", type=click.Choice(["exact", "paper", "numeric"]), default="exact",
              show_default=True,
              help="exact: exact moments; paper: the paper's printed formulas; "
                   "numeric: brute-force average of eq. (2) (total ± stderr).")
@click.option("--samples", type=click.IntRange(min=MIN_SAMPLES, max=MAX_SAMPLES), default=200_000,
              show_default=True, metavar="N",
              help=f"numeric: evaluations of eq. (2) per sensor × profile, "
                   f"{MIN_SAMPLES} to {MAX_SAMPLES:,}.")
@click.option("--seed", type=click.IntRange(min=0), default=0, show_default=True,
              metavar="S", help="numeric: random seed; the same seed gives the same numbers.")
@rate_option
@placement_option
@unit_option
@peak_factor_option
@click.option("--detail/--matrix", "detail", default=None,
              help="Tables: one table per profile with every term of eq. (13) (the default "
                   "with one or two profiles), or one compact matrix of the errors and their "
                   "dominant terms (the default with more).")
@format_option("table", "json", "csv", "markdown")
@output_option
@click.option("--recording", "recordings", metavar="RECORDING", multiple=True,
              help="Δ_V,rec of every sensor on a recording (docs/model.md section 13), beside "
                   "the fitted profile's closed form; see `gyrovib profile` for its options. "
                   "Repeat it for several recordings: each is reported, then each sensor's "
                   "worst.")
@recording_options
@jobs_option
def analyze(files: tuple[str, ...], sensors: tuple[str, ...], profiles: tuple[str, ...],
            placement: str | None,
            method: str, samples: int, seed: int, rate: str | None, unit: str,
            peak_factor: float, detail: bool | None, fmt: str,
            output: str | None, recordings: tuple[str, ...], jobs: int, **rec: Any) -> None:
    """The direct problem: the vibration error of every sensor under every profile.

    Computes the additive terms Δ0 (eq. 14/15), Δ_VA, Δ_VM, the total Δ_V
    (eq. 13) and the RMS error Δ_V(RMS) (eq. 16).

    With --method numeric the total Δ_V is the average of eq. (2) itself over
    the vibration minus eq. (2) at rest, with its standard error; the term
    breakdown uses the sample moments of the same samples.

    A sensor driven past its range (|Ω_K3| + Σ tone amplitudes + locked
    peaks + κσ3 > range, κ = --peak-factor) is marked saturated.
    """
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib import api
    from gyrovib.render import analysis as render

    unit = units.canonical_unit(unit)
    catalog = load_catalog(files)
    if jobs != 1 and not recordings:
        raise OptionError("--jobs runs recordings in processes: give it with --recording")
    if recordings:
        refuse_with_recording(profiles=profiles, rate=rate, method=method)
        if placement is not None:
            raise OptionError("--placement maps catalogue profiles; with --recording give "
                              "the recording's columns in sensor axes (--rate-columns)")
        analyze_recording(recordings, catalog, sensors, unit, fmt, output, recording_of(rec),
                          jobs)
        return

    with progress_bar("brute force", enabled=method == "numeric") as advance:
        result = run_placed(api.analyze, catalog, placement, fmt, sensors=sensors,
                            profiles=profiles, method=method,
                            rate=parse_rate_option(rate, unit), unit=unit, samples=samples,
                            seed=seed, progress=advance, peak_factor=peak_factor)
    result = as_options(result)  # a lot's note names select's option, not its argument
    if is_triad(result):
        write_triad(result, lambda r: rendered(render, r, fmt, output), fmt, output)
        return
    for note in result.notes:
        say(f"gyrovib: warning: {note}")
    if fmt == "table":
        note_slow_table(len(result.sensors) * len(result.profiles))
    write_output(rendered(render, result, fmt, output, detail=detail), output)
