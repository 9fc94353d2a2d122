"""Fleet benchmark: ``gyrovib profile`` over 100 logs with ``--jobs`` (docs/performance.md).

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_fleet.py                  # 100 logs of 10 min at 250 Hz,
                                                      # --jobs 1 and 2, three pairs
    python benchmarks/bench_fleet.py --logs 10 --jobs 1 2 --repeat 5
    python benchmarks/bench_fleet.py --folder /tmp/logs   # write the logs once, keep them

THE DATA ARE SYNTHETIC, made here with a seeded numpy Generator: each log is
10 minutes at 250 Hz of angular rate on three axes (150,000 samples × 3, a
3.6 MB float64 .npy), band-limited Gaussian noise (white, 0.3–0.8 deg/s rms,
through a first-order roll-off near 80 Hz), a rotor tone near 40 Hz and its
second harmonic (frequency, amplitude and noise level drawn per log), and a
slowly varying carrier Ω_K3. No real flight is involved.

Each run is the command line itself, in a fresh process: ``gyrovib profile
LOG... --fs 250 --jobs N -o envelope.yaml``; the wall-clock time includes the
interpreter's and the workers' start-up. The ``--jobs`` values run one after
the other, ``--repeat`` times (interleaved, so a change of the machine's load
hits every value alike); the minimum of each is what counts on a shared machine.
Reported per run: wall-clock and CPU time (user + system, of the command itself
and of its workers: they are its children, reaped before it exits), CPU / wall,
the 1-minute load average before and after, the largest resident set of any
process so far; then whether every run wrote the same bytes, and per ``--jobs``
the minimum wall time and its ratio to the first value's (the targets: ``--jobs
2`` at most 0.6 × the wall time of ``--jobs 1``, and ``--jobs 1``'s CPU time at
most 1.1 × its wall time).

On a machine shared with other work the wall times say little (with the
kernel's autogroup scheduling, every session gets its share of the cores
whatever its number of processes), so the wall time on idle cores is also
inferred from the CPU times: the command's own (its start, the envelope: serial,
the command waits while its workers fit) plus the workers' divided by ``--jobs``.
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


#: The command line, run through a launcher that writes, as it exits, the CPU time of
#: the command itself and of its reaped children (the --jobs workers) to $BENCH_CPU.
LAUNCHER = "\n".join([
    "import atexit, os, resource, sys",
    "def cpu():",
    "    own = resource.getrusage(resource.RUSAGE_SELF)",
    "    kids = resource.getrusage(resource.RUSAGE_CHILDREN)",
    "    with open(os.environ['BENCH_CPU'], 'w') as fh:",
    "        fh.write(f'{own.ru_utime + own.ru_stime} {kids.ru_utime + kids.ru_stime}')",
    "atexit.register(cpu)",
    "sys.argv = ['gyrovib', *sys.argv[1:]]",
    "from gyrovib.cli import main",
    "main()",
])


def run(paths: list[str], jobs: int, out: str) -> tuple[float, float, float, bytes]:
    """One run of the command line: its wall-clock time, the CPU time of the command
    itself and of its workers, and the bytes it wrote."""
    command = [sys.executable, "-c", LAUNCHER, "profile", *paths, "--fs", str(FS),
               "--jobs", str(jobs), "-o", out]
    report = out + ".cpu"
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, check=False,
                          env={**os.environ, "BENCH_CPU": report})
    elapsed = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(done.stderr.decode())
    with open(report) as fh:
        own, workers = (float(x) for x in fh.read().split())
    with open(out, "rb") as fh:
        return elapsed, own, workers, fh.read()


def logs_in(folder: str, count: int, minutes: float) -> list[str]:
    """The logs of ``folder`` if it holds these (by name and size), else written there."""
    n = int(minutes * 60 * FS)
    paths = [os.path.join(folder, f"log-{k:03d}.npy") for k in range(count)]
    if all(os.path.exists(p) and os.path.getsize(p) == 128 + 24 * n for p in paths):
        print(f"{count} synthetic logs of {minutes:g} min at {FS:g} Hz found in {folder}")
        return paths
    t0 = time.perf_counter()
    paths = make_logs(folder, count, minutes)
    print(f"{count} synthetic logs of {minutes:g} min at {FS:g} Hz written in "
          f"{time.perf_counter() - t0:.1f} s")
    return paths


Times = dict[int, list[tuple[float, float, float]]]


def measure(paths: list[str], jobs_values: list[int], repeat: int, folder: str) -> Times:
    """``repeat`` rounds of every ``--jobs``: per run (wall, command CPU, workers' CPU)."""
    times: Times = {j: [] for j in jobs_values}
    outputs = set()
    for round_ in range(repeat):
        for jobs in jobs_values:
            before = os.getloadavg()[0]
            seconds, own, workers, text = run(paths, jobs,
                                              os.path.join(folder, f"envelope-{jobs}.yaml"))
            after = os.getloadavg()[0]
            peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
            times[jobs].append((seconds, own, workers))
            outputs.add(hashlib.sha256(text).hexdigest())
            cpu = own + workers
            print(f"run {round_ + 1}, --jobs {jobs}: {seconds:6.2f} s wall, {cpu:6.2f} s CPU "
                  f"(command {own:.2f} s, workers {workers:.2f} s; CPU/wall "
                  f"{cpu / seconds:.2f}); load average {before:.1f} before, {after:.1f} "
                  f"after; largest process so far {peak:.0f} MB", flush=True)
    print("same output for every run:", len(outputs) == 1)
    return times


def summary(times: Times, jobs_values: list[int]) -> None:
    """The minima, their ratios to the first ``--jobs``, and the wall time the CPU times
    imply on idle cores: the command's own CPU (its start, the envelope: serial) plus
    the workers' shared out over ``--jobs`` cores."""
    first = jobs_values[0]
    wall_first = min(w for w, _, _ in times[first])
    idle_first = min(own + workers / first for _, own, workers in times[first])
    for jobs in jobs_values:
        fastest = min(times[jobs])
        wall = fastest[0]
        cpu = min(own + workers for _, own, workers in times[jobs])
        idle = min(own + workers / jobs for _, own, workers in times[jobs])
        print(f"--jobs {jobs}: min wall {wall:.2f} s ({wall / wall_first:.2f} x --jobs "
              f"{first}); CPU/wall of that run {(fastest[1] + fastest[2]) / wall:.2f}; "
              f"min CPU {cpu:.2f} s; on idle cores (from the CPU times) "
              f"{idle:.2f} s ({idle / idle_first:.2f} x --jobs {first})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--logs", type=int, default=100)
    parser.add_argument("--minutes", type=float, default=10.0)
    parser.add_argument("--jobs", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--folder", help="where the logs are kept (default: a temporary "
                        "folder, removed afterwards)")
    args = parser.parse_args()
    print(f"{os.cpu_count()} CPUs; load average {os.getloadavg()[0]:.1f}")
    with tempfile.TemporaryDirectory() as scratch:
        folder = args.folder or scratch
        os.makedirs(folder, exist_ok=True)
        paths = logs_in(folder, args.logs, args.minutes)
        times = measure(paths, args.jobs, args.repeat, scratch)
    summary(times, args.jobs)


if __name__ == "__main__":
    main()
