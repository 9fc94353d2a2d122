"""Recordings (docs/model.md section 13): a vehicle's own angular rate, read, fitted, analysed.

=====================  =========================================================
module                 what it holds
=====================  =========================================================
``readers``            the reader interface and the plain formats (CSV,
                       ``.npy``/``.npz``); samples in float64
``px4``                PX4 ULog: topics, instances, the raw FIFO, damage
``dataflash``          ArduPilot DataFlash: IMU and the batch sampler, damage
``betaflight``         the CSV of Betaflight's blackbox_decode (a preset)
``registry``           the readers by suffix, else by the file's first bytes
``quiet``              what a log library prints, kept off standard output
``reading``            ``read_recording``: columns, units, gaps -> a ``Recording``
``passes``             the pass over the segments (the split into carrier and
                       vibration a column at a time, the sums of Δ_V,rec)
``results``            what a fit gives: ``RecordingFit`` and its parts
``fit``                ``fit_recording``: a ``Recording`` -> a ``RecordingFit``,
                       the profile and mission it writes (``gyrovib profile``)
``yaml``               a fit written as catalogue text
``analysis``           ``analyze_recording``: every sensor's Δ_V,rec beside the
                       fitted profile's closed form (``analyze --recording``)
``honesty``            the analysis's warnings, where the two disagree
``records``            the analysis's columns, declared once
=====================  =========================================================

The feature reads in one direction, reader -> fit -> analysis; the analysis
evaluates the fitted profile with the command views (:mod:`gyrovib.api.commands`),
so this package stands above them. Many recordings at once are
:mod:`gyrovib.api.fleet`.
"""

from __future__ import annotations

from gyrovib.api.recordings.reading import (
    Recording,
    iter_segments,
    parse_columns,
    read_recording,
)
from gyrovib.api.recordings.results import AxisHonesty, FittedPart, RecordingFit

__all__ = ["AxisHonesty", "FittedPart", "Recording", "RecordingFit", "iter_segments",
           "parse_columns", "read_recording"]
