"""Options and calls shared by ``gyrovib profile`` and ``gyrovib analyze --recording``."""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

import click

from gyrovib.cli.common import rendered
from gyrovib.cli.options import as_options
from gyrovib.cli.output import write_output
from gyrovib.errors import OptionError
from gyrovib.limits import (
    DEFAULT_BREAKPOINTS,
    DEFAULT_CROSSOVER,
    DEFAULT_RESOLUTION,
    DEFAULT_THRESHOLD,
)

if TYPE_CHECKING:
    from gyrovib.api.fleet.run import RecordingOptions

F = TypeVar("F", bound=Callable[..., Any])


def reader_options(f: F) -> F:
    """How a recording is read (docs/recordings.md): its columns, units,
    topic, instance, preset and sample rate, and whether damage is refused; shared by
    ``profile``, ``analyze --recording``, ``report --recording`` and ``allan``."""
    options = [
        click.option("--strict", is_flag=True,
                     help="Refuse (exit status 2) a recording that is only warned about "
                          "otherwise: a log cut short, with corrupt data or with clipped "
                          "samples."),
        click.option("--preset", type=click.Choice(["betaflight"]), default=None,
                     help="A CSV written by another tool: betaflight (blackbox_decode's "
                          "time (us), gyroADC[0..2] in deg/s, accSmooth[0..2])."),
        click.option("--instance", type=click.IntRange(min=0), default=None, metavar="N",
                     help="Which instance of the topic or message (a log with several "
                          "gyros); default: the only one."),
        click.option("--topic", metavar="NAME",
                     help="ULog topic (default sensor_combined; sensor_gyro, "
                          "sensor_gyro_fifo) or DataFlash message (IMU, the default, or "
                          "batch)."),
        click.option("--accel-unit", metavar="UNIT",
                     help="Unit of the accelerations: g or m/s^2 (default g; ULog m/s^2)."),
        click.option("--rate-unit", metavar="UNIT",
                     help="Unit of the rates: deg/s, deg/h, rad/s, rpm (default deg/s; "
                          "ULog rad/s)."),
        click.option("--accel-columns", metavar="X,Y,Z",
                     help="Acceleration columns: names or 0-based indices, - for none."),
        click.option("--rate-columns", metavar="X,Y,Z",
                     help="Rate columns: names or 0-based indices, - for an axis not "
                          "recorded (default: the first three columns other than t/time)."),
        click.option("--fs", type=float, metavar="HZ",
                     help="Sample rate, Hz, for a recording without a time column."),
    ]
    for option in options:
        f = option(f)
    return f


def recording_options(f: F) -> F:
    """The recording input and fit options (docs/recordings.md)."""
    options = [
        click.option("--id", "profile_id", metavar="NAME",
                     help="Id of the fitted profile (default: the file's name + -fitted)."),
        click.option("--independent-tones", is_flag=True,
                     help="Write integer-multiple lines as independent tones, not as one "
                          "phase-locked harmonics group (phase: worst)."),
        click.option("--breakpoints", type=click.IntRange(min=2), default=DEFAULT_BREAKPOINTS,
                     show_default=True, metavar="B",
                     help="At most B log-log breakpoints for the random part's PSD: the "
                          "best set for the power-weighted log error, the variance held."),
        click.option("--tone-threshold", type=float, default=DEFAULT_THRESHOLD, show_default=True,
                     metavar="DB", help="A line stands this many dB above the running median."),
        click.option("--resolution", type=float, default=DEFAULT_RESOLUTION, show_default=True,
                     metavar="DF", help="Frequency resolution of the Welch PSD, Hz."),
        click.option("--crossover", type=float, default=DEFAULT_CROSSOVER, show_default=True,
                     metavar="F",
                     help="f_c, Hz: below it the carrier's manoeuvres, above it vibration."),
    ]
    for option in options:
        f = option(f)
    return reader_options(f)


def jobs_option(f: F) -> F:
    """``--jobs N``: recordings fitted in N worker processes (docs/recordings.md)."""
    return click.option(
        "--jobs", type=click.IntRange(min=1), default=1, show_default=True, metavar="N",
        help="Fit the recordings in N worker processes (the output is the same as with 1; "
             "memory grows with N, one recording per worker).")(f)


def recording_of(given: dict[str, Any]) -> RecordingOptions:
    """The parsed reader and fit options, once, as one :class:`RecordingOptions` (a
    command with only :func:`reader_options` leaves the fit's at their defaults)."""
    # lazy: the library and the renderers load when it runs, not for --help
    from gyrovib.api.fleet.run import RecordingOptions
    from gyrovib.api.recordings.reading import parse_columns

    named = {f.name for f in dataclasses.fields(RecordingOptions)} - {"responses"}
    return RecordingOptions(**{
        **{k: v for k, v in given.items() if k in named},
        "rate_columns": parse_columns(given["rate_columns"], "rate_columns"),
        "accel_columns": parse_columns(given["accel_columns"], "accel_columns")})


def analyze_recording(paths: tuple[str, ...], catalog: Any, sensors: tuple[str, ...], unit: str,
                      fmt: str, output: str | None, options: RecordingOptions,
                      jobs: int = 1) -> None:
    """``gyrovib analyze --recording`` (once or more): one library call, then the renderer."""
    # lazy: the library and the renderers load when it runs, not for --help
    from gyrovib.api.fleet.pool import one_thread
    from gyrovib.api.fleet.run import analyze_recordings
    from gyrovib.api.recordings.analysis import analyze_recording as run
    from gyrovib.render import fleet as render_many
    from gyrovib.render import recording as render

    if len(paths) == 1:

        with one_thread():  # one BLAS/OpenMP thread, as with --jobs 1 on several
            result = run(options.read(paths[0]), catalog, sensors=sensors, unit=unit,
                         **options.fit_arguments())
        result = as_options(result)  # its notes name the options, not the arguments
        if fmt != "table" or output is not None:  # the table on the terminal lists them itself
            base = f"{os.path.basename(result.fit.file)}: "  # every warning names its file
            for warning in result.fit.warnings:
                named = warning if warning.startswith(base) else base + warning
                click.echo(f"gyrovib: warning: {named}", err=True)
        write_output(rendered(render, result, fmt, output), output)
        return

    many = as_options(analyze_recordings(paths, catalog, options,
                                         sensors=sensors, unit=unit, jobs=jobs))
    write_output(rendered(render_many, many, fmt, output), output)


def refuse_with_recording(**given: Any) -> None:
    """Options of ``analyze`` that mean nothing with ``--recording``: refused, not ignored."""

    bad = []
    if given["profiles"]:
        bad.append("--profile (the recording is the profile)")
    if given["rate"] is not None:
        bad.append("--rate (the carrier rate is the recorded one)")
    if given["method"] != "exact":
        bad.append("--method (Δ_V,rec is the recording's own average; the fit uses exact)")
    if bad:
        raise OptionError(f"--recording does not take {', '.join(bad)}")


def report_recording(path: str, catalog: Any, sensors: tuple[str, ...],
                     profiles: tuple[str, ...], unit: str, options: RecordingOptions,
                     ) -> tuple[Any, tuple[str, ...], str]:
    """``gyrovib report --recording``: the catalogue with the fitted profile added, the
    profiles to study (the fitted one too when some were named), and the HTML section."""
    # lazy: the library and the renderers load when it runs, not for --help
    from gyrovib.api.recordings.analysis import analyze_recording as run
    from gyrovib.api.recordings.yaml import with_fitted_profile
    from gyrovib.render.recording import report_section

    result = as_options(run(options.read(path), catalog, sensors=sensors, unit=unit,
                            **options.fit_arguments()))  # its notes name the options
    combined = with_fitted_profile(catalog, result.fit)
    chosen = (*profiles, result.fit.profile_id) if profiles else profiles
    return combined, chosen, report_section(result)
