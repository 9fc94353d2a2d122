"""Flight-log readers: time and memory of reading a long DataFlash and ULog FIFO log.

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_readers.py                  # 10 min logs
    python benchmarks/bench_readers.py --minutes 1      # a quicker look

Writes, with the tests' writers (tests/logwriters.py, synthetic data), an ArduPilot
DataFlash log of ``IMU`` messages at 1 kHz (one instance, rate and acceleration) and
a PX4 ULog with ``sensor_gyro_fifo`` and ``sensor_accel_fifo`` at 8 kHz, 32 samples a
message; then, each in a fresh subprocess, ``read_recording`` of each, reporting the
wall-clock time, the peak resident memory (``VmHWM``: the interpreter and the
libraries included) and its growth over the libraries' import, and the size of the
float64 arrays the recording holds (rate and acceleration, n × 6 × 8 bytes).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

_CHILD = """
import json, sys, time
sys.path.insert(0, {src!r})
from gyrovib.api.recordings.reading import read_recording
import pymavlink.DFReader, pyulog, scipy.signal  # the libraries, before the baseline

def hwm():  # this process's own peak (ru_maxrss keeps the parent's across fork)
    with open("/proc/self/status") as fh:
        return next(int(ln.split()[1]) for ln in fh if ln.startswith("VmHWM")) / 1024

base = hwm()
start = time.perf_counter()
rec = read_recording({path!r}, topic={topic!r})
wall = time.perf_counter() - start
rss = hwm()
print(json.dumps({{"samples": rec.samples, "wall_s": wall, "maxrss_mb": rss,
                  "growth_mb": rss - base, "arrays_mb": rec.samples * 6 * 8 / 2**20}}))
"""


def _write(directory: Path, minutes: float) -> dict[str, tuple[str, str]]:
    from tests.logwriters import ACCEL_SCALE, GYRO_SCALE, dataflash_imu, motion, ulog_fifo

    fs = 1000.0
    n = int(minutes * 60 * fs)
    w, g = motion(n, fs, 1, 180.0, 3.0, 1.0)
    t_us = np.round(np.arange(n) * 1e6 / fs)
    bin_path = dataflash_imu(directory / "imu.bin", t_us,
                             [(w * np.pi / 180).astype(np.float32)],
                             [(g * 9.80665).astype(np.float32)])
    fs = 8000.0
    n = int(minutes * 60 * fs) // 32 * 32
    w, g = motion(n, fs, 2, 450.0, 5.0, 2.0)
    gyro = np.round(w * np.pi / 180 / GYRO_SCALE).astype(np.int16)
    accel = np.round(g * 9.80665 / ACCEL_SCALE).astype(np.int16)
    ulg = ulog_fifo(directory / "fifo.ulg", 125.0, 32, [gyro],
                    [accel], GYRO_SCALE, ACCEL_SCALE)
    return {"dataflash IMU 1 kHz": (str(bin_path), "IMU"),
            "ULog FIFO 8 kHz": (str(ulg), "sensor_gyro_fifo")}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--minutes", type=float, default=10.0)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as directory:
        logs = _write(Path(directory), args.minutes)
        for name, (path, topic) in logs.items():
            code = _CHILD.format(src=os.path.join(ROOT, "src"), path=path, topic=topic)
            done = subprocess.run([sys.executable, "-c", code], capture_output=True,
                                  text=True, check=True)
            figures = json.loads(done.stdout)
            figures["file_mb"] = os.path.getsize(path) / 2**20
            print(f"{name}: " + ", ".join(f"{k} {v:.4g}" for k, v in figures.items()))


if __name__ == "__main__":
    main()
