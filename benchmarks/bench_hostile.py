"""Hostile-input cost benchmark: each case within 10 s and 400 MB, or refused.

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_hostile.py                    # this checkout's src/
    python benchmarks/bench_hostile.py --src OTHER/src    # another tree (before/after)
    python benchmarks/bench_hostile.py --only worst       # cases whose name has "worst"

Each case is a fresh ``python -m gyrovib`` subprocess under ``timeout`` (SIGTERM
at ``--timeout`` seconds, then SIGKILL 5 s later) and ``/usr/bin/time -v``; the
table gives the wall time, the peak resident memory, the exit status (124/137:
killed by the timeout) and the first line of standard error (a refusal's
FILE:LINE:COL). The catalogues are generated into a temporary directory:

* harmonic orders 1 and N (N = 64 over a sweep inside the swing, 1,000, 10^5,
  10^9, 10^20);
* ``phase: worst`` on 2, 4, 8, 16, 64 orders (``select``), 4 orders over a
  5-rate and the default 401-rate sweep;
* 2, 3, 4 and 5 locked groups of orders 1 and 2;
* one tone (a = 100) on a tiny random part (σ = 1e-3), the default 401-rate sweep;
* two locked groups with a tone and a random PSD (σ3 = 2.2): ``analyze``,
  ``select``, the default sweep and ``report``; with a narrow random part
  (σ = 0.01) and with none (refused); one group, a tone and σ = 1e-3;
* the bundled catalogue swept at 2,000 and 20,000 rates;
* 3,000 datasheet (spec-form) sensors with all-different ranges × 2 profiles,
  ``select`` and ``report``.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

SENSOR = """gyrovib: 1
units: {rate: deg/s}
sensors:
  - id: s
    range: 500
    coefficients: {A1: 1.0e-3, k2: 2.0e-4, k3: 1.0e-5, k4: -3.0e-7, k5: 1.0e-8}
"""
HEAD = """gyrovib: 1
units: {rate: deg/s}
profiles:
  - id: p
    rate: [0, 0, 0.5]
"""


def one_group(orders: list[tuple[int, str]], amplitude: float = 1.0) -> str:
    lines = [HEAD, "    harmonics:\n      fundamental: 20\n      orders:\n"]
    lines += [f"        - {{order: {n}, amplitude: [0, 0, {amplitude}], phase: {phase}}}\n"
              for n, phase in orders]
    return "".join(lines)


def groups(count: int) -> str:
    lines = [HEAD, "    harmonics:\n"]
    for g in range(count):
        lines += [f"      - fundamental: {10 * g + 13}\n", "        orders:\n",
                  "          - {order: 1, amplitude: [0, 0, 0.5], phase: [0, 0, 0]}\n",
                  "          - {order: 2, amplitude: [0, 0, 0.3], phase: [0, 0, 30]}\n"]
    return "".join(lines)


def mixture(count: int, tones: list[float], random: str | None) -> str:
    """``count`` locked groups (orders 1 and 2), independent ``tones`` (x3 amplitudes)
    and a ``random`` part (YAML of its mapping, or none)."""
    lines = [groups(count)]
    if tones:
        lines.append("    harmonic:\n")
        lines += [f"      - {{frequency: {50 + 10 * i}, amplitude: [0, 0, {a}]}}\n"
                  for i, a in enumerate(tones)]
    if random is not None:
        lines.append(f"    random: {random}\n")
    return "".join(lines)


PSD = "{psd: {x3: [[20, 2.5e-3], [2000, 2.5e-3]]}}"  # σ3 = √(2.5e-3·1980) = 2.22 deg/s


TONE_ON_TINY_RANDOM = HEAD + """    harmonic:
      - {frequency: 50, amplitude: [0, 0, 100]}
    random: {rms: [0, 0, 0.001]}
"""


def spec_sensors(count: int) -> str:
    """``count`` datasheet sensors, every range different (100 + i·0.37 deg/s)."""
    lines = ["gyrovib: 1\nunits: {rate: deg/s}\nsensors:\n"]
    for i in range(count):
        lines.append(f"  - id: spec{i:05d}\n    specs:\n      range: {100 + 0.37 * i:.2f}\n"
                     "      nonlinearity: {value: 0.1, unit: \"%FS\", fit: least-squares, "
                     "measure: max, of: range}\n")
    return "".join(lines)


TWO_PROFILES = """gyrovib: 1
units: {rate: deg/s}
profiles:
  - id: tone
    rate: [0, 0, 0.5]
    harmonic:
      - {frequency: 95, amplitude: [1.2, 0.8, 2.5]}
  - id: random
    rate: [0, 0, 2]
    random: {rms: [0.5, 0.5, 1.0]}
"""


def cases(tmp: Path) -> list[tuple[str, list[str]]]:
    def write(name: str, text: str) -> str:
        path = tmp / name
        path.write_text(text, encoding="utf-8")
        return str(path)

    s = write("s.yaml", SENSOR)
    out: list[tuple[str, list[str]]] = []
    p = write("o64.yaml", one_group([(1, "[0, 0, 0]"), (64, "[0, 0, 0]")]))
    out.append(("orders 1,64 sweep -3:3:401", ["sweep", s, p, "--rate-range", "-3:3:401",
                                               "--format", "csv"]))
    for n, label in ((1000, "1,000"), (100_000, "10^5"), (10**9, "10^9"), (10**20, "10^20")):
        p = write(f"o{n}.yaml", one_group([(1, "[0, 0, 0]"), (n, "[0, 0, 0]")]))
        out.append((f"orders 1,{label} analyze", ["analyze", s, p]))
    for count in (2, 4, 8, 16, 64):
        p = write(f"w{count}.yaml", one_group([(n, "worst") for n in range(1, count + 1)],
                                             0.1 if count > 8 else 1.0))
        out.append((f"phase: worst x{count} select", ["select", s, p, "--budget", "1"]))
    p = str(tmp / "w4.yaml")
    out.append(("phase: worst x4 sweep 5 rates", ["sweep", s, p, "--rate-range", "-3:3:5",
                                                  "--format", "csv"]))
    out.append(("phase: worst x4 sweep 401 rates", ["sweep", s, p, "--format", "csv"]))
    for count in (2, 3, 4, 5):
        p = write(f"g{count}.yaml", groups(count))
        out.append((f"{count} locked groups sweep -2:2:401",
                    ["sweep", s, p, "--rate-range", "-2:2:401", "--format", "csv"]))
    p = write("tr.yaml", TONE_ON_TINY_RANDOM)
    out.append(("tone a=100 + random 1e-3 sweep 401", ["sweep", s, p, "--format", "csv"]))
    p = write("g2tr.yaml", mixture(2, [1.0], PSD))
    for command in (["analyze"], ["select", "--budget", "1"], ["sweep", "--format", "csv"],
                    ["report", "--budget", "1", "-o", str(tmp / "g2tr.html")]):
        out.append((f"2 groups + tone + PSD {command[0]}", [command[0], s, p, *command[1:]]))
    p = write("g2trs.yaml", mixture(2, [1.0], "{rms: [0, 0, 0.01]}"))
    out.append(("2 groups + tone + rms 0.01 sweep", ["sweep", s, p, "--format", "csv"]))
    p = write("g2t.yaml", mixture(2, [1.0], None))
    out.append(("2 groups + tone, no random, sweep", ["sweep", s, p, "--format", "csv"]))
    p = write("g1trs.yaml", mixture(1, [1.0], "{rms: [0, 0, 0.001]}"))
    out.append(("1 group + tone + rms 1e-3 sweep", ["sweep", s, p, "--format", "csv"]))
    out.append(("bundled sweep 2,000 rates", ["sweep", "--rate-range", "-200:200:2000",
                                              "--format", "csv"]))
    out.append(("bundled sweep 20,000 rates", ["sweep", "--rate-range", "-200:200:20000",
                                               "--format", "csv"]))
    big = write("spec3000.yaml", spec_sensors(3000))
    two = write("two.yaml", TWO_PROFILES)
    out.append(("3,000 spec sensors x 2 select", ["select", big, two, "--budget", "1",
                                                  "--format", "csv"]))
    out.append(("3,000 spec sensors x 2 report", ["report", big, two, "--budget", "1",
                                                  "-o", str(tmp / "r.html")]))
    return out


def measure(src: str, args: list[str], timeout: float) -> tuple[float, float, int, str]:
    """(wall s, peak RSS MB, exit status, first stderr line of gyrovib)."""
    env = dict(os.environ, PYTHONPATH=src)
    command = ["/usr/bin/time", "-v", "timeout", "-k", "5", str(timeout),
               sys.executable, "-m", "gyrovib", *args]
    done = subprocess.run(command, env=env, capture_output=True, text=True, check=False)
    err = done.stderr
    wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", err)
    seconds = 0.0
    if wall:
        h = float(wall.group(1) or 0)
        seconds = h * 3600 + float(wall.group(2)) * 60 + float(wall.group(3))
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", err)
    first = next((line for line in err.splitlines()
                  if line and not line.startswith(("\t", "Command ")) and "note:" not in line),
                 "")
    return seconds, (int(rss.group(1)) / 1024 if rss else float("nan")), done.returncode, first


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--src", default=str(Path(__file__).resolve().parent.parent / "src"))
    parser.add_argument("--timeout", type=float, default=60.0)
    parser.add_argument("--only", default="", help="run the cases whose name contains this")
    opts = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        print(f"{'case':40} {'wall s':>8} {'RSS MB':>8} {'exit':>5}  message")
        for name, args in cases(Path(tmp)):
            if opts.only and opts.only not in name:
                continue
            wall, rss, code, first = measure(opts.src, args, opts.timeout)
            first = first.replace(tmp + "/", "")
            print(f"{name:40} {wall:8.2f} {rss:8.0f} {code:5d}  {first[:110]}", flush=True)


if __name__ == "__main__":
    main()
