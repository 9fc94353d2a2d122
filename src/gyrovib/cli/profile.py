"""`gyrovib profile`: fit a catalogue profile to a recording (docs/model.md section 13)."""

from __future__ import annotations

from typing import Any

import click

from gyrovib.cli.options import output_option
from gyrovib.cli.recording import fit_options, read, recording_options


@click.command()
@click.argument("recording", metavar="RECORDING")
@recording_options
@click.option("--plot", metavar="PNG", help="Plot the measured PSD against the fit, per axis, "
              "each panel titled with its shape figures.")
@output_option
def profile(recording: str, plot: str | None, output: str | None, **options: Any) -> None:
    """Fit a profile (and its carrier mission) to a RECORDING.

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
    """
    from gyrovib.api.commands.recording import fit_recording
    from gyrovib.cli.output import write_output
    from gyrovib.render.recording import honesty_table, plot_fit

    fit = fit_recording(read(recording, options), **fit_options(options))
    write_output(fit.yaml, output)
    click.echo(honesty_table(fit), err=True, nl=False)
    if plot is not None:
        plot_fit(fit, plot)
