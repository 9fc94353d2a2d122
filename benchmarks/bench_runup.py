"""Run-up test benchmark: 10 steps of 60 s at 1 kHz (docs/runup.md, docs/performance.md).

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_runup.py             # 10 × 60 s at 1000 Hz, 3 repeats

A synthetic run-up (tests/runup_sim.py: angular and linear vibration stepped up and
down, k2, vre, a drift and white noise; synthetic numbers) is written once as a .npy
(600 000 samples, 6 columns). Each measurement runs ``gyrovib runup`` on it in a fresh
process — the whole command as a user runs it: start-up, reading, the split, the
steps found, the fit and the table — and reports its wall-clock and CPU time. The
goal is under 5 s.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

from tests.runup_sim import simulate  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fs", type=float, default=1000.0)
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    data, steps = simulate(np.random.default_rng(1), {"k2": 0.002, "vre": 0.01},
                           fs=args.fs, seconds=args.seconds, gap=2.0)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "runup.npy")
        np.save(path, data)
        command = [sys.executable, "-m", "gyrovib", "runup", path, "--fs", str(args.fs),
                   "--rate-columns", "0,1,2", "--accel-columns", "3,4,5", "--estimate",
                   "k2,vre", "--format", "json"]
        print(f"{len(steps)} steps of {args.seconds:g} s at {args.fs:g} Hz: "
              f"{data.shape[0]} samples")
        for _ in range(args.repeats):
            wall, cpu = time.perf_counter(), os.times()
            done = subprocess.run(command, capture_output=True, text=True, check=False)
            end = os.times()
            wall = time.perf_counter() - wall
            used = (end.children_user - cpu.children_user) + (end.children_system
                                                              - cpu.children_system)
            status = "ok" if done.returncode == 0 else f"exit {done.returncode}"
            print(f"gyrovib runup: {wall:.2f} s wall, {used:.2f} s CPU ({status})")


if __name__ == "__main__":
    main()
