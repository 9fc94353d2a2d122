"""Whether B's fits are over-dispersed between ranges of the coverage study under a seeding
(docs/error-budget.md section 5). Run on demand (it is not part of the test suite)::

    python benchmarks/allan_seed_dispersion.py                 # 150 ranges per seeding
    python benchmarks/allan_seed_dispersion.py --ranges 40     # a quicker look

For each of two seedings — the integers first + r (first = 1001 + 2000·k for range k),
and the entropy (k, r, 7) hashed by numpy's SeedSequence — it simulates the coverage
study's records with flicker (its cases 1 and 3, 80 records of 2¹⁵ samples per range;
synthetic, drawn by ``gyrovib.core.allan_sim``), fits each as ``gyrovib allan`` does
without a bootstrap, and counts per range the records whose B lies within ``--within``
(5.6 %, the bootstrap's typical half-width there) of the truth. Independent records make
those counts binomial: the χ² of their spread over the ranges, its p-value, and the
correlation between a range's share over its odd and over its even records are printed.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Callable

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "src"))

from bench_allan_coverage import CASES, TAU0

from gyrovib.core.allan import oadev, tau_grid
from gyrovib.core.allan_fit import fit, roll_off
from gyrovib.core.allan_sim import simulate

SAMPLES = 1 << 15


def b_ratio(seed: int | list[int], case: int, m_all: np.ndarray) -> float:
    """B fitted / B true on one record of the study's ``case``."""
    truth = CASES[case][1]
    y = simulate(truth, SAMPLES, TAU0, np.random.default_rng(seed))
    tau, adev = oadev(y, TAU0, m_all)
    start = roll_off(tau, adev)
    fitted = fit(tau[start:], adev[start:] ** 2, m_all[start:], SAMPLES + 1,
                 filtered=start > 0)
    return float(np.sqrt(max(fitted.coef[2], 0.0)) / truth.bias_instability)


def dispersion(seed_of: Callable[[int, int], int | list[int]], ranges: int,
               within: float) -> tuple[float, int, float, float]:
    """χ², degrees of freedom, p and the odd/even correlation of the per-range counts."""
    from scipy import stats

    m_all = tau_grid(SAMPLES)
    held = np.array([[abs(b_ratio(seed_of(k, r), r % 5, m_all) - 1.0) < within
                      for r in range(200) if r % 5 in (1, 3)] for k in range(ranges)])
    counts = held.sum(axis=1)
    n = held.shape[1]
    p = counts.sum() / held.size
    chi2 = float(np.sum((counts - n * p) ** 2 / (n * p * (1 - p))))
    odd, even = held[:, 1::2].mean(axis=1), held[:, 0::2].mean(axis=1)
    return chi2, ranges - 1, float(stats.chi2.sf(chi2, ranges - 1)), float(
        np.corrcoef(odd, even)[0, 1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--ranges", type=int, default=150)
    parser.add_argument("--within", type=float, default=0.056)
    args = parser.parse_args()
    seedings: dict[str, Callable[[int, int], int | list[int]]] = {
        "integers first + r": lambda k, r: 1001 + 2000 * k + r,
        "SeedSequence (k, r, 7)": lambda k, r: int(
            np.random.SeedSequence([k, r, 7]).generate_state(1)[0]),
    }
    for name, seed_of in seedings.items():
        start = time.perf_counter()
        chi2, df, p, corr = dispersion(seed_of, args.ranges, args.within)
        print(f"{name:24} χ² {chi2:6.1f} on {df} df, p = {p:.3g}; odd/even correlation "
              f"{corr:.3f} ({time.perf_counter() - start:.0f} s)", flush=True)


if __name__ == "__main__":
    main()
