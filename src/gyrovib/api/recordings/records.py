"""The records of ``analyze --recording`` (:class:`RecordingAnalysis`), declared once: the
columns its CSV, DataFrame and JSON ``results`` are written from (:mod:`gyrovib.records`)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from gyrovib.core.recording import MOMENTS
from gyrovib.records import Column, known


def recording_columns(a: Any) -> tuple[Column[int], ...]:
    """The records of ``a``, a :class:`~gyrovib.api.recordings.analysis.RecordingAnalysis`
    (typed loosely: this module is below the one that defines it). One row per sensor
    (its index): Δ_V,rec and its parts, the fitted profile's closed
    form and their ratio, the profile at its mean rate, saturation and the peak rate; a
    number that is not finite is unknown (CSV: empty, JSON: null). The JSON nests the
    figures under its keys and alone has each row's source and warnings."""
    def of(values: Any) -> Callable[[int], float]:
        listed = np.asarray(values, dtype=float).tolist()
        return lambda i: listed[i]

    numbers = [("recorded", "recorded.total", a.recorded),
               *((f"recorded_{m}", f"recorded.additive_terms.{m}", a.terms[:, k])
                 for k, m in enumerate(MOMENTS)), ("recorded_g2", "recorded.g2", a.g2),
               ("fitted", "fitted.total", a.fitted),
               ("fitted_rms", "fitted.rms", a.fitted_rms), ("ratio", None, a.ratio)]
    json: tuple[str, ...] = ("csv", "frame")  # what only the JSON has
    at_mean, at_ratio = of(a.at_mean), of(a.at_mean_ratio)
    # unknown (null) where the ratio is: no verdict on a figure that is not there
    outside = [bool(o) if np.isfinite(r) else None
               for o, r in zip(a.at_mean_outside.tolist(), a.at_mean_ratio.tolist(),
                               strict=True)]
    return (Column("sensor", None, lambda i: a.sensors[i]),
            *(Column(name, None if name == "ratio" else "rate", of(values), cell=known,
                     key=key) for name, key, values in numbers),
            # the profile at its mean rate: nested after the ratio in JSON, last in CSV
            Column("at_mean_rate", "rate", at_mean, cell=known, key="at_mean_rate.total",
                   csv_after="unit"),
            Column("at_mean_ratio", None, at_ratio, cell=known, key="at_mean_rate.ratio",
                   csv_after="at_mean_rate"),
            Column("at_mean_rate.outside", None, lambda i: outside[i], skip=json),
            Column("saturated", None, lambda i: bool(a.saturated[i])),
            Column("peak_rate", "rate", of(a.peak_rate)),
            Column("unit", None, lambda i: a.unit, skip=("json",)),
            Column("source", None, lambda i: "specs" if a.spec[i] else "coefficients",
                   skip=json),
            Column("warnings", None, lambda i: list(a.warnings.get(i, ())), skip=json))
