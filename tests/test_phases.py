"""``phase: worst`` (docs/model.md section 10): the worst case over unknown relative phases.

References: the closed form M3 = −¾·a1²·a2·sin(φ2 − 2φ1) of docs/model.md section 10
(so max |M3| = ¾·a1²·a2), and the error at phases drawn at random, which the
worst case must never fall below.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gyrovib.core.analysis import COEFFICIENTS, profile_multipliers, vibration_error
from gyrovib.core.harmonics import locked_group
from gyrovib.core.phases import (
    apply_offsets,
    free_offsets,
    worst_phase_errors,
    worst_phase_multipliers,
)
from gyrovib.core.statistics import vibration_at_sensor

NONE = vibration_at_sensor()
A1, A2 = 1.2, 0.5


def rows(*values: dict[str, float]) -> np.ndarray:
    out = np.zeros((len(values), len(COEFFICIENTS)))
    for i, row in enumerate(values):
        for name, value in {"k1": 1.0, **row}.items():
            out[i, COEFFICIENTS.index(name)] = value
    return out


def test_time_origin_fixes_one_offset() -> None:
    all_worst = locked_group([1, 2, 3], np.ones((3, 3)), np.zeros((3, 3)), worst=[True] * 3)
    one_known = locked_group([1, 2], np.ones((2, 3)), np.zeros((2, 3)), worst=[False, True])
    assert free_offsets([all_worst]) == [(0, 1), (0, 2)]
    assert free_offsets([one_known, all_worst]) == [(0, 1), (1, 1), (1, 2)]


def test_worst_k3_term_is_three_quarters_a1_squared_a2() -> None:
    # Ω = 0 and only k3: Δ_V = k3·M3, max over phases |M3| = ¾·a1²·a2 = 0.54 (docs/model.md 10)
    g = locked_group([1, 2], [[0, 0, A1], [0, 0, A2]], [[0, 0, 10.0], [0, 0, 0.0]],
                     worst=[True, True])
    c = rows({"k3": 2e-3}, {"k3": -1e-3})
    got = worst_phase_errors(c, NONE, [g], [0.0])[0]
    assert got.free == ((0, 1),)
    expected = 0.75 * A1**2 * A2
    assert np.abs(got.error.total) == pytest.approx([2e-3 * expected, 1e-3 * expected],
                                                    rel=1e-10)
    # the phases found: sin(φ2 + ψ2 − 2φ1) = ±1
    for psi in got.offsets[:, 0]:
        assert abs(math.sin(psi - 2 * math.radians(10.0))) == pytest.approx(1.0, abs=1e-10)
    assert got.multipliers.m3 is not None
    assert np.abs(got.multipliers.m3) == pytest.approx([expected, expected], rel=1e-10)


def test_worst_is_never_below_any_phase() -> None:
    g = locked_group([1, 2, 3], [[0.2, 0.0, 1.0], [0.0, 0.1, 0.6], [0.0, 0.0, 0.3]],
                     [[0, 0, 0], [0, 0, 40], [0, 0, 0]], worst=[False, True, True])
    vib = vibration_at_sensor([(7.0, (0.0, 0.0, 0.3), (0.0, 0.0, 0.0))], rms=(0.0, 0.0, 0.5))
    c = rows({"A1": 0.02, "k2": 1e-3, "k3": -2e-3, "k4": 1e-3, "k5": 5e-4},
             {"k3": 1e-3, "k4": -2e-3})
    omega = 0.5
    got = worst_phase_errors(c, vib, [g], [omega])[0]
    free = free_offsets([g])
    rng = np.random.default_rng(7)
    for psi in rng.uniform(0, 2 * math.pi, size=(12, len(free))):
        mu = profile_multipliers(vib, np.array(omega), locked=apply_offsets([g], free, psi))
        trial = np.abs(vibration_error(c, mu).total)
        assert np.all(np.abs(got.error.total) >= trial * (1 - 1e-12))
    # the reported error is the error at the reported phases
    for k in range(2):
        mu = profile_multipliers(vib, np.array(omega),
                                 locked=apply_offsets([g], free, got.offsets[k]))
        assert float(vibration_error(c[k : k + 1], mu).total[0]) == pytest.approx(
            float(got.error.total[k]), rel=1e-12)


def test_worst_multipliers_for_synthesis() -> None:
    g = locked_group([1, 2], [[0, 0, A1], [0, 0, A2]], [[0, 0, 0.0], [0, 0, 0.0]],
                     worst=[True, True])
    omega = np.array([0.0, 0.9])
    got = worst_phase_multipliers(NONE, [g], omega)
    assert got.m3 == pytest.approx([0.75 * A1**2 * A2] * 2, rel=1e-10)
    # M2 does not depend on the phases: (1.44 + 0.25)/2 = 0.845
    assert got.m2 == pytest.approx([0.845, 0.845], rel=1e-14)
    rng = np.random.default_rng(11)
    for psi in rng.uniform(0, 2 * math.pi, size=(10, 1)):
        mu = profile_multipliers(NONE, omega, locked=apply_offsets([g], [(0, 1)], psi))
        assert np.all(got.asymmetry >= mu.asymmetry * (1 - 1e-12))
        assert np.all(got.m4 >= mu.m4 * (1 - 1e-12))
        assert np.all(got.m5 >= np.abs(mu.m5) * (1 - 1e-12))
