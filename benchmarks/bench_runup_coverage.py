"""Coverage of the run-up test's intervals on simulated records (docs/runup.md).

Run on demand (it is not part of the test suite; tests/test_runup.py runs 30 records)::

    python benchmarks/bench_runup_coverage.py                  # 200 records
    python benchmarks/bench_runup_coverage.py --records 50 --seed 7

Each record is a fresh simulated run-up (tests/runup_sim.py; synthetic numbers, a seed
the tests do not use): ten 20 s steps at 200 Hz, angular and linear vibration stepped
up and down and apart, with transitions of 2 s between steps that the step finder must
cut out; A1 = 0, k2 = 0.002 (deg/s)^-1, vre = 0.01 deg/s/g², a drift of 1e-4 deg/s/s
and white noise of 0.01 deg/s/√Hz. ``gyrovib.api.runup`` finds the steps and estimates
A1, k2 and vre with the drift. Reported per term: the share of records whose 95 %
interval (value ± 1.96 u) holds the simulated value (the goal: at least 93 %), the
share reported "found" (for the zero A1, the false findings), and the mean u.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.join(ROOT, "src"))

from tests.runup_sim import simulate  # noqa: E402

from gyrovib.api.recordings import read_recording  # noqa: E402
from gyrovib.api.runup import runup  # noqa: E402

TRUTH = {"A1": 0.0, "k2": 0.002, "vre": 0.01}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", type=int, default=200)
    parser.add_argument("--seed", type=int, default=90210)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    covered = dict.fromkeys(TRUTH, 0)
    found = dict.fromkeys(TRUTH, 0)
    sigma = dict.fromkeys(TRUTH, 0.0)
    drift_estimated = 0
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "runup.npy")
        for _ in range(args.records):
            data, _ = simulate(rng, TRUTH, gap=2.0)
            np.save(path, data)
            rec = read_recording(path, fs=200.0, rate_columns=(0, 1, 2),
                                 accel_columns=(3, 4, 5))
            result = runup(rec, estimate=list(TRUTH))
            drift_estimated += bool(np.isfinite(result.drift))
            for e in result.estimates:
                covered[e.name] += abs(e.value - TRUTH[e.name]) <= 1.96 * e.uncertainty
                found[e.name] += e.status == "found"
                sigma[e.name] += e.uncertainty / args.records
    n = args.records
    print(f"{n} simulated run-ups (seed {args.seed}), {time.perf_counter() - start:.1f} s; "
          f"drift estimated in {drift_estimated}")
    print(f"{'term':5} {'truth':>8} {'95 % covers':>12} {'found':>7} {'mean u':>10}")
    for name, value in TRUTH.items():
        print(f"{name:5} {value:8.4g} {100 * covered[name] / n:11.1f}% "
              f"{100 * found[name] / n:6.1f}% {sigma[name]:10.3g}")


if __name__ == "__main__":
    main()
