"""Memory of ``select --format json`` on a big catalogue, and what ``bounds`` loads.

Run on demand (it is not part of the test suite; about two minutes and 4 GB
of memory at the default size)::

    python benchmarks/bench_select.py                  # 100,000 sensors x 8 profiles
    python benchmarks/bench_select.py --sensors 20000  # smaller
    python benchmarks/bench_select.py --before DIR     # also DIR/src, in the same run

The catalogue is bench_scale.py's (same generator and eight profiles), its
sensors split over files of 25,000 (a catalogue file is at most 16 MiB). Three
measurements, each in a fresh subprocess with its peak resident memory
(``ru_maxrss``):

* ``gyrovib select CAT --budget 0.01 --format json -o /dev/null`` end to end
  (target: under 1.5 GB peak);
* the same in phases, in one child: import, load (YAML + validation),
  ``api.select``, ``render.select.to_json``, writing, each with its time, the
  resident memory after it and the peak so far, to show where memory goes;
* ``gyrovib bounds`` on the catalogue against ``bounds`` on its profiles
  alone: ``bounds`` uses no sensor, so the difference is sensors loaded and
  validated for nothing.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import bench_scale  # the catalogue generator (after the sys.path entry)

PYTHON = sys.executable
CHILD_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
TARGET_MB = 1500.0

PHASES = """
import os, resource, sys, time
def rss():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20
def peak():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
marks = []
def mark(name, t0):
    marks.append((name, time.perf_counter() - t0, rss(), peak()))
t = time.perf_counter()
from gyrovib import api
from gyrovib.cli.output import write_output
from gyrovib.render import select as render
mark("import", t); t = time.perf_counter()
catalog = api.load(sys.argv[1:])
mark("load: YAML + validation", t); t = time.perf_counter()
result = api.select(catalog, budget=0.01)
mark("api.select", t); t = time.perf_counter()
if hasattr(render, "to_json_chunks"):  # streamed: rendered while written
    write_output(render.to_json_chunks(result), os.devnull)
    mark("render.select.to_json_chunks + write, streamed", t)
else:
    text = render.to_json(result)
    mark(f"render.select.to_json ({len(text) / 2**20:.0f} MB of text)", t)
    t = time.perf_counter()
    write_output(text, os.devnull)
    mark("write", t)
for name, seconds, now, top in marks:
    print(f"{name}\\t{seconds:.2f}\\t{now:.0f}\\t{top:.0f}")
"""


def run_fresh(argv: list[str], env: dict[str, str] | None = None) -> tuple[float, float, str]:
    """Wall time (s), peak RSS (MB) and stdout of ``argv`` (exit 0 or 1), run from a
    fresh intermediate process so that its RUSAGE_CHILDREN sees this child only."""
    code = ("import json, subprocess, time, resource, os;"
            f"argv = {argv!r}; t = time.perf_counter();"
            "p = subprocess.run(argv, capture_output=True, env=os.environ);"
            "e = time.perf_counter() - t;"
            "assert p.returncode in (0, 1), p.stderr.decode();"
            "print(json.dumps([e, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024,"
            " p.stdout.decode()]))")
    proc = subprocess.run([PYTHON, "-c", code], capture_output=True, env=env or CHILD_ENV,
                          check=True)
    elapsed, peak, out = json.loads(proc.stdout)
    return float(elapsed), float(peak), str(out)


HEADER = "gyrovib: 1\nunits:\n  rate: deg/s\n"
#: Sensors per file: a catalogue file may not exceed 16 MiB (README, "Catalogue files").
PER_FILE = 25_000


def write_sensors(work: Path, n: int, seed: int) -> list[Path]:
    """bench_scale.py's sensors, ``PER_FILE`` to a file."""
    rng = random.Random(seed + n)
    paths = []
    for start in range(0, n, PER_FILE):
        path = work / f"sensors-{start // PER_FILE:02d}.yaml"
        with open(path, "w", encoding="utf-8") as f:
            f.write(HEADER + "sensors:\n")
            for i in range(start, min(n, start + PER_FILE)):
                f.write(bench_scale.sensor_yaml(i, rng))
        paths.append(path)
    return paths


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sensors", type=int, default=100_000)
    parser.add_argument("--seed", type=int, default=6)
    parser.add_argument("--before", metavar="DIR",
                        help="also run the gyrovib in DIR/src, in the same run")
    args = parser.parse_args()

    work = Path(tempfile.mkdtemp(prefix="gyrovib-select-"))
    profiles_only = work / "profiles.yaml"
    profiles_only.write_text(HEADER + bench_scale.PROFILES, encoding="utf-8")
    files = [profiles_only, *write_sensors(work, args.sensors, args.seed)]
    size_mb = sum(f.stat().st_size for f in files) / 2**20
    gyrovib = [PYTHON, "-m", "gyrovib"]
    subprocess.run([PYTHON, "-m", "compileall", "-q", str(Path(__file__).parents[1] / "src")],
                   check=True, env=CHILD_ENV, stdout=subprocess.DEVNULL)

    print(f"Python {sys.version.split()[0]}, nproc {os.cpu_count()}; catalogue: "
          f"{args.sensors:,} sensors x 8 profiles, {size_mb:.1f} MB of YAML\n")

    catalogue = [str(f) for f in files]
    versions: dict[str, dict[str, str]] = {"after": CHILD_ENV}
    if args.before:
        src = str(Path(args.before).resolve() / "src")
        subprocess.run([PYTHON, "-m", "compileall", "-q", src], check=True,
                       env=CHILD_ENV, stdout=subprocess.DEVNULL)
        versions = {"before": {**CHILD_ENV, "PYTHONPATH": src}, **versions}
    print("| command | version | time | peak RSS | target | |")
    print("|---|---|---:|---:|---:|---|")
    phases: dict[str, str] = {}
    for version, env in versions.items():
        t, peak, _ = run_fresh([*gyrovib, "select", *catalogue, "--budget", "0.01",
                                "--format", "json", "-o", os.devnull], env)
        ok = "met" if peak < TARGET_MB else "not met"
        print(f"| select --format json, {args.sensors:,} sensors | {version} | "
              f"{t * 1000:.0f} ms | {peak:.0f} MB | < {TARGET_MB:.0f} MB | {ok} |")
        for label, paths in (("bounds, whole catalogue", catalogue),
                             ("bounds, its profiles alone", [str(profiles_only)])):
            t, peak, _ = run_fresh([*gyrovib, "bounds", *paths, "--budget", "0.01",
                                    "--format", "json", "-o", os.devnull], env)
            print(f"| {label} | {version} | {t * 1000:.0f} ms | {peak:.0f} MB | | |")
        phases[version] = run_fresh([PYTHON, "-c", PHASES, *catalogue], env)[2]

    for version, out in phases.items():
        print(f"\n| phase of select --format json ({version}) | time | RSS after | peak so far |")
        print("|---|---:|---:|---:|")
        for line in out.strip().splitlines():
            name, seconds, now, top = line.split("\t")
            print(f"| {name} | {float(seconds) * 1000:.0f} ms | {now} MB | {top} MB |")
    print(f"\n(files in {work})")


if __name__ == "__main__":
    main()
