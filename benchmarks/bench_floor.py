"""``gyrovib analyze`` start-up against its floor (benchmarks/floor.py): a minimal
program of the same stack and shape (click, PyYAML's CSafeLoader, a dozen pydantic
models validating the bundled catalogue files, numpy, one rich table).

Targets (docs/performance.md, "Start-up"): at most 1.3× the
floor for the bundled coefficient-form sensors, at most 1.5× for the whole
bundled catalogue (the datasheet sensors add their envelope programmes). Each
pair (gyrovib, floor) is given the same sensors and runs ``--repeat`` times,
interleaved, so that a busy moment of the shared machine hits both alike; the
medians of wall-clock and CPU (user + system) time and their ratios are printed.
CPU time is the steadier figure on a loaded machine.

    python benchmarks/bench_floor.py [--repeat 21] [--src src]

``--src SRC`` times gyrovib from that ``src`` directory instead of the installed one.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
FLOOR = [sys.executable, os.path.join(HERE, "floor.py")]
ANALYZE = [sys.executable, "-m", "gyrovib", "analyze"]
#: The bundled sensors given by coefficients (eq. 1 or eq. 2), not by a datasheet.
COEFFICIENT_SENSORS = ("adxrs453", "generic-rate-mems", "generic-tactical-fog",
                       "generic-navigation-fog", "generic-navigation-rlg")
ONLY_COEFFICIENTS = [f"--sensor={s}" for s in COEFFICIENT_SENSORS]
#: (name, gyrovib's arguments, the floor's arguments, target ratio)
PAIRS = (
    ("coefficient sensors", ONLY_COEFFICIENTS, ONLY_COEFFICIENTS, 1.3),
    ("whole bundled catalogue", [], [], 1.5),
)


def timed(argv: list[str], env: dict[str, str]) -> tuple[float, float]:
    """Wall-clock and CPU (user + system) seconds of one run; output to a pipe."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(argv, env=env, capture_output=True, check=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=21)
    parser.add_argument("--src", help="time gyrovib from this src directory")
    args = parser.parse_args()
    # As installed by pip: bytecode written (and so compiled once, in the warm-up run).
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "COLUMNS", "PYTHONDONTWRITEBYTECODE")}
    own = {**env, "PYTHONPATH": os.path.abspath(args.src)} if args.src else env
    cases: dict[str, tuple[list[str], dict[str, str]]] = {}
    for name, mine, floor, _ in PAIRS:
        cases[f"gyrovib analyze ({name})"] = ([*ANALYZE, *mine], own)
        cases[f"floor ({name})"] = ([*FLOOR, *floor], env)
    walls: dict[str, list[float]] = {name: [] for name in cases}
    cpus: dict[str, list[float]] = {name: [] for name in cases}
    for argv, e in cases.values():  # warm the file cache, write the bytecode
        timed(argv, e)
    for _ in range(args.repeat):
        for name, (argv, e) in cases.items():
            wall, cpu = timed(argv, e)
            walls[name].append(wall)
            cpus[name].append(cpu)
    print(f"start-up against the floor, median of {args.repeat} interleaved runs")
    print(f"{'command':<48} {'wall ms':>8} {'cpu ms':>8}")
    for name in cases:
        print(f"{name:<48} {statistics.median(walls[name]) * 1e3:8.0f} "
              f"{statistics.median(cpus[name]) * 1e3:8.0f}")
    print(f"\n{'ratio to the floor':<32} {'wall':>6} {'cpu':>6} {'target':>7}")
    for name, _, _, target in PAIRS:
        mine, floor = f"gyrovib analyze ({name})", f"floor ({name})"
        wall = statistics.median(walls[mine]) / statistics.median(walls[floor])
        cpu = statistics.median(cpus[mine]) / statistics.median(cpus[floor])
        verdict = "met" if max(wall, cpu) <= target else "over"
        print(f"{name:<32} {wall:6.2f} {cpu:6.2f} {target:7.1f}  {verdict}")


if __name__ == "__main__":
    main()
