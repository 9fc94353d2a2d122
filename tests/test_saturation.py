"""Saturation reach (docs/model.md section 9): |Ω_K3| + Σ a3 + Σ locked peaks + κ·σ3 against R."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gyrovib.core.harmonics import locked_group
from gyrovib.core.saturation import group_peak, saturated, saturation_reach


def test_reach_by_hand_and_vectorised() -> None:
    # profile 1: Ω = −20, tones 30 + 10, σ3 = 5 → 20 + 40 + 3·5 = 75
    # profile 2: Ω = 50, no tones, σ3 = 0 → 50
    reach = saturation_reach([-20.0, 50.0], [[30.0, 10.0], [0.0, 0.0]], [5.0, 0.0])
    assert reach == pytest.approx([75.0, 50.0])
    # κ = 4: 20 + 40 + 20 = 80
    assert saturation_reach(-20.0, [30.0, 10.0], 5.0, kappa=4.0) == pytest.approx(80.0)
    # sensors × profiles: an input-side response ν = 0.5 halves the vibration of sensor 2
    amps = np.array([[[30.0, 10.0], [0.0, 0.0]], [[15.0, 5.0], [0.0, 0.0]]])
    sig = np.array([[5.0, 0.0], [2.5, 0.0]])
    both = saturation_reach(np.array([-20.0, 50.0]), amps, sig)
    assert both == pytest.approx(np.array([[75.0, 50.0], [47.5, 50.0]]))
    # R = 60: sensor 1 saturates under profile 1; its input filter keeps sensor 2 out
    assert saturated(both, [60.0, 60.0]).tolist() == [[True, False], [False, False]]


@pytest.mark.parametrize(("range_", "expected"), [
    (75.0 * (1 + 1e-12), False), (75.0, False), (75.0 * (1 - 1e-12), True),
    (None, False), (math.inf, False), (math.nan, False),
])
def test_the_edge(range_: float | None, expected: bool) -> None:
    reach = saturation_reach(-20.0, [30.0, 10.0], 5.0)
    assert bool(saturated(np.array([reach]), [range_])[0]) is expected


def test_locked_group_uses_its_true_peak() -> None:
    # sin θ + ½ sin 2θ peaks at θ = 60°: 3√3/4 = 1.2990381 (< Σa = 1.5, the upper bound)
    g = locked_group([1, 2], [[0, 0, 1.0], [0, 0, 0.5]], np.zeros((2, 3)))
    assert group_peak(g) == pytest.approx(3 * math.sqrt(3) / 4, rel=1e-13)
    # phase: worst on order 2 — aligned with the peak of the rest: 1 + 0.5
    worst = locked_group([1, 2], [[0, 0, 1.0], [0, 0, 0.5]], np.zeros((2, 3)),
                         worst=[False, True])
    assert group_peak(worst) == pytest.approx(1.5, rel=1e-14)
    reach = saturation_reach(0.5, [0.2], 0.1, locked_peaks=[group_peak(g)])
    assert reach == pytest.approx(0.5 + 0.2 + 3 * math.sqrt(3) / 4 + 0.3, rel=1e-13)


def test_bad_kappa_refused() -> None:
    with pytest.raises(ValueError):
        saturation_reach(0.0, [1.0], 1.0, kappa=-1.0)
