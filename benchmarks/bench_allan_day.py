"""A day-long log at 1 kHz on three axes: ``gyrovib allan`` within 60 s and 500 MB
(docs/performance.md, docs/error-budget.md).

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_allan_day.py                 # 24 h × 1 kHz × 3 axes, 1 GB
    python benchmarks/bench_allan_day.py --hours 2       # a quicker look

The log is synthetic (white rate noise of N = 0.1 deg/√h, flicker-free, a rate random
walk of K = 1 deg/h/√h and a constant bias, float32 rows of three axes, seeded), written
once as a .npy a block of rows at a time, by a process of its own (``--keep`` leaves it
for the next run). The command then runs in a fresh process, as a user runs it; the
wall-clock time and the peak resident memory of that process are printed: ``VmHWM``
read from /proc while it runs (``ru_maxrss`` of a child also counts the pages it shared
with this process before its exec), and ``ru_maxrss`` as a cross-check.
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


def _vm_hwm(pid: int) -> float:
    """The process's peak resident memory so far, MB (0 once it is gone)."""
    try:
        with open(f"/proc/{pid}/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return 0.0


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
        subprocess.run([sys.executable, "-c", f"import sys; sys.path.insert(0, {HERE!r}); "
                        f"import bench_allan_day as b; b.write_log({path!r}, {samples})"],
                       check=True)
        print(f"wrote {path} ({os.path.getsize(path) / 1e9:.2f} GB) in "
              f"{time.perf_counter() - t:.0f} s")
    command = [sys.executable, "-m", "gyrovib", "allan", path, "--fs", str(FS),
               "--format", "json"]
    if args.per_decade is not None:
        command += ["--per-decade", args.per_decade]
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    start = time.perf_counter()
    child = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
    hwm = 0.0
    while child.poll() is None:
        hwm = max(hwm, _vm_hwm(child.pid))
        time.sleep(0.05)
    stderr = child.stderr.read() if child.stderr is not None else ""
    wall = time.perf_counter() - start
    cpu = resource.getrusage(resource.RUSAGE_CHILDREN)
    maxrss = cpu.ru_maxrss / 1024.0
    grid = "octave grid" if args.per_decade is None else f"--per-decade {args.per_decade}"
    print(f"{samples} samples × 3 axes at {FS:g} Hz ({args.hours:g} h), {grid}: exit "
          f"{child.returncode}, wall {wall:.1f} s, CPU {cpu.ru_utime + cpu.ru_stime:.1f} s, "
          f"peak RSS {hwm:.0f} MB (VmHWM; ru_maxrss {maxrss:.0f} MB); load average "
          f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    if child.returncode != 0:
        print(stderr)
    if not args.keep:
        os.remove(path)


if __name__ == "__main__":
    main()
