"""Peak memory of ``gyrovib profile`` on a large recording, against the array's size.

Run on demand (not part of the test suite), one size at a time on a quiet machine::

    python benchmarks/bench_recording_memory.py                  # 4.8 M rows × 6 (230 MB)
    python benchmarks/bench_recording_memory.py --rows 28800000  # 1.38 GB
    python benchmarks/bench_recording_memory.py --csv-rows 2000000  # a CSV as well
    python benchmarks/bench_recording_memory.py --rows 0 --ulog-rows 2000000  # a ULog

It writes a float64 recording of ``--rows`` rows × 6 columns (rate X, Y, Z in
deg/s: Gaussian noise, a 37 Hz tone and a slow carrier on Z; acceleration
X, Y, Z in g with gravity on Z) as a ``.npy`` in a temporary directory (a
block at a time, so the writer itself stays small), runs
``gyrovib profile FILE --fs 8000 --accel-columns 3,4,5`` on it in a
subprocess, and reports that subprocess's peak resident memory
(``resource.getrusage(RUSAGE_CHILDREN).ru_maxrss`` read by a fresh wrapper
process, so one measurement does not see another's) and its wall-clock time,
beside the array's size in bytes. With ``--csv-rows`` it does the same for a
CSV of that many rows with a time column, and with ``--ulog-rows`` for a PX4
ULog: the public test log's ``sensor_combined`` repeated to that many rows
and written by pyulog (slow: about 10,000 rows a second). Besides the ratio
to the array, each line gives the ratio of what the run adds to a process
that only imports gyrovib and scipy.signal (the floor, printed first): at
small sizes the floor dominates. The temporary files are deleted.

The figures go into docs/performance.md.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

FS = 8000.0
WRAPPER = """
import json, resource, subprocess, sys, time
t0 = time.perf_counter()
done = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
seconds = time.perf_counter() - t0
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024
print(json.dumps({"rc": done.returncode, "seconds": seconds, "max_rss": peak,
                  "stderr": done.stderr[-2000:]}))
"""


def _block(rng: np.random.Generator, start: int, rows: int) -> np.ndarray:
    t = (start + np.arange(rows)) / FS
    out = rng.normal(0.0, 0.7, (rows, 6))
    out[:, 2] += 1.5 * np.sin(2 * np.pi * 37.0 * t) + 3.0 + 2.0 * np.sin(2 * np.pi * 0.05 * t)
    out[:, 5] += 1.0
    return out


def write_npy(path: str, rows: int, seed: int = 0) -> int:
    """A rows × 6 float64 .npy written a block at a time; its array's size in bytes."""
    rng = np.random.default_rng(seed)
    array = np.lib.format.open_memmap(path, mode="w+", dtype=np.float64, shape=(rows, 6))
    step = 1 << 20
    for lo in range(0, rows, step):
        hi = min(rows, lo + step)
        array[lo:hi] = _block(rng, lo, hi - lo)
        array.flush()
    del array
    return rows * 6 * 8


def write_csv(path: str, rows: int, seed: int = 0) -> int:
    """The same signal as a CSV with a time column; the float64 arrays' size in bytes."""
    rng = np.random.default_rng(seed)
    step = 1 << 18
    with open(path, "w") as fh:
        fh.write("t,wx,wy,wz,ax,ay,az\n")
        for lo in range(0, rows, step):
            hi = min(rows, lo + step)
            block = np.column_stack([np.arange(lo, hi) / FS, _block(rng, lo, hi - lo)])
            np.savetxt(fh, block, delimiter=",", fmt="%.17g")
    return rows * 6 * 8


def write_ulog(path: str, rows: int) -> int:
    """The test log's sensor_combined repeated to ``rows`` rows (timestamps running on),
    written by pyulog; the float64 arrays' size in bytes (rate and acceleration)."""
    from pyulog import ULog

    log = ULog(os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                            "tests", "data", "px4-sample.ulg"), ["sensor_combined"])
    data = log.data_list[0]
    stamps = data.data["timestamp"].astype(np.int64)
    step = int(np.median(np.diff(stamps)))
    span = int(stamps[-1] - stamps[0]) + step
    reps = -(-rows // stamps.size)
    grown = {k: np.tile(v, reps)[:rows] for k, v in data.data.items()}
    grown["timestamp"] = np.concatenate([stamps + r * span for r in range(reps)])[:rows] \
        .astype(data.data["timestamp"].dtype)
    data.data = grown
    log.write_ulog(path)
    return rows * 6 * 8


def measure(*args: str) -> dict[str, float]:
    """Peak RSS and time of ``gyrovib profile ARGS`` in a fresh process tree."""
    cmd = [sys.executable, "-c", WRAPPER, sys.executable, "-m", "gyrovib", "profile", *args]
    done = subprocess.run(cmd, capture_output=True, text=True, check=True)
    result: dict[str, float] = json.loads(done.stdout)
    if result["rc"] != 0:
        raise SystemExit(f"gyrovib profile failed:\n{result['stderr']}")
    return result


def _report(label: str, size: int, result: dict[str, float],
            floor: float) -> dict[str, object]:
    row = {"what": label, "array_bytes": size, "max_rss": result["max_rss"],
           "ratio": result["max_rss"] / size,
           "above_floor": (result["max_rss"] - floor) / size,
           "seconds": round(result["seconds"], 1)}
    print(f"{label}: array {size / 2**20:.0f} MiB, peak RSS {result['max_rss'] / 2**20:.0f} MiB "
          f"= {row['ratio']:.2f} × the array ({row['above_floor']:.2f} × above the floor), "
          f"{result['seconds']:.1f} s", flush=True)
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rows", type=int, default=4_800_000, help="rows of the .npy")
    parser.add_argument("--csv-rows", type=int, default=0, help="rows of a CSV (0: none)")
    parser.add_argument("--ulog-rows", type=int, default=0, help="rows of a ULog (0: none)")
    parser.add_argument("--json", action="store_true", help="print the rows as JSON too")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        floor = subprocess.run(
            [sys.executable, "-c", WRAPPER, sys.executable, "-c",
             "import gyrovib.cli.main, scipy.signal, numpy"], capture_output=True, text=True)
        base = json.loads(floor.stdout)["max_rss"]
        print(f"interpreter + gyrovib + scipy.signal imported: {base / 2**20:.0f} MiB")
        out = os.path.join(tmp, "out.yaml")
        if args.rows:
            npy = os.path.join(tmp, "big.npy")
            size = write_npy(npy, args.rows)
            rows.append(_report(f".npy {args.rows} × 6", size,
                                measure(npy, "--fs", str(FS), "--accel-columns", "3,4,5",
                                        "-o", out), base))
            os.remove(npy)
        if args.csv_rows:
            csv = os.path.join(tmp, "big.csv")
            size = write_csv(csv, args.csv_rows)
            rows.append(_report(f"CSV {args.csv_rows} × 6 (+ t)", size,
                                measure(csv, "--accel-columns", "ax,ay,az", "-o", out), base))
            os.remove(csv)
        if args.ulog_rows:
            ulg = os.path.join(tmp, "big.ulg")
            size = write_ulog(ulg, args.ulog_rows)
            rows.append(_report(f"ULog {args.ulog_rows} × 6", size,
                                measure(ulg, "--crossover", "2", "-o", out), base))
            os.remove(ulg)
    if args.json:
        print(json.dumps({"import_rss": base, "rows": rows}))


if __name__ == "__main__":
    main()
