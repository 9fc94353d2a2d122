"""First run: ``gyrovib analyze`` (default table) on the bundled catalogues against
``python -c "import numpy, yaml, pydantic, rich.console, rich.table"`` (the
stack's own floor), as ratios measured in the same run.

The targets (docs/performance.md): at most 1.5 for the bundled coefficient-form
sensors, at most 1.8 for the whole bundled catalogue (the datasheet sensors add
their HiGHS programmes): the command should cost little more than importing the
libraries it is built on. Each
command runs ``--repeat`` times, interleaved so that a busy moment of the
machine hits both alike; the medians and the ratio of the medians are printed.

``--src SRC`` times gyrovib from that ``src`` directory instead of the installed
one (a worktree); ``--other SRC`` also times the same commands from another
source tree (e.g. an older commit unpacked with ``git archive``), run with the
same interpreter, so that before and after are measured in one run.

The table's cost per row is measured in-process on a catalogue of
``--sensors`` sensors (the bundled ones repeated under new ids) and the
bundled profiles.

    python benchmarks/bench_startup.py [--repeat 21] [--src src] [--other /tmp/old/src]
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

FLOOR = [sys.executable, "-c", "import numpy, yaml, pydantic, rich.console, rich.table"]
COMMAND = [sys.executable, "-m", "gyrovib", "analyze"]
#: The bundled sensors given by coefficients (eq. 1 or eq. 2), not by a datasheet.
COEFFICIENT_SENSORS = ("adxrs453", "generic-rate-mems", "generic-tactical-fog",
                       "generic-navigation-fog", "generic-navigation-rlg")
COEFFICIENTS = [*COMMAND, *(f"--sensor={s}" for s in COEFFICIENT_SENSORS)]


def timed(argv: list[str], env: dict[str, str]) -> tuple[float, float]:
    """Wall-clock and CPU (user + system) seconds of one run; output to a pipe."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(argv, env=env, capture_output=True, check=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def startup(repeat: int, other: str | None, src: str | None = None) -> None:
    # As installed by pip: bytecode written (and so compiled once, in the warm-up run).
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "COLUMNS", "PYTHONDONTWRITEBYTECODE")}
    own = {**env, "PYTHONPATH": os.path.abspath(src)} if src else env
    cases: dict[str, tuple[list[str], dict[str, str]]] = {
        "python -c 'import numpy, yaml, pydantic, rich'": (FLOOR, env),
        "gyrovib analyze (coefficient sensors) | cat": (COEFFICIENTS, own),
        "gyrovib analyze | cat": (COMMAND, own),
    }
    if other:
        cases[f"gyrovib analyze (coefficient sensors) ({other})"] = (
            COEFFICIENTS, {**env, "PYTHONPATH": other})
        cases[f"gyrovib analyze | cat  ({other})"] = (COMMAND, {**env, "PYTHONPATH": other})
    walls: dict[str, list[float]] = {name: [] for name in cases}
    cpus: dict[str, list[float]] = {name: [] for name in cases}
    for argv, e in cases.values():  # warm the file cache, write the bytecode
        timed(argv, e)
    for _ in range(repeat):
        for name, (argv, e) in cases.items():
            wall, cpu = timed(argv, e)
            walls[name].append(wall)
            cpus[name].append(cpu)
    first = next(iter(cases))
    floor_wall, floor_cpu = statistics.median(walls[first]), statistics.median(cpus[first])
    print(f"start-up, median of {repeat} interleaved runs (ratio to the first line)")
    for name in cases:
        wall, cpu = statistics.median(walls[name]), statistics.median(cpus[name])
        print(f"  {name:<52} wall {wall * 1000:6.1f} ms  ratio {wall / floor_wall:4.2f}   "
              f"cpu {cpu * 1000:6.1f} ms  ratio {cpu / floor_cpu:4.2f}")


def per_row(n_sensors: int) -> None:
    import yaml

    from gyrovib import api
    from gyrovib.catalog.loader import bundled_paths
    from gyrovib.render import analysis

    paths = {p.name: p for p in bundled_paths()}
    sensors_path = next(p for name, p in paths.items() if name.startswith("sensors"))
    profiles_path = next(p for name, p in paths.items() if name.startswith("profiles"))
    data = yaml.safe_load(sensors_path.read_text(encoding="utf-8"))
    base = data["sensors"]
    data["sensors"] = [{**base[k % len(base)], "id": f"{base[k % len(base)]['id']}-{k}"}
                       for k in range(n_sensors)]
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "many.gyrovib.yaml"
        path.write_text(yaml.safe_dump(data), encoding="utf-8")
        result = api.analyze(api.load([path, profiles_path]))
    rows = len(result.sensors) * len(result.profiles)
    best = float("inf")
    for _ in range(3):
        start = time.perf_counter()
        text = analysis.to_table(result)
        best = min(best, time.perf_counter() - start)
    print(f"table rendering: {rows} rows in {best * 1000:.1f} ms, "
          f"{best / rows * 1e6:.1f} µs per row ({len(text.splitlines())} lines)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=21)
    parser.add_argument("--sensors", type=int, default=2000)
    parser.add_argument("--src", metavar="SRC", help="time gyrovib from this src tree")
    parser.add_argument("--other", metavar="SRC", help="also time gyrovib from this src tree")
    parser.add_argument("--no-rows", action="store_true", help="skip the per-row measurement")
    args = parser.parse_args()
    if args.src:
        sys.path.insert(0, os.path.abspath(args.src))
    startup(args.repeat, args.other, args.src)
    if args.no_rows:
        return
    per_row(args.sensors)


if __name__ == "__main__":
    main()
