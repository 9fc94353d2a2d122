"""The recorded error Δ_V,rec of docs/model.md section 13, evaluated independently in
float64 from a recording's samples: split at gaps of 1.5 median intervals, segments
shorter than 4/f_c (or than sosfiltfilt's padding) dropped, scipy's own
butter/sosfiltfilt, eq. (2) written out (tests/test_recording.py ``_eq2``) for the
``every-term`` sensor of tests/test_recording.py ``SENSOR``."""

from __future__ import annotations

import itertools

import numpy as np

from tests.test_recording import _eq2

#: The every-term sensor's coefficients and g² sensitivities (G11, G22, G33, G12, G13, G23).
COEFFICIENTS = {"k0": 0.3, "k1": 1.02, "A1": 2.0e-2, "k2": 8.0e-4, "k3": -6.4e-5,
                "k4": 1.28e-5, "k5": -7.8e-7, "m1": 1.0e-2, "m2": -2.0e-2, "m31": 4.0e-3,
                "m32": -3.0e-3}
G2 = [0.01, 0.02, 0.03, 0.004, 0.005, 0.006]
PAIRS = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]


def recorded_error(w: np.ndarray, g: np.ndarray | None, t: np.ndarray, fc: float) -> float:
    """Δ_V,rec (deg/s) of rates ``w`` (n, 3) deg/s and specific force ``g`` (n, 3) in g
    (None: not recorded) sampled at times ``t`` s."""
    from scipy import signal

    c = COEFFICIENTS
    dt = np.diff(t)
    edges = [0, *(np.flatnonzero(dt > 1.5 * np.median(dt)) + 1).tolist(), t.size]
    fs = 1.0 / np.median(dt)
    sos = signal.butter(4, fc, fs=fs, output="sos")
    total, count = 0.0, 0
    for lo, hi in itertools.pairwise(edges):
        if (hi - lo) / fs < 4.0 / fc or hi - lo <= 15:
            continue
        ws = w[lo:hi]
        ks = signal.sosfiltfilt(sos, ws, axis=0)
        x = ws - ks
        per = (_eq2(c, ws) - _eq2(c, ks) - c["k1"] * x[:, 2] - c["m1"] * x[:, 0]
               - c["m2"] * x[:, 1])
        if g is not None:
            gs = g[lo:hi]
            big = signal.sosfiltfilt(sos, gs, axis=0)
            per += sum(gj * (gs[:, j] * gs[:, k] - big[:, j] * big[:, k])
                       for gj, (j, k) in zip(G2, PAIRS, strict=True))
        total += float(per.sum())
        count += hi - lo
    assert count > 0
    return total / count
