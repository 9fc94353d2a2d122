"""Many recordings at once (docs/fleet.md): the one-recording step, and running it over
many recordings in worker processes.

The one-recording step is :func:`profile_one`, a pure function of a path and a
:class:`RecordingOptions`: it reads the recording, fits it
(:func:`gyrovib.api.recordings.fit.fit_recording`) and returns the
:class:`~gyrovib.api.recordings.results.RecordingFit` — spectra on the Welch grid,
lines, carrier histogram, moments and honesty figures: tens of kB at 250 Hz, growing
with fs/Δf and never with the recording's length; never its samples. It pickles, so
it can run in another process (:func:`run_recordings`, ``--jobs N``) or on another
machine (Dask, docs/fleet.md).
Their envelope profile is :mod:`gyrovib.api.fleet.envelope`;
:func:`analyze_recordings` is ``analyze --recording A --recording B``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from gyrovib import units
from gyrovib.api.fleet.duplicates import refuse_same_contents, refuse_same_paths
from gyrovib.api.fleet.pool import located, one_thread, raise_failure, run_in_processes
from gyrovib.api.recordings.analysis import analysis_of_fit, recording_responses
from gyrovib.api.recordings.fit import fit_recording
from gyrovib.api.recordings.reading import Recording, read_recording
from gyrovib.api.recordings.results import RecordingFit
from gyrovib.core._types import FloatArray, Table
from gyrovib.errors import Crash, GyrovibError, OptionError
from gyrovib.frozen import Frozen
from gyrovib.limits import (
    DEFAULT_BREAKPOINTS,
    DEFAULT_CROSSOVER,
    DEFAULT_RESOLUTION,
    DEFAULT_THRESHOLD,
)
from gyrovib.progress import advance


@dataclass(frozen=True, eq=False, repr=False)
class RecordingOptions(Frozen):
    """How to read and fit each recording (the options of ``gyrovib profile``).

    ``responses``: input-side sensor responses whose Δ_V,rec moments the fit should
    also gather (:func:`gyrovib.api.recordings.analysis.recording_responses`).
    """

    fs: float | None = None
    rate_columns: tuple[str | int | None, ...] | None = None
    accel_columns: tuple[str | int | None, ...] | None = None
    rate_unit: str | None = None
    accel_unit: str | None = None
    topic: str | None = None
    crossover: float = DEFAULT_CROSSOVER
    resolution: float = DEFAULT_RESOLUTION
    tone_threshold: float = DEFAULT_THRESHOLD
    breakpoints: int = DEFAULT_BREAKPOINTS
    independent_tones: bool = False
    profile_id: str | None = None
    responses: tuple[Table, ...] = ()
    strict: bool = False
    instance: int | None = None
    preset: str | None = None

    def read(self, path: str) -> Recording:
        """The recording at ``path``, read with these options."""
        return read_recording(
            path, fs=self.fs, rate_columns=self.rate_columns, accel_columns=self.accel_columns,
            rate_unit=self.rate_unit, accel_unit=self.accel_unit, topic=self.topic,
            strict=self.strict, instance=self.instance, preset=self.preset)

    def fit_arguments(self) -> dict[str, Any]:
        """The keyword arguments these options give the fit (:func:`fit_recording`,
        :func:`~gyrovib.api.recordings.analysis.analyze_recording`)."""
        return {"crossover": self.crossover, "resolution": self.resolution,
                "tone_threshold": self.tone_threshold, "breakpoints": self.breakpoints,
                "independent_tones": self.independent_tones, "profile_id": self.profile_id}


#: The options' defaults (those of ``gyrovib profile``).
DEFAULTS = RecordingOptions()


def profile_one(path: str, options: RecordingOptions = DEFAULTS) -> RecordingFit:
    """Read and fit one recording: the one-recording step, a pure function of its
    arguments (the same file and options give the same fit, in any process)."""
    return fit_recording(options.read(path), **options.fit_arguments(),
                         responses=options.responses)


# ----------------------------------------------------------------- many recordings


def run_recordings(paths: Sequence[str], options: Any = DEFAULTS, *, jobs: int = 1,
                   step: Callable[[str, Any], Any] = profile_one,
                   label: str = "recordings") -> tuple[Any, ...]:
    """``step(path, options)`` for every path, in input order.

    ``jobs`` > 1 runs them in that many worker processes, started once for the run
    (:func:`gyrovib.api.fleet.pool.run_in_processes`); each holds one recording at a
    time and returns only the step's result. Every process running the step runs one
    BLAS/OpenMP thread, this one too with ``jobs`` = 1. The first user error in input
    order is raised, as with ``jobs`` = 1; an unexpected exception, or a worker that
    died, is raised as a :class:`~gyrovib.errors.Crash` naming its recording. Progress
    goes to :func:`gyrovib.progress.advance` under ``label``.
    """

    if jobs < 1:
        raise OptionError(argument="jobs", value=str(jobs), reason="give at least 1")
    total = len(paths)
    if jobs > 1 and total > 1:
        outcomes = run_in_processes(paths, options, jobs, step, label)
        for path, result in zip(paths, outcomes, strict=False):
            raise_failure(result, path)
        return tuple(outcomes)
    results = []
    with one_thread():
        for k, path in enumerate(paths):
            try:
                results.append(step(path, options))
            except GyrovibError as exc:
                placed = located(exc, path)
                if placed is exc:
                    raise
                raise placed from None
            except Exception as exc:  # a bug, named by the recording it met
                raise Crash(path, type(exc).__name__, str(exc)) from exc
            advance(label, k + 1, total)
    return tuple(results)


# ----------------------------------------------------------------- analyze --recording A B …


@dataclass(frozen=True, eq=False, repr=False)
class RecordingsAnalysis(Frozen):
    """``analyze --recording`` on several recordings: ``analyses`` in input order (the
    same sensors in each), and per sensor ``worst`` the index of the recording with the
    largest |Δ_V,rec| (-1 where no recording gives a finite one)."""

    unit: str
    sensors: tuple[str, ...]
    analyses: tuple[Any, ...]
    worst: tuple[int, ...]


def worst_recordings(recorded: FloatArray) -> tuple[int, ...]:
    """Per column of ``recorded`` (recordings × sensors) the row of the largest |value|;
    the first such row on a tie, -1 where a value is not finite (unknown on one
    recording, say an axis it did not record: the worst is then unknown too)."""
    magnitude = np.where(np.isfinite(recorded), np.abs(recorded), -1.0)
    rows = np.argmax(magnitude, axis=0)
    return tuple(int(r) if np.all(magnitude[:, k] >= 0) else -1 for k, r in enumerate(rows))


def analyze_recordings(paths: Sequence[str], catalog: Any, options: RecordingOptions, *,
                       sensors: Sequence[str] = (), unit: str = "deg/s",
                       jobs: int = 1) -> RecordingsAnalysis:
    """Δ_V,rec of every chosen sensor on each recording, and each sensor's worst.

    The fits run in ``jobs`` processes (:func:`run_recordings`), gathering the moments
    of the chosen sensors' input responses (``options.responses`` is replaced by them);
    each fit is then evaluated here as ``analyze --recording`` evaluates one.
    """

    unit = units.canonical_unit(unit)
    refuse_same_paths(paths)
    entries, responses = recording_responses(catalog, sensors)
    fits = run_recordings(paths, dataclasses.replace(options, responses=responses), jobs=jobs)
    refuse_same_contents((fit.file, fit.sha256) for fit in fits)
    analyses = tuple(analysis_of_fit(fit, catalog, entries, unit=unit) for fit in fits)
    recorded = np.array([a.recorded for a in analyses], dtype=float).reshape(len(analyses), -1)
    return RecordingsAnalysis(unit, analyses[0].sensors, analyses, worst_recordings(recorded))
