"""Allan deviation benchmark: a 10-hour 100 Hz static log (docs/performance.md).

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_allan.py               # 10 h at 100 Hz, three axes
    python benchmarks/bench_allan.py --hours 1     # a quicker look

A synthetic static log (white rate noise, a rate random walk and a bias on X, Y,
Z: 3.6 M samples an axis) is written once as a .npy; each measurement runs in a
fresh subprocess and reports wall-clock and CPU time, the peak traced allocation
(tracemalloc, which numpy reports to) and the peak resident memory:

* **kernel**: ``core.allan.oadev`` of one axis already in memory, on the default grid;
* **allan**: ``gyrovib.api.noise.allan`` reading the .npy and computing every axis
  (the curve, N, B and K), as ``gyrovib allan LOG.npy --fs 100`` does;
* **allantools** (when installed): its ``oadev`` of one axis on the same τ, for
  comparison.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import textwrap

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.join(os.path.dirname(HERE), "src")

_PRELUDE = """
import json, resource, sys, time, tracemalloc
sys.path.insert(0, {src!r})
import numpy as np
{setup}
if {trace!r}:
    tracemalloc.start()
t0, c0 = time.perf_counter(), time.process_time()
"""
_EPILOGUE = """
elapsed, cpu = time.perf_counter() - t0, time.process_time() - c0
peak = tracemalloc.get_traced_memory()[1]
rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
print(json.dumps({"seconds": elapsed, "cpu": cpu, "traced_peak": peak, "max_rss": rss}))
"""

CASES = {
    "kernel": ("y = np.load({path!r})[:, 0].copy()\nfrom gyrovib.core.allan import oadev",
               "tau, adev = oadev(y, 0.01)"),
    "allan": ("from gyrovib.api.recordings.reading import read_recording\n"
              "from gyrovib.api.noise import allan",
              "r = allan(read_recording({path!r}, fs=100.0))"),
    "allantools": ("y = np.load({path!r})[:, 0].copy()\nimport allantools\n"
                   "from gyrovib.core.allan import tau_grid\nm = tau_grid(y.size)",
                   "allantools.oadev(y, rate=100.0, data_type='freq', taus=m * 0.01)"),
}


def _run(case: str, path: str, trace: bool) -> dict[str, float] | None:
    setup, body = CASES[case]
    code = (_PRELUDE.format(src=SRC, trace=trace, setup=setup.format(path=path))
            + body.format(path=path) + "\n" + _EPILOGUE)
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                          text=True, check=False)
    if done.returncode != 0:
        if "No module named 'allantools'" in done.stderr:
            return None
        raise SystemExit(done.stderr)
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> None:
    import numpy as np

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--hours", type=float, default=10.0)
    args = parser.parse_args()
    n = int(args.hours * 3600 * 100)
    g = np.random.default_rng(2024)
    rate = (g.standard_normal((n, 3)) * (0.2 / 60) * 10.0           # N = 0.2 deg/√h
            + np.cumsum(g.standard_normal((n, 3)), axis=0) * (1 / 216_000) * 0.1  # K = 1
            + 0.05)                                                   # a bias, deg/s
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "static.npy")
        np.save(path, rate)
        size = rate[:, 0].nbytes
        del rate
        print(f"{n} samples an axis ({args.hours:g} h at 100 Hz); one axis is "
              f"{size / 1e6:.1f} MB")
        for case in CASES:
            timing = _run(case, path, trace=False)
            if timing is None:
                print(f"{case:>11}: not installed")
                continue
            memory = _run(case, path, trace=True)
            assert memory is not None
            print(f"{case:>11}: {timing['seconds']:.2f} s wall, {timing['cpu']:.2f} s CPU; "
                  f"traced peak {memory['traced_peak'] / size:.2f}× one axis, max RSS "
                  f"{memory['max_rss'] / 1e6:.0f} MB")


if __name__ == "__main__":
    main()
