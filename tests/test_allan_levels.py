"""The level each noise term's interval is read at (core/allan_levels.py): the calibration
the coverage study sets, the study's offline reading of saved roots
(benchmarks/allan_coverage_levels.py) against the intervals the noise model reports, and
each term read at its own level (the study itself: docs/error-budget.md section 5)."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from gyrovib.core.allan import oadev, tau_grid
from gyrovib.core.allan_fit import (
    TERMS,
    Curve,
    bootstrap,
    fit,
    intervals,
    resolution,
    terms,
)
from gyrovib.core.allan_levels import READ_LEVELS, read_level
from gyrovib.core.allan_sim import simulate
from tests.docpages import ROOT

sys.path.insert(0, str(ROOT / "benchmarks"))

import allan_coverage_levels as levels
import bench_allan_coverage as study


def _docs_levels() -> dict[str, tuple[float, float]]:
    """The levels table of docs/error-budget.md section 5 (percent), by term."""
    text = (ROOT / "docs" / "error-budget.md").read_text(encoding="utf-8")
    table = text[text.index("term                68 % read at"):]
    table = table[:table.index("```")]
    rows = [line.split() for line in table.splitlines()[1:] if line.strip()]
    return {r[0]: (float(r[1]) / 100.0, float(r[3]) / 100.0) for r in rows}


def test_the_read_levels_are_the_documented_ones_and_keep_their_order() -> None:
    # The levels in code are the table docs/error-budget.md quotes, term by term in
    # TERMS order (a swap of two terms' levels fails here).
    documented = _docs_levels()
    assert list(documented) == list(TERMS)
    grid = np.linspace(0.0, 1.0, 201)
    for j, term in enumerate(TERMS):
        r68, r95 = READ_LEVELS[j]
        assert (r68, r95) == pytest.approx(documented[term], abs=1e-12), term
        assert read_level(j, 0.68) == pytest.approx(r68)
        assert read_level(j, 0.95) == pytest.approx(r95)
        assert 0.0 < r68 < r95 < 1.0
        read = [read_level(j, float(g)) for g in grid]
        # a higher confidence is read at a higher level: the intervals still nest
        assert all(np.diff(read) > 0)
        assert read[0] == 0.0 and read[-1] == 1.0
    # the Gauss–Markov σ, which the study does not simulate, is read as asked
    assert read_level(len(TERMS), 0.68) == 0.68


@pytest.mark.parametrize("case", [3, 4])
def test_each_term_is_read_at_its_own_level(case: int) -> None:
    # One record of the study's case with flicker and random walk (3) and of its case
    # with quantization and a ramp (4), 2¹³ samples, seed 950: each resolved term's
    # intervals, as the noise model gives them, are the replicates read at that term's
    # own levels (READ_LEVELS[j], by index: not through read_level), and for the ramp they
    # differ from the intervals read at the nominal 68 % and 95 %.
    n, tau0 = 1 << 13, 1.0
    y = simulate(study.CASES[case][1], n, tau0, np.random.default_rng(950))
    m = tau_grid(n)
    tau, adev = oadev(y, tau0, m)
    var = adev**2
    fitted = fit(tau, var, m, n + 1, True)
    coefs = bootstrap(fitted, tau, m, n, tau0, seed=950)
    curve = Curve(tau, var, m, n + 1, fitted)
    got = terms(curve, coefs, (0.68, 0.95))
    resolved = resolution(fitted, tau, coefs)
    checked = 0
    for j, term in enumerate(got[:len(TERMS)]):
        if term.value is None:
            continue
        own = intervals(term.value, j, coefs, READ_LEVELS[j], curve, resolved)
        np.testing.assert_array_equal(term.intervals, own, err_msg=TERMS[j])
        checked += 1
        if TERMS[j] == "rate_ramp":
            nominal = intervals(term.value, j, coefs, (0.68, 0.95), curve, resolved)
            assert not np.allclose(nominal, own, rtol=1e-6, atol=0)
    assert checked >= 2


def test_the_studys_offline_reading_is_what_the_model_reports() -> None:
    # The study's --save roots, read at the calibrated levels (the pickled rows through
    # allan_coverage_levels.judge), must give, record by record, the same value-or-bound
    # and the same held/missed as the intervals noise_model reports: the coverage the
    # docs quote from the saved roots is the coverage of gyrovib's own intervals. One
    # record of each of the study's five cases (2¹³ samples, seeds 900–904).
    saved: list[dict[str, object]] = []
    got = study.run(5, 1 << 13, 900, (study.METHOD,), saved=saved)[study.METHOD]
    for j, term in enumerate(TERMS):
        rows = [r for r in saved if r["term"] == j and float(r["true"]) > 0]  # type: ignore[arg-type]
        want = [levels.judge(r, (read_level(j, 0.68), read_level(j, 0.95))) for r in rows]
        reported = [g for g in got[term] if g[0] != "absent"]
        assert [(w[0] == "bound", w[1], w[2]) for w in want] == [
            (g[0] == "bound", g[1], g[2]) for g in reported], term
        assert rows, term
