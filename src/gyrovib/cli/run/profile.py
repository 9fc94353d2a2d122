"""The body of `gyrovib profile` (declared in :mod:`gyrovib.cli.profile`)."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.api.commands.recording import fit_recording
from gyrovib.api.fleet.envelope import profile_recordings
from gyrovib.api.fleet.pool import one_thread
from gyrovib.cli.output import write_output
from gyrovib.cli.recording import fit_options
from gyrovib.cli.run.recording import read, step_options
from gyrovib.render import fleet as render
from gyrovib.render.recording import honesty_table, plot_fit


def profile(recordings: tuple[str, ...], jobs: int, plot: str | None, fmt: str,
            output: str | None, **options: Any) -> None:
    """See :func:`gyrovib.cli.profile.profile`."""

    if len(recordings) == 1:

        with one_thread():  # one BLAS/OpenMP thread, as with --jobs 1 on several
            fit = fit_recording(read(recordings[0], options), **fit_options(options))
        table = honesty_table(fit)
        document = render.profile_json(fit) if fmt == "json" else fit.yaml
    else:

        env = profile_recordings(recordings, step_options(options), jobs=jobs)
        fit, table = env.fit, render.envelope_table(env)
        document = render.envelope_json(env) if fmt == "json" else fit.yaml
    write_output(document, output)
    click.echo(table, err=True, nl=False)
    if plot is not None:
        plot_fit(fit, plot)
