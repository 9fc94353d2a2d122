"""``gyrovib allan``: the overlapping Allan deviation of a static recording, per axis,
and N, B, K read from it (docs/model.md section 15; the kernels are core/allan.py)."""

from __future__ import annotations

import math

import numpy as np

from gyrovib import units
from gyrovib.api.noise.results import FIGURE_UNITS, AllanResult, AxisAllan, Figure
from gyrovib.api.recordings.reading import AXES, Recording, RecordingError
from gyrovib.core import allan as kernel
from gyrovib.errors import OptionError, Problem

#: From the kernel's figures (deg/s·√s, deg/s, deg/s/√s) to the reported units.
TO_REPORTED = {"arw": 60.0, "bias_instability": 3600.0, "rrw": 216_000.0}
#: Fewest samples an Allan deviation is computed from.
MIN_SAMPLES = 30


def _figure(read: kernel.Read, name: str) -> Figure:
    f = TO_REPORTED[name]
    return Figure(read.value * f, FIGURE_UNITS[name], read.uncertainty * f, read.tau, read.share)


def longest_segment(recording: Recording) -> tuple[int, int]:
    """The longest contiguous segment (a gap breaks the record: σ needs even spacing)."""
    seg = recording.segments
    k = int(np.argmax(seg[:, 1] - seg[:, 0]))
    return int(seg[k, 0]), int(seg[k, 1])


def allan_axis(axis: str, rate: np.ndarray, fs: float, unit: str,
               per_decade: int = kernel.PER_DECADE) -> AxisAllan:
    """One axis: ``rate`` in deg/s at ``fs`` Hz; σ(τ) reported in ``unit``."""
    tau0 = 1.0 / fs
    m = kernel.tau_grid(rate.size, per_decade)
    adev = kernel.oadev(rate, tau0, m)[1]
    tau = m / fs  # as written: 3 / 10 is 0.3, where 3 · 0.1 is 0.30000000000000004
    terms = kernel.noise_terms(tau, adev, rate.size + 1, tau0)
    n2, b2, k2 = (float(c) for c in terms.fitted)
    fitted = (math.sqrt(n2) * TO_REPORTED["arw"], math.sqrt(b2) * TO_REPORTED["bias_instability"],
              math.sqrt(k2) * TO_REPORTED["rrw"])
    scale = units.scale(unit)
    return AxisAllan(axis=axis, tau=tau, adev=adev / scale, unit=unit,
                     arw=_figure(terms.arw, "arw"),
                     bias_instability=_figure(terms.bias_instability, "bias_instability"),
                     rrw=_figure(terms.rrw, "rrw"), fitted=fitted)


def allan(recording: Recording, unit: str = "deg/h",
          per_decade: int = kernel.PER_DECADE) -> AllanResult:
    """Every recorded axis of ``recording`` (read by :func:`gyrovib.api.recordings.
    read_recording`): σ(τ) in ``unit`` on a log grid (``per_decade`` points a decade),
    N, B, K with their uncertainties, from its longest contiguous segment."""
    unit = units.canonical_unit(unit)
    if per_decade < 1:
        raise OptionError(f"--per-decade {per_decade}: give at least 1")
    lo, hi = longest_segment(recording)
    if hi - lo < MIN_SAMPLES:
        raise RecordingError(Problem(
            f"{hi - lo} contiguous samples: an Allan deviation needs {MIN_SAMPLES} at least "
            "(and hours of a static record for the bias instability and rate random walk)",
            recording.file, None, None))
    axes = tuple(allan_axis(name, recording.rate[lo:hi, k], recording.fs, unit, per_decade)
                 for k, name in enumerate(AXES) if recording.rate_axes[k])
    return AllanResult(file=recording.file, sha256=recording.sha256, fs=recording.fs,
                       samples=hi - lo, segments=int(recording.segments.shape[0]), axes=axes,
                       topic=recording.topic, instance=recording.instance,
                       warnings=recording.warnings)
