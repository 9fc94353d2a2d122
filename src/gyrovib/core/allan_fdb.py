"""The fast double bootstrap's calibration of an interval's level (docs/model.md section
15; Davidson & MacKinnon 2007, "Improving the reliability of bootstrap tests with the fast
double bootstrap", Comput. Stat. Data Anal. 51; Chang & Hall 2015, "Double-bootstrap
methods that use a single double-bootstrap simulation", Biometrika 102).

A bootstrap interval takes the γ-quantile of a root's replicates T* (distribution F*) for
the quantile of the root T itself (distribution F). Where the replicates are drawn from a
fitted model that is wrong in a way that matters (the noise model's fit reads a rate
random walk low, and bias instability's scatter grows with it), F* is shifted or narrower
than F, and the interval covers less than γ says. One level down the same happens again:
from each replicate's own fit one more record is drawn and refitted, and its root T**
taken about that replicate's fit, so the pooled T** (distribution F**) stand to F* as F*
stands to F. The level at which F** puts the nominal quantile of F*,

    γ' = F**(F*⁻¹(γ)),

is the level F*'s quantile must be read at to hold γ of F, and the interval takes
F*⁻¹(γ'). Where F* = a·F and F** = a·F* (a spread too small by a factor a), this gives
F⁻¹(γ) exactly: γ' = F**(a·F⁻¹(γ)) = F(F⁻¹(γ)/a) read back through F* = a·F. It costs
one further record per replicate (twice the single bootstrap), where a nested double
bootstrap costs some 25 times.

The interval is then the set of c where the calibrated quantiles hold the root
(:func:`inverted`; the studentized root of :func:`gyrovib.core.allan_fit.studentized`).

What ``allan`` uses: :func:`inverted` and :func:`bisect` build every studentized interval,
and :func:`calibrated` without inner roots is the plain quantiles. The calibration itself
(the ``calibrated`` method) is run only by the coverage study
(benchmarks/bench_allan_coverage.py ``--interval calibrated``), for comparison: measured
there it does not improve the coverage (docs/error-budget.md section 5).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from gyrovib.core._types import FloatArray


def level(inner: FloatArray, at: float) -> float:
    """F**(at): the share of the inner roots below ``at``, ties counted half."""
    below = np.count_nonzero(inner < at)
    tied = np.count_nonzero(inner == at)
    return float((below + 0.5 * tied) / inner.size)


def calibrated(outer: FloatArray, inner: FloatArray, levels: Sequence[float]) -> list[float]:
    """F*⁻¹(F**(F*⁻¹(γ))) for each γ in ``levels``: the outer roots' quantile at the level
    the inner roots calibrate (module docstring); non-finite roots are left out, and
    with fewer than 10 inner roots the nominal quantiles are returned."""
    outer = outer[np.isfinite(outer)]
    inner = inner[np.isfinite(inner)]
    nominal = [float(q) for q in np.quantile(outer, levels)]
    if inner.size < 10:
        return nominal
    return [float(np.quantile(outer, level(inner, q))) for q in nominal]


def bisect(f: Callable[[float], float], lo: float, hi: float, target: float) -> float:
    """x in [lo, hi] where the decreasing f crosses ``target`` (bisection)."""
    for _ in range(48):
        mid = 0.5 * (lo + hi)
        if f(mid) > target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def inverted(root: Callable[[float], float], c_hat: float, q_lo: float, q_hi: float
             ) -> tuple[float, float] | None:
    """√ of the c where q_lo ≤ root(c) ≤ q_hi (root decreasing, 0 at ĉ); None where it
    has no upper end. Where both quantiles lie on one side of 0 (q_hi ≤ 0 or q_lo ≥ 0)
    that set lies wholly on one side of ĉ; the interval is then taken from ĉ itself to
    its far end, so that it always holds the estimate."""
    # the least c tried is a little above 0: at 0 a term alone in its model has none
    floor = c_hat * 1e-12
    lo = c_hat if q_hi <= 0 else (0.0 if root(floor) <= q_hi
                                  else bisect(root, floor, c_hat, q_hi))
    if q_lo >= 0:
        return math.sqrt(lo), math.sqrt(c_hat)
    top = 2.0 * c_hat
    while root(top) > q_lo:
        top *= 2.0
        if top > c_hat * 2.0 ** 40:
            return None
    return math.sqrt(lo), math.sqrt(bisect(root, c_hat, top, q_lo))


__all__ = ["bisect", "calibrated", "inverted", "level"]
