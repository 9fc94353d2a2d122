"""Coverage at any level, from the roots the coverage study saved (docs/error-budget.md
section 5). Run after ``bench_allan_coverage.py --save FILE`` (one file per range)::

    python benchmarks/allan_coverage_levels.py /tmp/cov_5001.pkl /tmp/cov_7001.pkl
    python benchmarks/allan_coverage_levels.py --plain FILE...     # the levels as asked
    python benchmarks/allan_coverage_levels.py --solve FILE...     # the levels that hit 68/95

For each record and term the study saved what decides whether the interval holds the
truth at a level γ: the replicates' studentized roots T* and the record's root at the
truth, at 0 and far above the estimate (where the interval would have no upper end),
and the replicates' ratios θ*/θ̂ for the pivot. The interval of
``gyrovib.core.allan_fit.studentized`` at γ holds the truth exactly when
min(q_lo, 0) ≤ T(θ²) ≤ max(q_hi, 0), q the (1 ∓ γ)/2 quantiles of T*; it has no upper
end when T far above stays above q_lo (the pivot is then used at every level, as
``intervals`` does); its lower end is 0, and the term a bound, when T(0) ≤ q_hi at the
95 % level. So the whole study can be read at other levels without running it again.
By default the levels are those ``allan_fit.read_level`` reads for 68 % and 95 %.
"""

from __future__ import annotations

import argparse
import math
import os
import pickle
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "src"))

from gyrovib.core.allan_fit import TERMS, read_level

Row = dict[str, object]


def _quantiles(values: np.ndarray, level: float) -> tuple[float, float]:
    values = values[np.isfinite(values)]
    lo, hi = np.quantile(values, [(1.0 - level) / 2.0, (1.0 + level) / 2.0])
    return float(lo), float(hi)


def judge(row: Row, levels: tuple[float, float], key: str = "own"
          ) -> tuple[str, bool, bool]:
    """('value', held at the first level, at the second), ('bound', holds, holds), or
    ('none', …) where the term has no interval (fitted at 0)."""
    true, value = float(row["true"]), float(row["value"])  # type: ignore[arg-type]
    if key == "own" and not row["resolved"]:
        return "bound", true <= float(row["bound"]), true <= float(row["bound"])  # type: ignore[arg-type]
    roots = row[key]
    ratio = row["ratio"]
    if ratio is None:
        return "none", False, False
    held: list[bool] = []
    zero = False
    stud = roots is not None
    if stud:
        assert isinstance(roots, dict)
        qs = [_quantiles(roots["t_star"], g) for g in levels]
        stud = not any(q_lo < 0 and roots["t_top"] > q_lo for q_lo, _ in qs)
    if stud:
        t = roots["t_true"]  # type: ignore[index]
        held = [min(q_lo, 0.0) <= t <= max(q_hi, 0.0) for q_lo, q_hi in qs]
        q_hi = qs[-1][1]
        zero = q_hi > 0 and roots["t_zero"] <= q_hi  # type: ignore[index]
    else:
        assert isinstance(ratio, np.ndarray)
        x = value / true
        held = [lo <= x <= hi for lo, hi in (_quantiles(ratio, g) for g in levels)]
    if key == "own" and zero:
        return "bound", true <= float(row["bound"]), true <= float(row["bound"])  # type: ignore[arg-type]
    return "value", held[0], held[1]


def coverage(rows: list[Row], term: int, levels: tuple[float, float], key: str = "own"
             ) -> tuple[int, float, float, int, float]:
    """Values, share held at each level, bounds, share of bounds holding."""
    got = [judge(r, levels, key) for r in rows if r["term"] == term and r["true"] > 0]
    values = [g for g in got if g[0] == "value"]
    bounds = [g for g in got if g[0] == "bound"]
    if key == "every":
        values = [g for g in got if g[0] != "bound"]  # a term fitted at 0 misses
    c68 = float(np.mean([g[1] for g in values])) if values else math.nan
    c95 = float(np.mean([g[2] for g in values])) if values else math.nan
    hold = float(np.mean([g[1] for g in bounds])) if bounds else math.nan
    return len(values), c68, c95, len(bounds), hold


def solve(rows: list[Row], term: int, targets: tuple[float, float] = (0.68, 0.95)
          ) -> tuple[float, float]:
    """The levels, on a grid of 0.005, at which the pooled coverage first reaches each
    target (the second level first: it sets which records are bounds)."""
    grid = np.round(np.arange(0.40, 0.9951, 0.005), 3)
    hi = next((float(g) for g in grid
               if coverage(rows, term, (0.68, float(g)))[2] >= targets[1]), 0.995)
    lo = next((float(g) for g in grid
               if coverage(rows, term, (float(g), hi))[1] >= targets[0]), 0.995)
    return lo, hi


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("files", nargs="+")
    parser.add_argument("--plain", action="store_true",
                        help="read the intervals at 68 % and 95 % as asked")
    parser.add_argument("--solve", action="store_true",
                        help="print, per term, the levels at which the pooled coverage "
                             "first reaches 68 % and 95 %")
    args = parser.parse_args()
    rows: list[Row] = []
    for name in args.files:
        with open(name, "rb") as f:
            rows.extend(pickle.load(f))
    # a record is (range, record) where saved so (its "seed" is range + record, a label)
    seeds = {(r.get("range"), r.get("record"), int(r["seed"]))  # type: ignore[call-overload]
             for r in rows}
    print(f"{len(seeds)} records from {len(args.files)} file(s)")
    print(f"{'term':18} {'levels read':>13} {'values':>7} {'68 % cover':>16} "
          f"{'95 % cover':>16} {'bounds':>7} {'hold':>7} {'every 68/95':>13}")
    for j, term in enumerate(TERMS):
        levels = ((0.68, 0.95) if args.plain
                  else (read_level(j, 0.68), read_level(j, 0.95)))
        v, c68, c95, b, hold = coverage(rows, j, levels)
        if v == 0 and b == 0:
            continue
        ev = coverage(rows, j, levels, "every")
        se68, se95 = (100 * math.sqrt(p * (1 - p) / max(v, 1)) for p in (0.68, 0.95))
        print(f"{term:18} {levels[0]:6.3f}/{levels[1]:5.3f} {v:7d} "
              f"{100 * c68:6.1f} % (± {se68:3.1f}) {100 * c95:6.1f} % (± {se95:3.1f}) "
              f"{b:7d} {100 * hold:6.1f}% {100 * ev[1]:5.1f}/{100 * ev[2]:5.1f}")
        if args.solve:
            print(f"{'':18} levels reaching 68 % and 95 %: {solve(rows, j)}")


if __name__ == "__main__":
    main()
