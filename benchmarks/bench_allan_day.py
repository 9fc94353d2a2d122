"""A day-long log at 1 kHz on three axes: ``gyrovib allan`` within 60 s and 500 MB
(docs/performance.md, docs/error-budget.md).

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_allan_day.py                 # 24 h × 1 kHz × 3 axes, 1 GB
    python benchmarks/bench_allan_day.py --hours 2       # a quicker look

The log is synthetic (white rate noise of N = 0.1 deg/√h, flicker-free, a rate random
walk of K = 1 deg/h/√h and a constant bias, float32 rows of three axes, seeded), written
once as a .npy a block of rows at a time (``--keep`` leaves it for the next run). The
command then runs in a fresh process, as a user runs it; the wall-clock time and the
peak resident memory of that process (``ru_maxrss`` of the child) are printed.
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
FS = 1000.0
N_DEG_SQRT_S, K_DEG_S_SQRT_S = 0.1 / 60.0, 1.0 / 216_000.0


def write_log(path: str, samples: int, seed: int = 1) -> None:
    """The synthetic log, a block of rows at a time."""
    out = np.lib.format.open_memmap(path, mode="w+", dtype=np.float32, shape=(samples, 3))
    rng = np.random.default_rng(seed)
    walk = np.zeros(3)
    block = 1 << 20
    for lo in range(0, samples, block):
        hi = min(samples, lo + block)
        white = rng.standard_normal((hi - lo, 3)) * (N_DEG_SQRT_S * math.sqrt(FS))
        steps = rng.standard_normal((hi - lo, 3)) * (K_DEG_S_SQRT_S / math.sqrt(FS))
        rw = walk + np.cumsum(steps, axis=0)
        walk = rw[-1]
        out[lo:hi] = (0.02 + white + rw).astype(np.float32)
    out.flush()
    del out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--hours", type=float, default=24.0)
    parser.add_argument("--dir", default=tempfile.gettempdir())
    parser.add_argument("--keep", action="store_true")
    parser.add_argument("--per-decade", default=None,
                        help="the τ grid (default: the command's, the octave grid)")
    args = parser.parse_args()
    samples = int(args.hours * 3600 * FS)
    path = os.path.join(args.dir, f"gyrovib-day-{samples}.npy")
    if not os.path.exists(path):
        t = time.perf_counter()
        write_log(path, samples)
        print(f"wrote {path} ({os.path.getsize(path) / 1e9:.2f} GB) in "
              f"{time.perf_counter() - t:.0f} s")
    command = [sys.executable, "-m", "gyrovib", "allan", path, "--fs", str(FS),
               "--format", "json"]
    if args.per_decade is not None:
        command += ["--per-decade", args.per_decade]
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    start = time.perf_counter()
    done = subprocess.run(command, env=env, capture_output=True, text=True, check=False)
    wall = time.perf_counter() - start
    peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0
    cpu = resource.getrusage(resource.RUSAGE_CHILDREN)
    grid = "octave grid" if args.per_decade is None else f"--per-decade {args.per_decade}"
    print(f"{samples} samples × 3 axes at {FS:g} Hz ({args.hours:g} h), {grid}: exit {done.returncode}, wall {wall:.1f} s, CPU "
          f"{cpu.ru_utime + cpu.ru_stime:.1f} s, peak RSS {peak_mb:.0f} MB")
    if done.returncode != 0:
        print(done.stderr)
    if not args.keep:
        os.remove(path)


if __name__ == "__main__":
    main()
