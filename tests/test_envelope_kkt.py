"""Newton's polish of the envelope's grid optimum (gyrovib.core.envelope_kkt).

References: V. Markov's bound for the odd coefficients of a polynomial bounded
by 1 on [−1, 1] (|a5| ≤ 16, attained by T5 = 16u⁵ − 20u³ + 5u, whose extrema
are cos(jπ/5)); the grid exchange alone (the polish switched off), which
converges to the same optimum from the other side; weak duality (the dual
bound is never below a feasible value).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.core import envelope_kkt, envelope_lp
from gyrovib.core.envelope_basis import FITS, true_max

MINIMAX = FITS.index("minimax")


def test_polish_reaches_chebyshev_from_a_perturbed_start() -> None:
    # max y5 over the minimax envelope: T5, h = 16, contact points cos(jπ/5), j = 0…5, with
    # signs (−1)^j·… alternating; start 1e-2 off in every point and 5 % off in y and λ
    ext = np.cos(np.pi * np.arange(6) / 5)[::-1]           # −1 … 1
    signs = np.array([-1.0, 1.0, -1.0, 1.0, -1.0, 1.0])     # T5(−1) = −1, alternating
    y_t5 = np.array([0.0, 0.0, -20.0, 0.0, 16.0])
    line_t5 = np.array([0.0, -5.0])                          # r = y·ψ − α − β·u, −β·u = 5u
    u0 = ext + np.array([0.0, 1e-2, -1e-2, 1e-2, -1e-2, 0.0])
    d = np.array([[0.0, 0.0, 0.0, 0.0, 1.0]])
    # the dual weights: d = Σ s_j λ_j ψ̃(v_j) at the Chebyshev points, solved directly
    psi = envelope_kkt._psi(np.array([MINIMAX]), ext[None, :])[0]   # (6, 7)
    lam = np.linalg.lstsq((signs[:, None] * psi).T, np.r_[d[0], 0.0, 0.0], rcond=None)[0]
    assert np.all(lam > 0) and lam.sum() == pytest.approx(16.0, rel=1e-12)
    pol = envelope_kkt.polish(np.array([MINIMAX]), d, y_t5[None] * 1.05, line_t5[None] * 0.95,
                              u0[None], signs[None], lam[None] * 1.05,
                              np.ones((1, 6), dtype=bool), 1e-12)
    assert pol.ok[0]
    assert pol.h[0] == pytest.approx(16.0, rel=1e-13)
    assert pol.upper[0] == pytest.approx(16.0, rel=1e-13)
    np.testing.assert_allclose(pol.points[0][~np.isnan(pol.points[0])], ext, atol=1e-12)
    np.testing.assert_allclose(pol.y[0], y_t5, atol=1e-10)


def test_wrong_contact_set_is_not_accepted() -> None:
    # the same problem started from only three of T5's six points: Newton may settle on
    # something, but its dual bound cannot agree with a feasible value, so it is refused
    ext = np.cos(np.pi * np.arange(6) / 5)[::-1]
    pick = np.array([0, 2, 4])
    pol = envelope_kkt.polish(np.array([MINIMAX]), np.array([[0.0, 0, 0, 0, 1.0]]),
                              np.array([[0.0, 0, -20.0, 0, 16.0]]), np.array([[0.0, -5.0]]),
                              ext[pick][None], np.array([[-1.0, -1.0, -1.0]]),
                              np.array([[3.0, 3.0, 3.0]]), np.ones((1, 3), dtype=bool), 1e-7)
    assert not pol.ok[0]


def test_contacts_merge_neighbours_straddling_an_extremum() -> None:
    # T5's interior extrema cos(π/5), cos(2π/5), … are not on this grid: the grid optimum
    # touches ±1 at neighbouring points on both sides of each; merged, there are T5's six
    # alternating contact points, each within a grid step of cos(jπ/5)
    grid = np.linspace(-1.0, 1.0, 41)
    lp = envelope_lp._GridLP(np.array([MINIMAX]), np.array([np.inf]),
                             np.array([[0.0, 0, 0, 0, 1.0]]), [grid])
    hg, _, _, x = lp.solve()
    u, s, lam, act = lp.contacts(x, np.array([0]))
    # strong duality on the grid: the weights sum to the grid optimum, an upper bound of 16
    assert lam[0][act[0]].sum() == pytest.approx(hg[0], rel=1e-9)
    assert hg[0] >= 16.0 * (1 - 1e-12)
    got = u[0][act[0]]
    assert got.size == 6
    assert np.all(np.diff(got) > 0)
    assert np.all(s[0][act[0]][1:] == -s[0][act[0]][:-1])
    np.testing.assert_allclose(got, np.cos(np.pi * np.arange(6) / 5)[::-1], atol=0.05)


def _exchange_only(monkeypatch: pytest.MonkeyPatch) -> None:
    real = envelope_lp._polish

    def never(*args: object, **kwargs: object) -> envelope_kkt.Polished:
        pol = real(*args, **kwargs)  # type: ignore[arg-type]
        return dataclasses.replace(pol, ok=np.zeros_like(pol.ok))

    monkeypatch.setattr(envelope_lp, "_polish", never)


def _count_accepted(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Record how many pairs each polish (from the grid or from a neighbour) certifies."""
    accepted: list[int] = []
    grid, seeded = envelope_lp._polish, envelope_kkt.polish

    def from_grid(*args: object, **kwargs: object) -> envelope_kkt.Polished:
        pol = grid(*args, **kwargs)  # type: ignore[arg-type]
        accepted.append(int(pol.ok.sum()))
        return pol

    def from_neighbour(*args: object, **kwargs: object) -> envelope_kkt.Polished:
        pol = seeded(*args, **kwargs)  # type: ignore[arg-type]
        accepted.append(int(pol.ok.sum()))
        return pol

    monkeypatch.setattr(envelope_lp, "_polish", from_grid)
    monkeypatch.setattr(envelope_lp.envelope_kkt, "polish", from_neighbour)
    return accepted


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), fit=st.sampled_from(range(len(FITS))))
def test_polished_equals_exchange_alone(seed: int, fit: int) -> None:
    # random directions (sparse ones included, where the optimum is degenerate): the support
    # with the polish and with the grid exchange alone agree to the exchange's tolerance, and
    # every answer is feasible on the continuous range (true max |r| ≤ 1)
    rng = np.random.default_rng(seed)
    d = rng.normal(size=(6, 5)) * (rng.random((6, 5)) < 0.7)
    d[np.all(d == 0, axis=1), 1] = 1.0
    f = np.full(6, fit)
    ms = np.zeros(6, dtype=int)
    a = np.full(6, np.inf)
    with pytest.MonkeyPatch.context() as mp:
        accepted = _count_accepted(mp)
        h, y, line, gap = envelope_lp.support(f, ms, a, d)
    assert sum(accepted) > 0  # the polish answered some of them
    with pytest.MonkeyPatch.context() as mp:
        _exchange_only(mp)
        h_ex, *_ = envelope_lp.support(f, ms, a, d)
    np.testing.assert_allclose(h, h_ex, rtol=3e-7)
    # support() returns the reference line itself (the fit's line added back): the
    # residual p(u) − line from it is what must stay within 1
    u = np.linspace(-1.0, 1.0, 20001)
    phi = np.stack([0.5 * np.abs(u), u**2, u**3, u**4, u**5], axis=1)
    r = y @ phi.T - line[:, :1] - line[:, 1:] * u
    assert np.max(np.abs(r)) <= 1.0 + 1e-9
    assert np.all(gap <= 1e-7)


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), fit=st.sampled_from(range(len(FITS))),
       cut=st.floats(0.01, 3.0))
def test_binding_cut_is_polished_like_the_exchange(seed: int, fit: int, cut: float) -> None:
    # with |y1| ≤ a binding (directions weighting A1 heavily), the polish solves the
    # conditions with the cut's weight μ; it agrees with the grid exchange alone and its
    # answer respects the cut
    rng = np.random.default_rng(seed)
    d = rng.normal(size=(4, 5))
    d[:, 0] = 5.0 + rng.random(4)
    f = np.full(4, fit)
    ms = np.zeros(4, dtype=int)
    a = np.full(4, cut)
    accepted: list[int] = []
    real = envelope_lp._polish

    def spy(*args: object, **kwargs: object) -> envelope_kkt.Polished:
        pol = real(*args, **kwargs)  # type: ignore[arg-type]
        accepted.append(int(pol.ok.sum()))
        return pol

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(envelope_lp, "_polish", spy)
        h, y, _, gap = envelope_lp.support(f, ms, a, d)
    with pytest.MonkeyPatch.context() as mp:
        _exchange_only(mp)
        h_ex, *_ = envelope_lp.support(f, ms, a, d)
    np.testing.assert_allclose(h, h_ex, rtol=3e-7)
    assert np.all(np.abs(y[:, 0]) <= cut * (1 + 1e-12))
    assert np.all(gap <= 1e-7)
    assert sum(accepted) > 0


@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), fit=st.sampled_from(range(len(FITS))),
       cut=st.sampled_from([np.inf, 0.3]))
def test_seeded_from_neighbours_equals_solved_alone(seed: int, fit: int, cut: float) -> None:
    # a sweep-like run: directions along a smooth path (neighbours alike), enough of them
    # that every SPACING-th is solved by the grid LP and the others are polished from
    # their neighbours; each answer equals the one solved without neighbours
    rng = np.random.default_rng(seed)
    k = envelope_lp.SEEDED + 40
    t = np.linspace(0.0, 1.0, k)[:, None]
    d = rng.normal(size=(1, 5)) + t * rng.normal(size=(1, 5)) + t**2 * rng.normal(size=(1, 5))
    f = np.full(k, fit)
    ms = np.zeros(k, dtype=int)
    a = np.full(k, cut)
    with pytest.MonkeyPatch.context() as mp:
        accepted = _count_accepted(mp)
        h, y, _, gap = envelope_lp.support(f, ms, a, d)
    # the grid LP's polish certifies the anchors, the neighbours' polish most of the rest
    assert sum(accepted) > k // 2
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(envelope_lp, "SEEDED", 10**9)
        h_alone, *_ = envelope_lp.support(f, ms, a, d)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(envelope_lp, "WINDOW", 100)  # windows of 100 pairs, the last one short
        h_windows, *_ = envelope_lp.support(f, ms, a, d)
    np.testing.assert_allclose(h, h_alone, rtol=2e-7)
    np.testing.assert_allclose(h_windows, h_alone, rtol=2e-7)
    assert np.all(gap <= 1e-7)
    assert np.all(np.abs(y[:, 0]) <= cut * (1 + 1e-12))


def test_true_max_of_the_polished_chebyshev_is_one() -> None:
    # the feasible y returned for max y5 (minimax) is T5 itself: max |r| = 1 exactly
    h, y, line, _ = envelope_lp.support(np.array([MINIMAX]), np.array([0]), np.array([np.inf]),
                                        np.array([[0.0, 0, 0, 0, 1.0]]))
    assert h[0] == pytest.approx(16.0, rel=1e-9)
    mx, _ = true_max(np.array([MINIMAX]), y, line)
    assert mx[0] == pytest.approx(1.0, abs=1e-9)
