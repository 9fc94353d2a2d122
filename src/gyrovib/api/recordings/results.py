"""What fitting a recording gives (docs/model.md section 13): the fitted profile's parts,
the honesty of the fit per axis, the fitted mission.

Result types of the recording view, apart from :mod:`gyrovib.api.recordings.analysis`
(which computes them, and still gives their names) so that
:mod:`gyrovib.api.recordings.yaml`, which writes a fit as catalogue text, imports
them without importing the command.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from gyrovib.core._types import FloatArray, Table
from gyrovib.frozen import Frozen


@dataclass(frozen=True, eq=False, repr=False)
class AxisHonesty(Frozen):
    """One axis of the honesty table: variance of x (unit²), the fraction of it the
    fitted profile holds, skewness and excess kurtosis of x (NaN: not recorded), and
    how well the fitted PSD's shape holds over f_c…fs/2: ``shape_db``, the power-weighted
    mean |dB| between the fitted and the measured random PSD, and ``off_3db``, the share
    of the measured power in bins off by more than 3 dB (NaN: no random part fitted)."""

    variance: float
    held: float
    skewness: float
    excess_kurtosis: float
    shape_db: float = float("nan")
    off_3db: float = float("nan")


@dataclass(frozen=True, eq=False, repr=False)
class FittedTone(Frozen):
    """A tone: frequency (Hz), amplitude (3,) and phase (3,) in degrees."""

    frequency: float
    amplitude: FloatArray
    phase: FloatArray


@dataclass(frozen=True, eq=False, repr=False)
class FittedHarmonics(Frozen):
    """A phase-locked group: fundamental (Hz), orders, amplitudes (orders, 3)."""

    fundamental: float
    orders: tuple[int, ...]
    amplitude: FloatArray
    phase: FloatArray


@dataclass(frozen=True, eq=False, repr=False)
class FittedPart(Frozen):
    """The fitted vibration of one kind (rate in deg/s, or acceleration in g).

    ``shape_db`` and ``off_3db`` (3,): the shape figures of each axis's fitted PSD
    (:class:`AxisHonesty`), NaN where no random part was fitted.
    """

    tones: tuple[FittedTone, ...]
    harmonics: tuple[FittedHarmonics, ...]
    psd: tuple[Table | None, Table | None, Table | None]
    coherence: FloatArray
    frequencies: FloatArray
    measured: FloatArray
    median: FloatArray
    variance: FloatArray
    held: FloatArray
    shape_db: FloatArray = field(default_factory=lambda: np.full(3, np.nan))
    off_3db: FloatArray = field(default_factory=lambda: np.full(3, np.nan))
    #: Lines at orders of a fundamental (Hz) written as independent tones, so that the
    #: ``phase: worst`` search over the groups stays within its budget.
    released: tuple[float, ...] = ()


@dataclass(frozen=True, eq=False, repr=False)
class RecordingFit(Frozen):
    """What :func:`fit_recording` found (rates deg/s, accelerations g).

    ``mission_rates`` (bins, 3) and ``mission_durations`` (bins,) s: the
    histogram of Ω_K3 (each bin's mean Ω_K3, the time means of Ω_K1, Ω_K2);
    ``yaml``: the catalogue text (profile ``profile_id``) with provenance;
    ``topic``, ``instance``: the topic or message and which of its instances was read
    from a log, None for a format without them (``source`` says both in words).
    """

    file: str
    sha256: str
    samples: int
    fs: float
    crossover: float
    segments: int
    duration: float
    profile_id: str
    rate: FloatArray
    mission_rates: FloatArray
    mission_durations: FloatArray
    angular: FittedPart
    linear: FittedPart | None
    honesty: tuple[AxisHonesty, AxisHonesty, AxisHonesty]
    rate_axes: tuple[bool, bool, bool]
    warnings: tuple[str, ...]
    yaml: str
    peak: FloatArray = field(default_factory=lambda: np.zeros(0))
    moments: dict[Any, FloatArray] = field(default_factory=dict)
    g2_moments: FloatArray | None = None
    topic: str | None = None
    instance: int | None = None

    @property
    def source(self) -> str | None:
        """``IMU instance 1``: the topic and instance read, or None."""
        return source_words(self.topic, self.instance)


def source_words(topic: str | None, instance: int | None) -> str | None:
    """A log's topic and instance in words (``sensor_gyro_fifo instance 0``), or None."""
    if topic is None:
        return None
    return topic if instance is None else f"{topic} instance {instance}"
