"""The interval constructions the coverage study compares with gyrovib's own
(docs/error-budget.md section 5; benchmarks/bench_allan_coverage.py ``--interval``).

gyrovib reports the studentized interval of ``gyrovib.core.allan_fit`` ("studentized",
read at the levels of ``gyrovib.core.allan_levels``). For comparison the study can also
read the same replicates as:

* "pivot": the ratio pivot θ̂/q_hi … θ̂/q_lo of the replicates' θ*/θ̂, at the nominal level;
* "percentile": θ̂·q_lo … θ̂·q_hi, the replicates' own quantiles;
* "calibrated": the studentized interval at the level the fast double bootstrap
  calibrates (Davidson & MacKinnon 2007, "Improving the reliability of bootstrap tests
  with the fast double bootstrap", Comput. Stat. Data Anal. 51; Chang & Hall 2015,
  "Double-bootstrap methods that use a single double-bootstrap simulation",
  Biometrika 102).

The fast double bootstrap: a bootstrap interval takes the γ-quantile of a root's
replicates T* (distribution F*) for the quantile of the root T itself (F). One level
down, from each replicate's own fit one more record is drawn and refitted, its root T**
taken about that replicate's fit, so that the pooled T** (F**) stand to F* as F* stands
to F. The level at which F** puts the nominal quantile of F*,

    γ' = F**(F*⁻¹(γ)),

is the level F*'s quantile must be read at to hold γ of F, and the interval takes
F*⁻¹(γ'). Where F* = a·F and F** = a·F* (a spread too small by a factor a), this gives
F⁻¹(γ) exactly. It costs one further record per replicate. Measured by the study it does
not improve the coverage, which is why gyrovib does not use it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from gyrovib.core import allan_fit
from gyrovib.core.allan_fit import (
    Curve,
    Fit,
    Term,
    _refine,
    _replicate_curves,
    design,
    envelope_bound,
    inverted,
    resolution,
    scale,
    studentized_root,
)

#: gyrovib's own interval, and every construction the study can compare it with.
METHOD = "studentized"
METHODS = ("studentized", "calibrated", "pivot", "percentile")


def level(inner: np.ndarray, at: float) -> float:
    """F**(at): the share of the inner roots below ``at``, ties counted half."""
    below = np.count_nonzero(inner < at)
    tied = np.count_nonzero(inner == at)
    return float((below + 0.5 * tied) / inner.size)


def calibrated(outer: np.ndarray, inner: np.ndarray, levels: Sequence[float]) -> list[float]:
    """F*⁻¹(F**(F*⁻¹(γ))) for each γ in ``levels``: the outer roots' quantile at the level
    the inner roots calibrate (module docstring); non-finite roots are left out, and
    with fewer than 10 inner roots the nominal quantiles are returned."""
    outer = outer[np.isfinite(outer)]
    inner = inner[np.isfinite(inner)]
    nominal = [float(q) for q in np.quantile(outer, levels)]
    if inner.size < 10:
        return nominal
    return [float(np.quantile(outer, level(inner, q))) for q in nominal]


def double_bootstrap(fitted: Fit, tau: np.ndarray, m: np.ndarray, n: int, tau0: float,
                     replicates: int = 200, seed: int = 0,
                     sim_cap: int = 1 << 15) -> tuple[np.ndarray, np.ndarray]:
    """``allan_fit.bootstrap``'s replicates (the same for the same seed) and, row for row,
    the coefficients of one record of each replicate's own fit, refitted the same way: the
    fast double bootstrap's second level."""
    curves = _replicate_curves(fitted, tau, m, n, tau0, replicates,
                               np.random.default_rng(seed), sim_cap)
    rng = np.random.default_rng([seed, 1])
    outer, inner = [], []
    for curve in curves:
        once = _refine(tau, curve, m, n + 1, fitted.tau_c, fitted.filtered)
        again = _replicate_curves(once, tau, m, n, tau0, 1, rng, sim_cap)[0]
        outer.append(once.coef)
        inner.append(_refine(tau, again, m, n + 1, fitted.tau_c, fitted.filtered).coef)
    return np.array(outer), np.array(inner)


def _calibrated_studentized(curve: Curve, j: int, replicates: np.ndarray,
                            resolved: np.ndarray, confidences: tuple[float, ...],
                            inner: np.ndarray) -> list[tuple[float, float] | None] | None:
    """The studentized interval read at the levels the inner roots (c** − c*)/s(c*)
    calibrate; None where the root has none at one confidence."""
    if (found := studentized_root(curve, j, replicates, resolved)) is None:
        return None
    t_star, root, active = found
    t_inner = np.array([(c2[j] - c1[j]) / scale(curve, c1, j, active)
                        for c1, c2 in zip(replicates, inner, strict=True)])
    out = []
    for confidence in confidences:
        q_lo, q_hi = calibrated(t_star, t_inner, [(1.0 - confidence) / 2.0,
                                                  (1.0 + confidence) / 2.0])
        out.append(inverted(root, float(curve.fitted.coef[j]), q_lo, q_hi))
    return None if any(f is None for f in out) else out


def intervals(value: float, j: int, replicates: np.ndarray, confidences: tuple[float, ...],
              method: str, curve: Curve, resolved: np.ndarray,
              inner: np.ndarray | None = None) -> tuple[tuple[float, float], ...]:
    """Term j's interval at each confidence by ``method`` (one of :data:`METHODS`);
    "calibrated" needs the ``inner`` replicates (without them it is "studentized"), and
    its pivot (where the studentized root has none) is read at the calibrated levels
    too, the inner ratios θ**/θ* beside the θ*/θ̂."""
    if method not in METHODS:
        raise ValueError(f"unknown interval method {method!r}: one of {', '.join(METHODS)}")
    if method == METHOD or (method == "calibrated" and inner is None):
        return allan_fit.intervals(value, j, replicates, confidences, curve, resolved)
    root = np.sqrt(np.maximum(replicates[:, j], 0.0))
    ratio = root / value
    if method == "calibrated":
        assert inner is not None
        found = _calibrated_studentized(curve, j, replicates, resolved, confidences, inner)
        if found is not None:
            return tuple(f for f in found if f is not None)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio2 = np.sqrt(np.maximum(inner[:, j], 0.0)) / root
    else:
        ratio2 = np.array([])
    out = []
    for c in confidences:
        lo_q, hi_q = calibrated(ratio, ratio2, [(1.0 - c) / 2.0, (1.0 + c) / 2.0])
        if method == "percentile":
            out.append((value * lo_q, value * hi_q))
        else:
            out.append((value / hi_q, value / lo_q if lo_q > 0 else math.inf))
    return tuple(out)


def terms(curve: Curve, replicates: np.ndarray, confidences: tuple[float, ...],
          method: str = METHOD, inner: np.ndarray | None = None) -> tuple[Term, ...]:
    """Each term as ``allan_fit.terms`` gives it, its interval by ``method``: gyrovib's own
    (read at its per-term levels) for :data:`METHOD`, the others at the nominal level."""
    if method == METHOD:
        return allan_fit.terms(curve, replicates, confidences)
    fitted = curve.fitted
    resolved = resolution(fitted, curve.tau, replicates)
    basis = design(curve.tau, fitted.tau_c)
    out = []
    for j in range(fitted.coef.size):
        value = 0.0 if (j == 0 and fitted.filtered) else math.sqrt(max(fitted.coef[j], 0.0))
        found = (intervals(value, j, replicates, confidences, method, curve, resolved, inner)
                 if resolved[j] else None)
        if found is None or found[-1][0] <= 0.0:
            out.append(Term(None, (), max(envelope_bound(basis[:, j], curve.var, fitted.nu),
                                          value)))
        else:
            out.append(Term(value, found, None))
    return tuple(out)
