"""Coverage of the noise model's intervals (docs/error-budget.md, docs/model.md section 15).

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_allan_coverage.py                 # 200 records
    python benchmarks/bench_allan_coverage.py --records 40    # a quicker look
    python benchmarks/bench_allan_coverage.py --seed 1001     # records not seen before
    python benchmarks/bench_allan_coverage.py --sim-cap 4096  # the long records' bootstrap
    python benchmarks/bench_allan_coverage.py --cases 2,3     # only the cases with K
    python benchmarks/bench_allan_coverage.py --save r.pkl    # and keep the roots (below)

Records of known terms are simulated (white rate noise, flicker, a rate random walk, a
rate ramp, angle quantization, in combinations cycled over the records; the numbers are
synthetic, drawn by ``gyrovib.core.allan_sim``; record r of the range ``--seed S`` from
the entropy (S, r), its bootstrap from (S, r, 1)), each analysed as ``gyrovib allan``
does, and for each term present in the truth the fraction of records whose 68 % and 95 %
intervals hold it is printed, with the number of records where the term was resolved (a
value) and where it was given as a bound (then whether the bound holds). Terms absent
from the truth must come out as bounds (or values whose interval is counted as a miss).
Every interval method named (--interval; those other than gyrovib's are in
benchmarks/allan_methods.py) is computed from the same replicates, and each is also
counted over every record whose truth has the term, resolved or not ("every record"):
the coverage before the choice between a value and a bound, which otherwise leaves out
the records where the term came out lowest. gyrovib's intervals are read at the levels
``gyrovib.core.allan_levels`` sets per term; ``--save`` keeps, per record and term, what
decides whether the interval holds at any level, which
benchmarks/allan_coverage_levels.py reads (the coverage at other levels, and the levels
that give 68 % and 95 %).
"""

from __future__ import annotations

import argparse
import math
import os
import pickle
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "src"))

from allan_methods import METHOD, METHODS, double_bootstrap, intervals, terms

from gyrovib.core.allan import oadev, tau_grid
from gyrovib.core.allan_fit import (
    SIM_CAP,
    TERMS,
    Curve,
    Fit,
    bootstrap,
    design,
    envelope_bound,
    fit,
    resolution,
    roll_off,
    studentized_root,
)
from gyrovib.core.allan_levels import read_level
from gyrovib.core.allan_sim import Truth, simulate

TAU0 = 1.0
#: Truths in the kernel's units (deg, deg/√s, deg/s, deg/s/√s, deg/s²): N = 0.1 deg/√h,
#: B = 1 deg/h, K = 3 deg/h/√h, R = 10 deg/h², Q = 3e-3 deg: over 2¹⁵ s (9.1 h) each
#: term present rules a stretch of the curve (N below 80 s, B to 530 s, K above).
N, B, K, R, Q = 0.1 / 60, 1.0 / 3600, 3.0 / 216_000, 10.0 / 3600 ** 2, 3e-3
CASES = (
    ("white", Truth(arw=N)),
    ("white+flicker", Truth(arw=N, bias_instability=B)),
    ("white+random walk", Truth(arw=N, rrw=K)),
    ("white+flicker+random walk", Truth(arw=N, bias_instability=B, rrw=K)),
    ("quantization+white+ramp", Truth(quantization=Q, arw=N, rate_ramp=R)),
)


#: The bootstrap seed of record r of range S under ``--integer-seeds``: INTEGER_BOOT + S + r.
INTEGER_BOOT = 1_000_000_000


def record_seed(first_seed: int, r: int, integer: bool = False) -> int | list[int]:
    """The entropy of record r of the range ``first_seed``: the pair, hashed by numpy's
    SeedSequence (records seeded with the integers first_seed + r had B's fit errors
    over-dispersed between ranges: docs/error-budget.md section 5). ``integer``: that
    integer seeding, with which the ranges the levels were set on were drawn."""
    return first_seed + r if integer else [first_seed, r]


def boot_seed(first_seed: int, r: int, integer: bool = False) -> int:
    """The seed of record r's bootstrap: drawn from the entropy (first_seed, r, 1), apart
    from the record's own; ``integer``: INTEGER_BOOT + first_seed + r."""
    if integer:
        return INTEGER_BOOT + first_seed + r
    return int(np.random.SeedSequence([first_seed, r, 1]).generate_state(1)[0])


def truth_values(truth: Truth) -> tuple[float, ...]:
    return (truth.quantization, truth.arw, truth.bias_instability, truth.rrw, truth.rate_ramp)


def run(records: int, samples: int, first_seed: int, methods: tuple[str, ...],
        sim_cap: int = SIM_CAP, cases: tuple[int, ...] = tuple(range(len(CASES))),
        saved: list[dict[str, object]] | None = None, integer_seeds: bool = False
        ) -> dict[str, dict[str, list[tuple[str, bool, bool]]]]:
    """Per interval method and term: (case, held at 68 %, held at 95 %) for resolved
    terms, and ('bound', holds, holds) for bounds — every method from the same fit and
    the same bootstrap replicates of each record; and per method + " (every record)"
    the same for every term present in the truth, its interval taken whether or not the
    record resolves it (a term fitted at 0 counts as a miss): the coverage before the
    choice between a value and a bound."""
    out = {meth: {name: [] for name in TERMS} for meth in methods}
    out.update({meth + " (every record)": {name: [] for name in TERMS} for meth in methods})
    m_all = tau_grid(samples)
    for r in range(records):
        name, truth = CASES[cases[r % len(cases)]]
        y = simulate(truth, samples, TAU0,
                     np.random.default_rng(record_seed(first_seed, r, integer_seeds)))
        boot = boot_seed(first_seed, r, integer_seeds)
        tau, adev = oadev(y, TAU0, m_all)
        start = roll_off(tau, adev)
        tau, var, m = tau[start:], adev[start:] ** 2, m_all[start:]
        fitted = fit(tau, var, m, samples + 1, filtered=start > 0)
        inner = None
        if "calibrated" in methods:   # the same outer replicates as bootstrap's, and more
            coefs, inner = double_bootstrap(fitted, tau, m, samples, TAU0, seed=boot,
                                            sim_cap=sim_cap)
        else:
            coefs = bootstrap(fitted, tau, m, samples, TAU0, seed=boot, sim_cap=sim_cap)
        curve = Curve(tau, var, m, samples + 1, fitted)
        if saved is not None:
            saved.extend(dict(row, range=first_seed, record=r) for row in _roots(
                first_seed + r, cases[r % len(cases)], truth, fitted, coefs, curve))
        for meth in methods:
            found = terms(curve, coefs, (0.68, 0.95), meth, inner)
            for term, got, true in zip(TERMS, found, truth_values(truth), strict=False):
                if got.resolved:
                    (lo68, hi68), (lo95, hi95) = got.intervals
                    out[meth][term].append((name if true > 0 else "absent",
                                            lo68 <= true <= hi68, lo95 <= true <= hi95))
                elif true > 0:
                    assert got.bound is not None
                    out[meth][term].append(("bound", true <= got.bound, true <= got.bound))
            every = out[meth + " (every record)"]
            for j, (term, true) in enumerate(zip(TERMS, truth_values(truth), strict=False)):
                if true > 0:
                    every[term].append((name, *_held(fitted, coefs, curve, j, true, meth,
                                                     inner)))
        if (r + 1) % 20 == 0:
            print(f"  {r + 1} records", file=sys.stderr, flush=True)
    return out


def _roots(seed: int, case: int, truth: Truth, fitted: Fit, coefs: np.ndarray,
           curve: Curve) -> list[dict[str, object]]:
    """What decides, at any level, whether each term's interval holds its truth (--save):
    the replicates' studentized roots and the record's root at the truth, at 0 and far
    above (where the interval has no upper end), and the replicates' ratios θ*/θ̂ (the
    pivot); as the term's own interval (its resolved neighbours refitted) and with every
    fitted term refitted (the study's "every record")."""
    resolved = resolution(fitted, curve.tau, coefs)
    basis = design(curve.tau, fitted.tau_c)
    everything = fitted.coef > 0
    out: list[dict[str, object]] = []
    for j, true in enumerate(truth_values(truth)):
        c_hat = float(fitted.coef[j])
        value = math.sqrt(max(c_hat, 0.0))
        row: dict[str, object] = {
            "seed": seed, "case": case, "term": j, "true": true, "value": value,
            "resolved": bool(resolved[j]),
            "bound": max(envelope_bound(basis[:, j], curve.var, fitted.nu), value),
            "ratio": np.sqrt(np.maximum(coefs[:, j], 0.0)) / value if value > 0 else None}
        for key, which in (("own", resolved), ("every", everything)):
            found = studentized_root(curve, j, coefs, which) if c_hat > 0 else None
            if found is None:
                row[key] = None
                continue
            t_star, root, _ = found
            row[key] = {"t_star": t_star,
                        "t_true": root(true * true) if true > 0 else math.nan,
                        "t_zero": root(c_hat * 1e-12), "t_top": root(c_hat * 2.0 ** 40)}
        out.append(row)
    return out


def _held(fitted: Fit, coefs: np.ndarray, curve: Curve, j: int, true: float,
          method: str, inner: np.ndarray | None = None) -> tuple[bool, bool]:
    """Whether term j's 68 % and 95 % intervals hold ``true``, resolved or not."""
    if fitted.coef[j] <= 0:
        return False, False          # no interval around a value (a term fitted at 0)
    value = float(np.sqrt(fitted.coef[j]))
    everything = np.ones(fitted.coef.size, dtype=bool) & (fitted.coef > 0)
    levels = (read_level(j, 0.68), read_level(j, 0.95)) if method == METHOD else (0.68, 0.95)
    (lo68, hi68), (lo95, hi95) = intervals(value, j, coefs, levels, method, curve, everything,
                                           inner)
    return bool(lo68 <= true <= hi68), bool(lo95 <= true <= hi95)


def table(result: dict[str, list[tuple[str, bool, bool]]]) -> None:
    """The coverage table of one method."""
    print(f"{'term':18} {'values':>7} {'68 % cover':>11} {'95 % cover':>11} "
          f"{'bounds':>7} {'bounds hold':>12}")
    for term, rows in result.items():
        values = [r for r in rows if r[0] not in ("bound", "absent")]
        bounds = [r for r in rows if r[0] == "bound"]
        absent = [r for r in rows if r[0] == "absent"]
        c68 = f"{100 * np.mean([r[1] for r in values]):.1f} %" if values else "-"
        c95 = f"{100 * np.mean([r[2] for r in values]):.1f} %" if values else "-"
        hold = f"{100 * np.mean([r[1] for r in bounds]):.1f} %" if bounds else "-"
        print(f"{term:18} {len(values):7d} {c68:>11} {c95:>11} {len(bounds):7d} {hold:>12}"
              + (f"   ({len(absent)} values of a term the truth lacks)" if absent else ""))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--records", type=int, default=200)
    parser.add_argument("--samples", type=int, default=1 << 15)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--integer-seeds", action="store_true",
                        help="seed record r with the integer SEED + r and its bootstrap with "
                             f"{INTEGER_BOOT} + SEED + r, as the ranges the levels were set "
                             "on were drawn (docs/error-budget.md section 5)")
    parser.add_argument("--interval", default=f"{METHOD},pivot",
                        help="the bootstrap intervals to compare, comma-separated "
                             "(calibrated, studentized, pivot, percentile; gyrovib's: "
                             f"{METHOD})")
    parser.add_argument("--cases", default=",".join(str(k) for k in range(len(CASES))),
                        help="which cases, by number (0–4: " + ", ".join(
                            name for name, _ in CASES) + ")")
    parser.add_argument("--sim-cap", type=int, default=SIM_CAP,
                        help="the longest record the bootstrap simulates whole: below "
                             "--samples it exercises the shortened bootstrap of long records")
    parser.add_argument("--save", metavar="FILE",
                        help="write, per record and term, the roots that decide at which "
                             "level its interval first holds the truth (a pickle), so that "
                             "any level's coverage can be computed afterwards")
    args = parser.parse_args()
    methods = tuple(args.interval.split(","))
    unknown = [m for m in methods if m not in METHODS]
    if unknown:
        parser.error(f"--interval: unknown {', '.join(unknown)} (one of {', '.join(METHODS)})")
    start = time.perf_counter()
    cases = tuple(int(k) for k in args.cases.split(","))
    saved: list[dict[str, object]] | None = [] if args.save else None
    result = run(args.records, args.samples, args.seed, methods, args.sim_cap, cases, saved,
                 args.integer_seeds)
    took = time.perf_counter() - start
    if args.save:
        with open(args.save, "wb") as out:
            pickle.dump(saved, out)
    short = (f", shortened bootstrap (whole records simulated up to {args.sim_cap} samples)"
             if args.sim_cap < args.samples else "")
    print(f"{args.records} records of {args.samples} samples at {TAU0} s "
          f"(range {args.seed}, records 0…{args.records - 1}){short}, {took:.0f} s")
    for meth in result:
        print(f"\n{meth} intervals" + (" (gyrovib's)" if meth == METHOD else ""))
        table(result[meth])
    print("binomial 1σ of a coverage over v values: √(p(1 − p)/v), "
          f"e.g. {100 * math.sqrt(0.68 * 0.32 / 40):.1f} points at 68 % over 40")


if __name__ == "__main__":
    main()
