"""Worst case over datasheet envelopes: 1,000 spec sensors × 8 profiles.

Run on demand (not part of the test suite):

    .venv/bin/python benchmarks/bench_envelope.py [--sensors 1000] [--seed 0]

Times :func:`gyrovib.core.envelope.worst_case` (the worst |Δ_V|, the attaining
polynomial and the per-term maxima for the RMS bound) in two catalogues:

* ``datasheet``: ranges from the values datasheets use (125…2000 deg/s),
  nonlinearity 0.01–0.5 %FS, fits and measures mixed, a third with an
  asymmetry spec, half with a VRE — sensors share envelopes where their
  (range, fit, measure, asymmetry·R/b) agree;
* ``distinct``: every sensor has its own range, so nothing is shared (the
  engine's worst case: one programme per sensor, profile and term).

The 8 profiles are Gaussian vibrations (σ 0.5–5 deg/s, exact multipliers of
docs/model.md section 4) at carrier rates 0–20 deg/s, two of them with odd moments
(a phase-locked pair, docs/model.md section 10). Reports the wall and CPU time
(best of ``--repeat``; on a shared machine the CPU time is the fairer figure)
and the number of unique programmes solved.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from gyrovib.core.envelope import term_functionals, worst_case

RANGES = np.array([125.0, 250.0, 300.0, 400.0, 450.0, 500.0, 1000.0, 2000.0])


def profiles(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    sigma = rng.uniform(0.5, 5.0, 8)
    omega = rng.uniform(0.0, 20.0, 8)
    omega[0] = 0.0
    # folded-normal mean minus |Ω| (docs/model.md section 4), halved: g_A
    z = omega / (sigma * math.sqrt(2.0))
    erf = np.array([math.erf(v) for v in z])
    g_a = 0.5 * (sigma * math.sqrt(2 / math.pi) * np.exp(-z**2) + omega * erf - omega)
    m3 = np.zeros(8)
    m5 = np.zeros(8)
    m3[[2, 5]] = -0.75 * sigma[[2, 5]] ** 3 * 0.3
    m5[[2, 5]] = 2.0 * sigma[[2, 5]] ** 5 * 0.3
    terms = term_functionals(g_a, sigma**2, m3, 3 * sigma**4, m5, omega)
    g2 = rng.uniform(0.0, 10.0, 8) * (rng.uniform(size=8) < 0.5)
    return terms, g2


def catalogue(rng: np.random.Generator, n: int, distinct: bool) -> dict[str, object]:
    r = rng.uniform(100.0, 2000.0, n) if distinct else rng.choice(RANGES, n)
    fit = rng.choice(["least-squares", "minimax", "endpoint"], n)
    measure = np.where((fit != "minimax") & (rng.uniform(size=n) < 0.2), "rms", "max")
    nl = rng.choice([0.01, 0.05, 0.1, 0.2, 0.5], n)
    b = nl / 100 * r
    asym = np.where(rng.uniform(size=n) < 1 / 3, rng.choice([1e-3, 5e-3, 2e-2], n), np.inf)
    vre = np.where(rng.uniform(size=n) < 0.5, rng.choice([1e-4, 4e-4, 1e-3], n), 0.0)
    return {"range_": r, "limit": b, "fit": list(fit), "measure": list(measure),
            "asymmetry": asym, "vre": vre}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sensors", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    from gyrovib.core import envelope_lp

    counted: list[int] = []
    inner = envelope_lp.support

    def counting(*a: np.ndarray) -> tuple[np.ndarray, ...]:
        counted.append(int(np.asarray(a[3]).shape[0]))
        return inner(*a)

    import gyrovib.core.envelope as env
    env.support = counting  # type: ignore[assignment]
    for kind in ("datasheet", "distinct"):
        rng = np.random.default_rng(args.seed)
        terms, g2 = profiles(rng)
        cat = catalogue(rng, args.sensors, kind == "distinct")
        best = cpu = math.inf
        for _ in range(args.repeat):
            counted.clear()
            t0, c0 = time.perf_counter(), time.process_time()
            wc = worst_case(terms, g2, **cat)  # type: ignore[arg-type]
            best = min(best, time.perf_counter() - t0)
            cpu = min(cpu, time.process_time() - c0)
        print(f"{kind:9s}: {args.sensors} sensors x {terms.shape[0]} profiles: wall {best:6.2f} s, "
              f"CPU {cpu:6.2f} s; {sum(counted)} unique programmes "
              f"({1e3 * cpu / max(sum(counted), 1):.1f} ms CPU each); "
              f"max gap {wc.gap.max():.1e}")


if __name__ == "__main__":
    main()
