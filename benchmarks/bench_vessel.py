"""The vessel path of docs/vessel.md, timed: each command of a SYNTHETIC scenario
(tools/make_vessel.py: a 4 h static log, 10 min of rough sea with an engine at 30 Hz and
its harmonics, blade-pass and slams, a 20-segment 4 h voyage, a triad, four candidates),
from the commands with no hand edit. The goal is at most 10 s of wall time each on the
project's 2-core machine, and progress on a terminal past 2 s.

Run on demand (not part of the test suite)::

    python benchmarks/bench_vessel.py              # every step
    python benchmarks/bench_vessel.py --only mission

Each step is a fresh ``python -m gyrovib`` subprocess; the table gives the wall time,
the CPU time (user + system, from ``os.wait4``: on a shared machine the wall time
also counts the waits for a core), the exit status and the first line of standard
error (the answer line of ``mission`` and ``select``).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))

import make_vessel  # noqa: E402

FILES = ("candidates.gyrovib.yaml", "rough-sea.gyrovib.yaml", "voyage.gyrovib.yaml")
STEPS: list[tuple[str, list[str]]] = [
    ("allan", ["allan", "static.npz", "--fs", "10", "--rate-columns", "-,-,gz"]),
    ("profile", ["profile", "rough-sea.npz", "--fs", "800", "--rate-columns", "gx,gy,gz",
                 "-o", "rough-sea.gyrovib.yaml"]),
    ("validate", ["validate", "rough-sea.gyrovib.yaml"]),
    ("analyze", ["analyze", "candidates.gyrovib.yaml", "rough-sea.gyrovib.yaml"]),
    ("analyze --recording", ["analyze", "candidates.gyrovib.yaml", "--recording",
                             "rough-sea.npz", "--fs", "800", "--rate-columns", "gx,gy,gz"]),
    ("mission", ["mission", *FILES, "--mission", "voyage", "--angle-budget", "1deg",
                 "--coverage", "2", "--plot", "theta.png"]),
    ("select --mission", ["select", *FILES, "--mission", "voyage", "--angle-budget", "1deg",
                          "--coverage", "2"]),
    ("report", ["report", *FILES, "--budget", "0.01", "--mission", "voyage",
                "--angle-budget", "1deg",
                "--coverage", "2", "-o", "report.html"]),
]


def run(args: list[str], cwd: Path, timeout: float) -> tuple[float, int, str]:
    """Wall seconds, exit status and first stderr line of one command (its CPU time is
    read by the caller from ``os.times()``' children)."""
    start = time.monotonic()
    proc = subprocess.Popen([sys.executable, "-m", "gyrovib", *args], cwd=cwd,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        _, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        _, err = proc.communicate()
    wall = time.monotonic() - start
    first = next((line for line in err.splitlines() if line.strip()), "")
    return wall, proc.returncode, first[:110]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default=None, help="only the steps whose name has this")
    parser.add_argument("--timeout", type=float, default=1200.0)
    parser.add_argument("--keep", type=Path, default=None, help="write the scenario here")
    a = parser.parse_args()
    directory = a.keep or Path(tempfile.mkdtemp(prefix="gyrovib-vessel-"))
    make_vessel.write(directory)
    print(f"scenario in {directory}; load average {os.getloadavg()[0]:.1f} on "
          f"{os.cpu_count()} cores")
    print(f"{'step':<22} {'wall s':>8} {'cpu s':>8} {'exit':>5}  first line of stderr")
    for name, args in STEPS:
        if a.only and a.only not in name and name != "profile":
            continue
        before = os.times()
        wall, code, first = run(args, directory, a.timeout)
        after = os.times()
        cpu = (after.children_user - before.children_user
               + after.children_system - before.children_system)
        print(f"{name:<22} {wall:8.1f} {cpu:8.1f} {code:5d}  {first}", flush=True)


if __name__ == "__main__":
    main()
