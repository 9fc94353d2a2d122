"""Many recordings at once (docs/fleet.md): the one-recording step, and running it over
many recordings in worker processes.

The one-recording step is :func:`profile_one`, a pure function of a path and a
:class:`RecordingOptions`: it reads the recording, fits it
(:func:`gyrovib.api.commands.recording.fit_recording`) and returns the
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
from gyrovib.api.commands.recording import analysis_of_fit, fit_recording, recording_responses
from gyrovib.api.recordings.reading import read_recording
from gyrovib.api.recordings.results import RecordingFit
from gyrovib.core.transmissibility import FloatArray, Table
from gyrovib.errors import GyrovibError, OptionError, Problem
from gyrovib.frozen import Frozen
from gyrovib.progress import advance


@dataclass(frozen=True, eq=False, repr=False)
class RecordingOptions(Frozen):
    """How to read and fit each recording (the options of ``gyrovib profile``).

    ``responses``: input-side sensor responses whose Δ_V,rec moments the fit should
    also gather (:func:`gyrovib.api.commands.recording.recording_responses`).
    """

    fs: float | None = None
    rate_columns: tuple[str | int | None, ...] | None = None
    accel_columns: tuple[str | int | None, ...] | None = None
    rate_unit: str | None = None
    accel_unit: str | None = None
    topic: str | None = None
    crossover: float = 5.0
    resolution: float = 0.5
    tone_threshold: float = 10.0
    breakpoints: int = 12
    independent_tones: bool = False
    profile_id: str | None = None
    responses: tuple[Table, ...] = ()
    strict: bool = False
    instance: int | None = None
    preset: str | None = None


#: The options' defaults (those of ``gyrovib profile``).
DEFAULTS = RecordingOptions()


def profile_one(path: str, options: RecordingOptions = DEFAULTS) -> RecordingFit:
    """Read and fit one recording: the one-recording step, a pure function of its
    arguments (the same file and options give the same fit, in any process)."""

    recording = read_recording(
        path, fs=options.fs, rate_columns=options.rate_columns,
        accel_columns=options.accel_columns, rate_unit=options.rate_unit,
        accel_unit=options.accel_unit, topic=options.topic, strict=options.strict,
        instance=options.instance, preset=options.preset)
    return fit_recording(
        recording, crossover=options.crossover, resolution=options.resolution,
        tone_threshold=options.tone_threshold, breakpoints=options.breakpoints,
        independent_tones=options.independent_tones, profile_id=options.profile_id,
        responses=options.responses)


# ----------------------------------------------------------------- many recordings


@dataclass(frozen=True, eq=False, repr=False)
class _Failed(Frozen):
    """A user error raised in a worker, carried back as data (its class and problems)."""

    kind: type[GyrovibError]
    problems: tuple[Problem, ...]

    def error(self) -> GyrovibError:
        try:
            return self.kind(self.problems)
        except TypeError:  # a subclass with another signature: the root keeps the words
            return GyrovibError(self.problems)


def _guarded(step: Callable[[str, Any], Any], path: str, options: Any) -> Any:
    try:
        return step(path, options)
    except GyrovibError as exc:
        return _Failed(type(exc), exc.problems)


def run_recordings(paths: Sequence[str], options: Any = DEFAULTS, *, jobs: int = 1,
                   step: Callable[[str, Any], Any] = profile_one,
                   label: str = "recordings") -> tuple[Any, ...]:
    """``step(path, options)`` for every path, in input order.

    ``jobs`` > 1 runs them in that many worker processes (a ``forkserver`` context
    where the platform has one, else ``spawn``: nothing of the parent's state is
    inherited); each worker holds one recording at a time and returns only the
    step's result. The first user error in input order is raised, as with
    ``jobs = 1``; progress goes to :func:`gyrovib.progress.advance` under ``label``.
    """

    if jobs < 1:
        raise OptionError(f"--jobs {jobs}: give at least 1")
    total = len(paths)
    if jobs == 1 or total <= 1:
        results = []
        for k, path in enumerate(paths):
            results.append(step(path, options))
            advance(label, k + 1, total)
        return tuple(results)
    outcomes = _in_processes(paths, options, min(jobs, total), step, label)
    for outcome in outcomes:
        if isinstance(outcome, _Failed):
            raise outcome.error()
    return tuple(outcomes)


def _in_processes(paths: Sequence[str], options: Any, jobs: int,
                  step: Callable[[str, Any], Any], label: str) -> list[Any]:
    # lazy: the process pool of --jobs only
    import multiprocessing
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    method = "forkserver" if "forkserver" in multiprocessing.get_all_start_methods() else "spawn"
    total = len(paths)
    outcomes: list[Any] = [None] * total
    first_bad = total  # the earliest failure seen: later recordings need not run
    with ProcessPoolExecutor(max_workers=jobs,
                             mp_context=multiprocessing.get_context(method)) as pool:
        pending = {pool.submit(_guarded, step, path, options): k for k, path in enumerate(paths)}
        done_count = 0
        while pending:
            done, _ = wait(pending, return_when=FIRST_COMPLETED)
            for future in done:
                k = pending.pop(future)
                if future.cancelled():
                    continue
                outcomes[k] = future.result()
                done_count += 1
                advance(label, done_count, total)
                if isinstance(outcomes[k], _Failed) and k < first_bad:
                    first_bad = k
                    for other, j in pending.items():
                        if j > k:
                            other.cancel()
            if first_bad < total and all(j > first_bad for j in pending.values()):
                for other in pending:
                    other.cancel()
                break
    return outcomes[:first_bad + 1] if first_bad < total else outcomes


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
    the first such row on a tie, -1 where no value is finite."""
    magnitude = np.where(np.isfinite(recorded), np.abs(recorded), -1.0)
    rows = np.argmax(magnitude, axis=0)
    return tuple(int(r) if magnitude[r, k] >= 0 else -1 for k, r in enumerate(rows))


def analyze_recordings(paths: Sequence[str], catalog: Any, options: RecordingOptions, *,
                       sensors: Sequence[str] = (), unit: str = "deg/s",
                       jobs: int = 1) -> RecordingsAnalysis:
    """Δ_V,rec of every chosen sensor on each recording, and each sensor's worst.

    The fits run in ``jobs`` processes (:func:`run_recordings`), gathering the moments
    of the chosen sensors' input responses (``options.responses`` is replaced by them);
    each fit is then evaluated here as ``analyze --recording`` evaluates one.
    """

    unit = units.canonical_unit(unit)
    entries, responses = recording_responses(catalog, sensors)
    fits = run_recordings(paths, dataclasses.replace(options, responses=responses), jobs=jobs)
    analyses = tuple(analysis_of_fit(fit, catalog, entries, unit=unit) for fit in fits)
    recorded = np.array([a.recorded for a in analyses], dtype=float).reshape(len(analyses), -1)
    return RecordingsAnalysis(unit, analyses[0].sensors, analyses, worst_recordings(recorded))
