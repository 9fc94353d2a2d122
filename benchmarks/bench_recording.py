"""Recording benchmark: reading + analysing a long recording (docs/performance.md).

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_recording.py                 # 10 min, 8 kHz, 6 channels
    python benchmarks/bench_recording.py --minutes 1     # a quicker look

The recording: 10 minutes at 8 kHz of rate and acceleration on
three axes each, 28.8 M samples (a 230 MB float64 array), written once as a
.npy (and ``--csv-minutes`` of it as a CSV with a time column). Each
measurement runs in a fresh subprocess and reports its wall-clock time and
its peak traced allocation (tracemalloc, which numpy reports to) together
with its peak resident memory (``ru_maxrss``, which includes the interpreter
and the imported libraries):

* **reference**: ``numpy.load`` of the array and one ``sosfiltfilt`` pass of
  the same 4th-order Butterworth over every column;
* **analyze**: ``gyrovib.api`` reading the .npy and running
  ``analyze_recording`` (split, Δ_V,rec of the bundled sensors, the fit and
  its closed form over the carrier histogram);
* **csv read**: reading the CSV alone (streamed into preallocated arrays).
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
if {trace!r}:
    tracemalloc.start()
t0 = time.perf_counter()
"""
_EPILOGUE = """
elapsed = time.perf_counter() - t0
peak = tracemalloc.get_traced_memory()[1]
rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
print(json.dumps({{"seconds": elapsed, "traced_peak": peak, "max_rss": rss}}))
"""

REFERENCE = """
import numpy as np
from scipy.signal import butter, sosfiltfilt
a = np.load({npy!r})
sos = butter(4, 5.0, fs={fs!r}, output="sos")
out = sosfiltfilt(sos, a, axis=0)
"""

ANALYZE = """
from gyrovib.api import load
from gyrovib.api.recordings.analysis import analyze_recording
from gyrovib.api.recordings.reading import read_recording
rec = read_recording({npy!r}, fs={fs!r}, rate_columns=(0, 1, 2), accel_columns=(3, 4, 5))
result = analyze_recording(rec, load())
"""

CSV = """
from gyrovib.api.recordings.reading import read_recording
rec = read_recording({csv!r}, rate_columns=("gx", "gy", "gz"),
                     accel_columns=("ax", "ay", "az"))
"""


def _once(body: str, trace: bool, **values: object) -> dict[str, float]:
    code = (_PRELUDE + textwrap.dedent(body) + _EPILOGUE).format(src=SRC, trace=trace,
                                                                  **values)
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True,
                         text=True)
    result: dict[str, float] = json.loads(out.stdout.strip().splitlines()[-1])
    return result


def _run(body: str, **values: object) -> dict[str, float]:
    """Time and resident peak of an untraced run; traced peak of a second, traced run
    (tracemalloc slows allocation-heavy code, so its run is not timed)."""
    plain = _once(body, False, **values)
    plain["traced_peak"] = _once(body, True, **values)["traced_peak"]
    return plain


def _make(path: str, n: int, fs: float) -> None:
    import numpy as np

    rng = np.random.default_rng(0)
    t = np.arange(n) / fs
    a = np.lib.format.open_memmap(path, mode="w+", dtype=float, shape=(n, 6))
    block = 1 << 20
    for lo in range(0, n, block):
        tt = t[lo:lo + block]
        m = tt.size
        noise = rng.normal(0.0, 0.7, (m, 6))
        noise[:, :3] += 1.5 * np.sin(2 * np.pi * 37.0 * tt)[:, None]
        noise[:, 2] += 3.0 + 2.0 * np.sin(2 * np.pi * 0.05 * tt)
        noise[:, 5] += 1.0
        a[lo:lo + m] = noise
    a.flush()
    del a


def _write_csv(npy: str, path: str, n: int, fs: float) -> None:
    import numpy as np

    a = np.load(npy, mmap_mode="r")
    with open(path, "w") as fh:
        fh.write("t,gx,gy,gz,ax,ay,az\n")
        for lo in range(0, n, 100_000):
            block = np.column_stack([np.arange(lo, min(lo + 100_000, n)) / fs,
                                     a[lo:min(lo + 100_000, n)]])
            np.savetxt(fh, block, delimiter=",", fmt="%.9g")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--minutes", type=float, default=10.0)
    parser.add_argument("--fs", type=float, default=8000.0)
    parser.add_argument("--csv-minutes", type=float, default=1.0)
    args = parser.parse_args()
    n = int(args.minutes * 60 * args.fs)
    with tempfile.TemporaryDirectory() as tmp:
        npy = os.path.join(tmp, "rec.npy")
        _make(npy, n, args.fs)
        size = n * 6 * 8
        print(f"recording: {n} samples x 6 channels = {n * 6 / 1e6:.1f} M samples, "
              f"array {size / 2**20:.0f} MiB")
        rows = [("numpy.load + sosfiltfilt", _run(REFERENCE, npy=npy, fs=args.fs)),
                ("read .npy + analyze_recording", _run(ANALYZE, npy=npy, fs=args.fs))]
        if args.csv_minutes > 0:
            m = int(args.csv_minutes * 60 * args.fs)
            csv = os.path.join(tmp, "rec.csv")
            _write_csv(npy, csv, m, args.fs)
            rows.append((f"read CSV ({m * 6 / 1e6:.2f} M samples, "
                         f"{os.path.getsize(csv) / 2**20:.0f} MiB)", _run(CSV, csv=csv)))
    print(f"{'what':<44} {'time s':>8} {'traced peak':>12} {'x array':>8} {'max RSS':>9}")
    for name, r in rows:
        print(f"{name:<44} {r['seconds']:>8.2f} {r['traced_peak'] / 2**20:>9.0f} MiB "
              f"{r['traced_peak'] / size:>8.2f} {r['max_rss'] / 2**20:>5.0f} MiB")


if __name__ == "__main__":
    main()
