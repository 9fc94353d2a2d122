"""gyrovib.core.highs (HiGHS through highspy) against scipy's linprog, which
wraps its own copy of the same solver: same optimum, same row duals (scipy's
``eqlin.marginals`` / ``ineqlin.marginals``), and nothing printed."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.core import highs
from gyrovib.core.envelope_lp import minimax_line


def dense_to_csc(a: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Column-wise (start, index, value) of a dense matrix, written out by hand."""
    start, index, value = [0], [], []
    for j in range(a.shape[1]):
        rows = np.flatnonzero(a[:, j])
        index.extend(rows.tolist())
        value.extend(a[rows, j].tolist())
        start.append(len(index))
    return np.array(start), np.array(index, dtype=int), np.array(value)


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), m=st.integers(1, 6), extra=st.integers(1, 8))
def test_equality_lp_matches_linprog(seed: int, m: int, extra: int) -> None:
    # min cᵀx, A x = b, x ≥ 0 with b = A·x0 for some x0 ≥ 0 (feasible) and c > 0
    # (bounded): a random instance of the envelope's dual form
    from scipy.optimize import linprog

    rng = np.random.default_rng(seed)
    n = m + extra
    a = rng.normal(size=(m, n))
    a[rng.random((m, n)) < 0.3] = 0.0
    b = a @ rng.random(n)
    c = rng.random(n) + 0.1
    ref = linprog(c, A_eq=a, b_eq=b, bounds=(0, None), method="highs")
    got = highs.solve(c, *dense_to_csc(a), b, b, np.zeros(n), np.full(n, np.inf))
    # feasible (x0) and bounded below (c > 0, x ≥ 0): both must find the optimum
    assert ref.status == 0 and got.ok
    assert c @ got.x == pytest.approx(ref.fun, rel=1e-9, abs=1e-12)
    # the duals certify the optimum: bᵀλ = cᵀx (strong duality), c − Aᵀλ ≥ 0 (dual
    # feasibility), as scipy's eqlin.marginals do
    assert b @ got.row_dual == pytest.approx(ref.fun, rel=1e-7, abs=1e-9)
    assert b @ ref.eqlin.marginals == pytest.approx(ref.fun, rel=1e-7, abs=1e-9)
    assert np.all(c - a.T @ got.row_dual >= -1e-7)


def test_row_dual_sign_is_scipys() -> None:
    # min x1 + x2 s.t. x1 + 2·x2 = 1, x ≥ 0: x = (0, ½), and raising the right-hand
    # side by ε raises the optimum by ε/2, so the dual is +½ (scipy: eqlin.marginals = [0.5])
    got = highs.solve(np.array([1.0, 1.0]), np.array([0, 1, 2]), np.array([0, 0]),
                      np.array([1.0, 2.0]), np.array([1.0]), np.array([1.0]),
                      np.zeros(2), np.full(2, np.inf), options=highs.TIGHT)
    assert got.ok and got.status == "Optimal"
    np.testing.assert_allclose(got.x, [0.0, 0.5], atol=1e-12)
    np.testing.assert_allclose(got.row_dual, [0.5], atol=1e-12)


def test_infeasible_is_reported_not_raised() -> None:
    # x1 = 1 and x1 = −1 cannot both hold
    got = highs.solve(np.array([1.0]), np.array([0, 2]), np.array([0, 1]), np.array([1.0, 1.0]),
                      np.array([1.0, -1.0]), np.array([1.0, -1.0]), np.zeros(1), np.full(1, np.inf))
    assert not got.ok
    assert "nfeasible" in got.status


def test_nothing_is_printed(capfd: pytest.CaptureFixture[str]) -> None:
    # highspy.Highs() prints HiGHS's banner to the C-level stdout: a JSON document
    # written to stdout would be corrupted. The solve must print nothing at all.
    highs.solve(np.array([1.0]), np.array([0, 1]), np.array([0]), np.array([1.0]),
                np.array([2.0]), np.array([2.0]), np.zeros(1), np.full(1, np.inf))
    out, err = capfd.readouterr()
    assert out == "" and err == ""


def test_minimax_line_matches_linprog() -> None:
    # the line of least max deviation from p = w³ on [−1, 1]: by symmetry c0 = 0; the
    # Chebyshev alternation of w³ − c1·w gives c1 = ¾ (T3 = 4w³ − 3w), error ¼
    from scipy.optimize import linprog

    w = np.linspace(-1.0, 1.0, 2001)
    p = w**3
    line = minimax_line(w, p)
    assert np.max(np.abs(p - line)) == pytest.approx(0.25, rel=1e-9)
    np.testing.assert_allclose(line, 0.75 * w, atol=1e-9)
    rng = np.random.default_rng(7)
    q = rng.normal(size=w.size).cumsum() / 30.0
    n = w.size
    a = np.concatenate([np.column_stack([-np.ones(n), -w, -np.ones(n)]),
                        np.column_stack([np.ones(n), w, -np.ones(n)])])
    ref = linprog([0.0, 0.0, 1.0], A_ub=a, b_ub=np.concatenate([-q, q]),
                  bounds=[(None, None)] * 3, method="highs")
    assert np.max(np.abs(q - minimax_line(w, q))) == pytest.approx(ref.fun, rel=1e-9)
