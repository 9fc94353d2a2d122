"""What the bodies of `analyze --recording`, `report --recording`, `profile` and
`allan` share: a recording read with the options given, and its analysis."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.api.commands.recording import analyze_recording as run
from gyrovib.api.fleet.pool import one_thread
from gyrovib.api.fleet.run import RecordingOptions, analyze_recordings
from gyrovib.api.recordings.reading import parse_columns, read_recording
from gyrovib.api.recordings.yaml import with_fitted_profile
from gyrovib.cli.output import write_output
from gyrovib.cli.recording import fit_options
from gyrovib.errors import OptionError
from gyrovib.render import fleet as render_many
from gyrovib.render import recording as render
from gyrovib.render.recording import report_section


def step_options(options: dict[str, Any]) -> Any:
    """The parsed options as the one-recording step's :class:`RecordingOptions`."""

    return RecordingOptions(
        fs=options["fs"],
        rate_columns=parse_columns(options["rate_columns"], "--rate-columns"),
        accel_columns=parse_columns(options["accel_columns"], "--accel-columns"),
        rate_unit=options["rate_unit"], accel_unit=options["accel_unit"],
        topic=options["topic"], strict=options.get("strict", False),
        instance=options.get("instance"), preset=options.get("preset"),
        **fit_options(options))


def read(path: str, options: dict[str, Any]) -> Any:
    """The recording named on the command line, read with the options given."""

    return read_recording(
        path, fs=options["fs"],
        rate_columns=parse_columns(options["rate_columns"], "--rate-columns"),
        accel_columns=parse_columns(options["accel_columns"], "--accel-columns"),
        rate_unit=options["rate_unit"], accel_unit=options["accel_unit"],
        topic=options["topic"], strict=options.get("strict", False),
        instance=options.get("instance"), preset=options.get("preset"))


def analyze_recording(paths: tuple[str, ...], catalog: Any, sensors: tuple[str, ...], unit: str,
                      fmt: str, output: str | None, options: dict[str, Any],
                      jobs: int = 1) -> None:
    """``gyrovib analyze --recording`` (once or more): one library call, then the renderer."""

    if len(paths) == 1:

        with one_thread():  # one BLAS/OpenMP thread, as with --jobs 1 on several
            result = run(read(paths[0], options), catalog, sensors=sensors, unit=unit,
                         **fit_options(options))
        if fmt != "table" or output is not None:  # the table on the terminal lists them itself
            for warning in result.fit.warnings:
                click.echo(f"gyrovib: warning: {warning}", err=True)
        renderers = {"table": render.to_table, "json": render.to_json, "csv": render.to_csv,
                     "markdown": render.to_markdown}
        write_output(renderers[fmt](result), output)
        return

    many = analyze_recordings(paths, catalog, step_options(options),
                              sensors=sensors, unit=unit, jobs=jobs)
    many_renderers = {"table": render_many.to_table, "json": render_many.to_json,
                      "csv": render_many.to_csv, "markdown": render_many.to_markdown}
    write_output(many_renderers[fmt](many), output)


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
                     profiles: tuple[str, ...], unit: str, options: dict[str, Any],
                     ) -> tuple[Any, tuple[str, ...], str]:
    """``gyrovib report --recording``: the catalogue with the fitted profile added, the
    profiles to study (the fitted one too when some were named), and the HTML section."""

    result = run(read(path, options), catalog, sensors=sensors, unit=unit,
                 **fit_options(options))
    combined = with_fitted_profile(catalog, result.fit)
    chosen = (*profiles, result.fit.profile_id) if profiles else profiles
    return combined, chosen, report_section(result)
