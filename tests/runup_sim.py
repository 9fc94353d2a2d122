"""Simulated run-up tests for tests/test_runup.py and benchmarks/bench_runup_coverage.py.

A sensor at rest (true rate OMEGA about x3) sees, step by step, an angular vibration x
(a tone plus a Gaussian part, on x3 and proportionally on x1 and x2) and a linear
vibration a (a tone per axis, gravity along Z). Its output about x3 is eq. (2) itself
applied to the rate it sees, plus the g² term, a linear drift and white noise:

    y3 = ω3 + ½·A1·|ω3| + k2·ω3² + k4·ω3⁴ + m31·ω3·ω1 + vre·Σ_j a_j² + d·t + n(t)

with ω = (0, 0, OMEGA) + x. Every number is synthetic: the truth the estimates are
checked against is the coefficients given here, not a measurement.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

OMEGA = 0.004  # deg/s: about the Earth's rate
#: Up and down, angular and linear vibration stepped apart (so every term separates).
ANGULAR = (0.0, 1.0, 2.0, 0.0, 2.0, 1.0, 0.0, 3.0, 0.0, 1.0)
LINEAR = (0.0, 1.0, 0.0, 2.0, 2.0, 0.0, 1.0, 1.0, 0.0, 2.0)


def simulate(rng: np.random.Generator, coefficients: Mapping[str, float], *,
             fs: float = 200.0, seconds: float = 20.0, gap: float = 0.0,
             angular: Sequence[float] = ANGULAR, linear: Sequence[float] = LINEAR,
             drift: float = 1e-4, arw: float = 0.01) -> tuple[np.ndarray, list[tuple[float,
                                                                                 float]]]:
    """A run-up record (n, 6): ω X, Y, Z in deg/s then a X, Y, Z in g, at ``fs``; and the
    true steps (start, end) in s. ``arw`` is the white noise's density, deg/s/√Hz.
    ``gap`` s of transition (the vibration ramping linearly) between steps."""
    n, g = round(seconds * fs), round(gap * fs)
    c = {k: 0.0 for k in ("A1", "k2", "k4", "m31", "vre")} | dict(coefficients)
    blocks, steps, at = [], [], 0
    levels = list(zip(angular, linear, strict=True))
    for k, (x_level, a_level) in enumerate(levels):
        if k and g:
            ramp = np.linspace(levels[k - 1][0], x_level, g)
            ramp_a = np.linspace(levels[k - 1][1], a_level, g)
            blocks.append(_block(rng, at, g, fs, ramp, ramp_a, c, drift, arw))
            at += g
        steps.append((at / fs, (at + n) / fs))
        blocks.append(_block(rng, at, n, fs, np.full(n, x_level), np.full(n, a_level), c,
                             drift, arw))
        at += n
    return np.vstack(blocks), steps


def _block(rng: np.random.Generator, at: int, n: int, fs: float, x_level: np.ndarray,
           a_level: np.ndarray, c: Mapping[str, float], drift: float,
           arw: float) -> np.ndarray:
    t = (at + np.arange(n)) / fs
    x3 = (x_level * np.sin(2 * np.pi * 47.0 * t + rng.uniform(0, 2 * np.pi))
          + 0.3 * x_level * rng.standard_normal(n))
    x1, x2 = 0.5 * x3, 0.3 * x3
    a = (a_level[:, None] * np.sin(2 * np.pi * 61.0 * t[:, None]
                                   + rng.uniform(0, 2 * np.pi, 3))
         + np.array([0.0, 0.0, 1.0]))
    w3 = OMEGA + x3
    y3 = (w3 + 0.5 * c["A1"] * np.abs(w3) + c["k2"] * w3**2 + c["k4"] * w3**4
          + c["m31"] * w3 * x1 + c["vre"] * np.sum(a**2, axis=1) + drift * t
          + arw * np.sqrt(fs) * rng.standard_normal(n))
    noise = arw * np.sqrt(fs) * rng.standard_normal((n, 2))
    return np.column_stack([x1 + noise[:, 0], x2 + noise[:, 1], y3, a])
