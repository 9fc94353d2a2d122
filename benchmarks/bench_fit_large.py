"""`gyrovib fit` on a large rate table: wall time, CPU time and peak memory (docs/performance.md).

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_fit_large.py                  # 2,000,000 rows, one unit
    python benchmarks/bench_fit_large.py --rows 200000    # a quicker look
    python benchmarks/bench_fit_large.py --units 8 --rows 1500000   # 8 units (16 MiB)

The table: 2 M rows of ``rate,output`` (about 15.5 MB, under the
16 MiB a rate table may have), the rates drawn from nine levels in ±4 deg/s,
the output eq. (1) with stated coefficients plus noise, two decimals. It is
written once into a temporary directory; ``gyrovib fit TABLE`` then runs
``--repeat`` times in a fresh subprocess (``python -m gyrovib``, output to
/dev/null), and the best wall time is reported with that run's CPU time
(user + system, of the child) and the largest peak resident memory of the runs
(``ru_maxrss`` from ``os.wait4``: interpreter, libraries and data).

The CPU time says what the wall time would be on a quiet machine: on a shared
one the wall time grows with the other processes' load, the CPU time much
less. BLAS threads count towards the CPU time; the fit's matrix products are
small (65,536 × p blocks), so the two are close when the machine is quiet.
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
SRC = os.path.join(os.path.dirname(HERE), "src")
LEVELS = np.array([-4.0, -3.0, -2.0, -1.0, 0.0, 1.0, 2.0, 3.0, 4.0])


def write_table(path: str, rows: int, units: int, seed: int = 1) -> int:
    """The table (see the module docstring); returns its size in bytes."""
    rng = np.random.default_rng(seed)
    w = LEVELS[rng.integers(0, LEVELS.size, rows)]
    u = 0.3 + 2.5 * (w + 0.0075 * np.abs(w) + 2e-3 * w**2 - 4e-3 * w**3)
    u += rng.normal(0.0, 0.05, rows)
    with open(path, "w", encoding="utf-8") as handle:
        if units == 1:
            handle.write("rate,output\n")
            handle.writelines(f"{a:g},{b:.2f}\n" for a, b in zip(w, u, strict=True))
        else:
            who = rng.integers(0, units, rows)
            handle.write("unit,rate,output\n")
            handle.writelines(f"u{k},{a:g},{b:.2f}\n" for k, a, b in zip(who, w, u,
                                                                       strict=True))
    return os.path.getsize(path)


def run_once(table: str, src: str = SRC) -> tuple[float, float, float]:
    """Wall seconds, CPU seconds (user + system) and peak RSS (MB) of one ``gyrovib fit``
    of the gyrovib sources in ``src``."""
    env = dict(os.environ, PYTHONPATH=src)
    with open(os.devnull, "wb") as null:
        start = time.perf_counter()
        child = subprocess.Popen([sys.executable, "-m", "gyrovib", "fit", table],
                                 stdout=null, stderr=subprocess.PIPE, env=env)
        _, status, usage = os.wait4(child.pid, 0)
        wall = time.perf_counter() - start
    if status != 0:
        assert child.stderr is not None
        raise SystemExit(f"gyrovib fit failed: {child.stderr.read().decode()}")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=2_000_000)
    parser.add_argument("--units", type=int, default=1)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--src", default=SRC, help="the gyrovib sources to run (another "
                        "checkout's src/, to compare); default this checkout's")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        table = os.path.join(tmp, "large.csv")
        size = write_table(table, args.rows, args.units)
        runs = [run_once(table, args.src) for _ in range(args.repeat)]
    wall, cpu, _ = min(runs)
    peak = max(r[2] for r in runs)
    print(f"gyrovib fit: {args.rows:,} rows, {args.units} unit(s), {size / 1e6:.1f} MB")
    print(f"  wall {wall:.2f} s (best of {args.repeat}), CPU {cpu:.2f} s, "
          f"peak RSS {peak:.0f} MB")
    print("  loadavg " + " ".join(f"{v:.1f}" for v in os.getloadavg()))


if __name__ == "__main__":
    main()
