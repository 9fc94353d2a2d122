"""The interval constructions the coverage study compares with gyrovib's own
(benchmarks/allan_methods.py): the fast double bootstrap's level calibration, in closed
form where the replicates' spread shrinks by the same factor at each level, and its second
level of replicates drawn from each replicate's own fit; and the inversion of a root that
gyrovib's studentized interval uses (core/allan_fit.inverted)."""

import math
import sys
from statistics import NormalDist

import numpy as np
import pytest

from gyrovib.core.allan import oadev, tau_grid
from gyrovib.core.allan_fit import bootstrap, fit, inverted
from gyrovib.core.allan_sim import Truth, simulate
from tests.docpages import ROOT

sys.path.insert(0, str(ROOT / "benchmarks"))

from allan_methods import calibrated, double_bootstrap, intervals, level

#: Evenly spread quantiles of the standard normal: a sample without sampling noise.
Z = np.array([NormalDist().inv_cdf((i + 0.5) / 20_001) for i in range(20_001)])


@pytest.mark.parametrize("a", [0.6, 0.8, 1.25])
def test_a_spread_too_small_by_a_is_undone(a: float) -> None:
    # The root T is N(0, 1); the replicates are a·T (outer) and a²·T (inner), as where each
    # level of the bootstrap shrinks the spread by a. By hand (allan_methods' docstring):
    # γ' = F**(F*⁻¹(γ)) = Φ(a·z_γ/a²) = Φ(z_γ/a), and F*⁻¹(γ') = a·z_γ/a = z_γ: the root's
    # own quantile, where the single bootstrap reads a·z_γ.
    for gamma in (0.025, 0.16, 0.5, 0.84, 0.975):
        got = calibrated(a * Z, a * a * Z, [gamma])[0]
        # to 0.01: at γ = 2.5 % and a = 0.6, γ' = Φ(−3.27) = 0.05 %, some 11 of the 20 001
        # values, where one place of the empirical quantile is 0.03 in z
        assert got == pytest.approx(NormalDist().inv_cdf(gamma), abs=1e-2)
        # the single bootstrap's quantile is off by the factor a: the test can tell
        assert abs(float(np.quantile(a * Z, gamma)) - got) > 0.01 or gamma == 0.5


def test_a_shift_is_undone() -> None:
    # outer T + b, inner T + 2b (a bias that grows by b a level): γ' = Φ(z_γ − b), and
    # F*⁻¹(γ') = z_γ − b + b = z_γ
    b = 0.3
    for gamma in (0.16, 0.84):
        assert calibrated(Z + b, Z + 2 * b, [gamma])[0] == pytest.approx(
            NormalDist().inv_cdf(gamma), abs=2e-3)


def test_inner_as_the_outer_leaves_the_level_alone() -> None:
    rng = np.random.default_rng(1)
    outer = rng.standard_normal(200)
    nominal = [float(q) for q in np.quantile(outer, [0.16, 0.84])]
    assert calibrated(outer, outer.copy(), [0.16, 0.84]) == pytest.approx(nominal, abs=0.05)
    # too few inner roots (fewer than 10): the nominal quantiles
    assert calibrated(outer, outer[:5], [0.16, 0.84]) == nominal
    # non-finite roots are left out
    assert calibrated(np.append(outer, np.nan), np.append(outer, np.inf),
                      [0.16, 0.84]) == pytest.approx(nominal, abs=0.05)


def test_level_counts_ties_half() -> None:
    assert level(np.array([1.0, 2.0, 2.0, 3.0]), 2.0) == 0.5
    assert level(np.array([1.0, 2.0, 3.0, 4.0]), 0.0) == 0.0


def test_inverted_holds_the_root_between_its_quantiles() -> None:
    # root(c) = (ĉ − c)/s with s fixed: the difference interval ĉ − s·q_hi … ĉ − s·q_lo
    c_hat, s = 4.0, 0.5
    found = inverted(lambda c: (c_hat - c) / s, c_hat, -1.0, 2.0)
    assert found is not None
    lo, hi = found
    assert (lo ** 2, hi ** 2) == pytest.approx((c_hat - 2.0 * s, c_hat + 1.0 * s), rel=1e-9)


def test_double_bootstrap_outer_level_is_the_bootstrap() -> None:
    # White noise alone (N = 0.2 deg/√h), 8000 samples at 0.1 s.
    n, tau0 = 8000, 0.1
    y = simulate(Truth(arw=0.2 / 60), n, tau0, np.random.default_rng(7))
    m = tau_grid(n)
    tau, adev = oadev(y, tau0, m)
    fitted = fit(tau, adev ** 2, m, n + 1)
    single = bootstrap(fitted, tau, m, n, tau0, replicates=60, seed=3)
    outer, inner = double_bootstrap(fitted, tau, m, n, tau0, replicates=60, seed=3)
    # the same replicates as the single bootstrap's for the same seed, row for row
    np.testing.assert_array_equal(outer, single)
    assert inner.shape == outer.shape and not np.array_equal(inner, outer)
    # each inner record is drawn about its replicate's fit: N²'s relative scatter about
    # the replicate, c**/c* − 1, is the outer level's about the record, c*/ĉ − 1 (N's
    # estimate has the same EDF at both levels), within the noise of 60 replicates
    # (the ratio of two standard deviations of 60 values: about ±13 % at 1σ)
    spread_outer = float(np.std(outer[:, 1] / fitted.coef[1] - 1.0))
    spread_inner = float(np.std(inner[:, 1] / outer[:, 1] - 1.0))
    assert 0.6 < spread_inner / spread_outer < 1.6
    assert spread_outer > 0.0
    assert math.isfinite(spread_inner)


def test_an_unknown_interval_method_is_refused() -> None:
    # a misspelt method must not fall through to the pivot and be reported under its name
    with pytest.raises(ValueError, match="unknown interval method 'studentised'"):
        intervals(1.0, 0, np.ones((10, 5)), (0.68,), "studentised", None,
                  np.ones(5, dtype=bool))
