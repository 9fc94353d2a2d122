"""The body of `gyrovib analyze` (declared in :mod:`gyrovib.cli.analyze`)."""

from __future__ import annotations

from typing import Any

from gyrovib import api
from gyrovib.cli.common import (
    load_catalog,
    note_slow_table,
    page_width,
    plain_ascii,
    say,
    use_color,
)
from gyrovib.cli.options import parse_rate_option, parse_unit
from gyrovib.cli.output import write_output
from gyrovib.cli.placement import is_triad, run_placed, write_triad
from gyrovib.cli.progress import progress_bar
from gyrovib.errors import OptionError
from gyrovib.render import analysis as render


def analyze(files: tuple[str, ...], sensors: tuple[str, ...], profiles: tuple[str, ...],
            placement: str | None,
            method: str, samples: int, seed: int, rate: str | None, unit: str,
            peak_factor: float, detail: bool | None, fmt: str,
            output: str | None, recordings: tuple[str, ...], jobs: int, **rec: Any) -> None:
    """See :func:`gyrovib.cli.analyze.analyze`."""
    unit = parse_unit(unit)
    catalog = load_catalog(files)
    if jobs != 1 and not recordings:
        raise OptionError("--jobs runs recordings in processes: give it with --recording")
    if recordings:
        # lazy: the recording stack (readers, fit, fleet) is not loaded by a first analyze
        # of the catalogue (tests/test_startup.py)
        from gyrovib.cli.run.recording import analyze_recording, refuse_with_recording

        refuse_with_recording(profiles=profiles, rate=rate, method=method)
        if placement is not None:
            raise OptionError("--placement maps catalogue profiles; with --recording give "
                              "the recording's columns in sensor axes (--rate-columns)")
        analyze_recording(recordings, catalog, sensors, unit, fmt, output, rec, jobs)
        return

    with progress_bar("brute force", enabled=method == "numeric") as advance:
        result = run_placed(api.analyze, catalog, placement, fmt, sensors=sensors,
                            profiles=profiles, method=method,
                            rate=parse_rate_option(rate, unit), unit=unit, samples=samples,
                            seed=seed, progress=advance, peak_factor=peak_factor)
    if is_triad(result):
        write_triad(result, lambda r: render.to_table(r, color=use_color(output),
                                                      width=page_width(output),
                                                      ascii=plain_ascii(output))
                    if fmt == "table" else {"json": render.to_json, "csv": render.to_csv,
                                            "markdown": render.to_markdown}[fmt](r),
                    fmt, output)
        return
    for note in result.notes:
        say(f"gyrovib: warning: {note}")
    if fmt == "table":
        note_slow_table(len(result.sensors) * len(result.profiles))
        write_output(render.to_table(result, color=use_color(output), width=page_width(output),
                                     ascii=plain_ascii(output), detail=detail), output)
        return
    renderers = {"json": render.to_json, "csv": render.to_csv, "markdown": render.to_markdown}
    write_output(renderers[fmt](result), output)
