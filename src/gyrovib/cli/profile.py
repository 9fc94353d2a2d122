"""`gyrovib profile`: fit a catalogue profile to one recording or the envelope of several
(docs/model.md section 13, docs/fleet.md)."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.cli.options import as_options, format_option, output_option
from gyrovib.cli.output import write_output
from gyrovib.cli.recording import jobs_option, recording_of, recording_options


@click.command()
@click.argument("recordings", metavar="RECORDING...", nargs=-1, required=True)
@recording_options
@jobs_option
@click.option("--plot", metavar="PNG", help="Plot the measured PSD against the fit, per axis, "
              "each panel titled with its shape figures (several recordings: their envelope).")
@format_option("yaml", "json")
@output_option
def profile(recordings: tuple[str, ...], jobs: int, plot: str | None, fmt: str,
            output: str | None, **options: Any) -> None:
    """Fit a profile (and its carrier mission) to a RECORDING, or to the envelope of several.

    RECORDING: CSV with a header row (time column t/time in s, or --fs),
    .npy (2-D, columns; read from the file a block at a time, never whole),
    .npz, or PX4 ULog .ulg (pip install 'gyrovib[ulog]'); every sample is
    promoted to float64 before it is scaled. A ULog cut short (its last
    message incomplete) or with corrupt data is warned about; --strict
    refuses it (exit status 2).
    Writes catalogue YAML (stdout, or -o FILE) that `gyrovib validate`
    accepts, with the fit's provenance as comments; the honesty table goes to
    standard error. Its "shape dB" is the power-weighted mean distance between the
    fitted and the measured random PSD, "off 3 dB" the share of the power more than
    3 dB out; an axis past 2 dB or 20 % is warned of.

    Several recordings give one envelope profile (docs/fleet.md): per frequency
    bin the largest PSD of the recordings, each tone at its largest amplitude,
    the missions joined; --id names it (default envelope-fitted), and each
    recording's honesty table comes before the envelope's. --jobs N fits them
    in N processes, with the same output.

    --format json writes, instead of the YAML, the honesty figures of each
    recording (and of the envelope) with the YAML as one string (docs/output.md).
    """
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib.api.fleet.envelope import profile_recordings
    from gyrovib.api.fleet.pool import one_thread
    from gyrovib.api.recordings.fit import fit_recording
    from gyrovib.render import fleet as render
    from gyrovib.render.recording import honesty_table, plot_fit

    given = recording_of(options)
    if len(recordings) == 1:

        with one_thread():  # one BLAS/OpenMP thread, as with --jobs 1 on several
            fit = as_options(fit_recording(given.read(recordings[0]),
                                           **given.fit_arguments()))  # notes name options
        table = honesty_table(fit)
        document = render.profile_json(fit) if fmt == "json" else fit.yaml
    else:

        env = as_options(profile_recordings(recordings, given, jobs=jobs))
        fit, table = env.fit, render.envelope_table(env)
        document = render.envelope_json(env) if fmt == "json" else fit.yaml
    write_output(document, output)
    click.echo(table, err=True, nl=False)
    if plot is not None:
        plot_fit(fit, plot)
