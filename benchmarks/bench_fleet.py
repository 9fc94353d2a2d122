"""Fleet benchmark: ``gyrovib profile`` over 100 logs with ``--jobs`` (docs/performance.md).

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_fleet.py                    # 100 logs of 10 min at 250 Hz, --jobs 2
    python benchmarks/bench_fleet.py --logs 10 --jobs 1 2

THE DATA ARE SYNTHETIC, made here with a seeded numpy Generator: each log is
10 minutes at 250 Hz of angular rate on three axes (150,000 samples × 3, a
3.6 MB float64 .npy), band-limited Gaussian noise (white, 0.3–0.8 deg/s rms,
through a first-order roll-off near 80 Hz), a rotor tone near 40 Hz and its
second harmonic (frequency, amplitude and noise level drawn per log), and a
slowly varying carrier Ω_K3. No real flight is involved.

Each run is the command line itself, in a fresh process: ``gyrovib profile
LOG... --fs 250 --jobs N -o envelope.yaml``; the wall-clock time includes the
interpreter's and the workers' start-up. Reported with it: the 1-minute load
average before and after (the machine may be shared), the largest resident set
of the command and of any of its workers (``ru_maxrss`` of the reaped
children), with ``--jobs 1`` the command's CPU time (the work itself: on a
quiet machine ``--jobs N`` takes about it divided by N, plus the workers'
start-up), and whether every ``--jobs`` wrote the same bytes.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
FS = 250.0


def make_logs(folder: str, count: int, minutes: float, seed: int = 2026) -> list[str]:
    """``count`` synthetic .npy logs (see the module docstring)."""
    from scipy.signal import lfilter

    rng = np.random.default_rng(seed)
    n = int(minutes * 60 * FS)
    t = np.arange(n) / FS
    alpha = np.exp(-2 * np.pi * 80.0 / FS)  # one-pole roll-off near 80 Hz
    paths = []
    for k in range(count):
        sigma = rng.uniform(0.3, 0.8)
        white = rng.normal(0.0, sigma, (n, 3))
        # y[i] = (1 - α)·x[i] + α·y[i-1], scaled back to about σ rms
        rate = lfilter([1 - alpha], [1, -alpha], white, axis=0) * np.sqrt((1 + alpha)
                                                                          / (1 - alpha))
        f0 = rng.uniform(38.0, 42.0)
        amp = rng.uniform(0.2, 1.0)
        for order, share in ((1, 1.0), (2, 0.4)):
            rate += np.outer(np.sin(2 * np.pi * order * f0 * t + rng.uniform(0, 2 * np.pi)),
                             amp * share * np.array([0.5, 0.7, 1.0]))
        rate[:, 2] += rng.uniform(-5, 5) + 3.0 * np.sin(2 * np.pi * t / rng.uniform(60, 180))
        path = os.path.join(folder, f"log-{k:03d}.npy")
        np.save(path, rate)
        paths.append(path)
    return paths


def run(paths: list[str], jobs: int, out: str) -> tuple[float, bytes]:
    command = [sys.executable, "-m", "gyrovib", "profile", *paths, "--fs", str(FS),
               "--jobs", str(jobs), "-o", out]
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, check=False)
    elapsed = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(done.stderr.decode())
    with open(out, "rb") as fh:
        return elapsed, fh.read()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--logs", type=int, default=100)
    parser.add_argument("--minutes", type=float, default=10.0)
    parser.add_argument("--jobs", type=int, nargs="+", default=[2])
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        t0 = time.perf_counter()
        paths = make_logs(folder, args.logs, args.minutes)
        print(f"{args.logs} synthetic logs of {args.minutes:g} min at {FS:g} Hz written in "
              f"{time.perf_counter() - t0:.1f} s ({os.cpu_count()} CPUs)")
        outputs = set()
        for jobs in args.jobs:
            before = os.getloadavg()[0]
            used = resource.getrusage(resource.RUSAGE_CHILDREN)
            seconds, text = run(paths, jobs, os.path.join(folder, f"envelope-{jobs}.yaml"))
            after = os.getloadavg()[0]
            usage = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = usage.ru_utime + usage.ru_stime - used.ru_utime - used.ru_stime
            outputs.add(hashlib.sha256(text).hexdigest())
            # workers forked by the forkserver are its children, not the command's: their
            # CPU time is not reaped here, so it is shown for --jobs 1 only
            shown = f"{cpu:.1f} s CPU, " if jobs == 1 else ""
            print(f"--jobs {jobs}: {seconds:.1f} s wall, {shown}"
                  f"{seconds / args.logs:.2f} s per log; load average {before:.1f} before, "
                  f"{after:.1f} after; largest process so far {usage.ru_maxrss / 1024:.0f} MB")
        if len(args.jobs) > 1:
            print("same output for every --jobs:", len(outputs) == 1)


if __name__ == "__main__":
    main()
