"""Scale benchmark of ``gyrovib analyze`` against what Python cannot avoid.

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_scale.py            # 100, 1,000 and 10,000 sensors
    python benchmarks/bench_scale.py --quick    # 100 and 1,000 only

Every measurement is the wall-clock time of a fresh subprocess, best of
``--repeat`` runs, so start-up and imports are included exactly as a user
sees them. The comparisons and their targets:

* ``analyze`` of a generated catalogue, JSON to a file, against the *floor*:
  a ``python -c`` that parses the same YAML with ``yaml.CSafeLoader`` and
  writes the same JSON document with ``json.dumps`` (the document is read from
  gyrovib's own output first; the time that takes is measured inside the child
  and subtracted). Target: ratio <= 2.0 at 10,000 sensors.
* first-run latency, ``gyrovib analyze --format json -o /dev/null`` on the
  bundled catalogues, against ``python -c "import numpy, yaml"`` (<= 2.0);
* ``gyrovib --help`` against ``python -c "import click"`` (<= 1.5);
* the peak resident memory of the 10,000-sensor run (< 500 MB);

gyrovib's bytecode is compiled first and children run without
PYTHONDONTWRITEBYTECODE, as after ``pip install`` (numpy and yaml have theirs).
* time per sensor at each size (is it linear?).

The generated catalogues are deterministic (``--seed``): sensors with random
but realistic eq. (2) coefficients, a quarter of them in the eq. (1)
``output_coefficients`` form, a third with a ``response`` table (2-pole
roll-off at one of a dozen bandwidths, as datasheets quote them), and eight
profiles: one tone, several tones, flat PSD, shaped PSD with a mount, RMS,
sine-on-random, a mounted tone in a fast turn (which saturates the sensors of
smallest range, so some results carry a warning) and tones plus RMS.
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import os
import platform
import random
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PYTHON = sys.executable
TARGETS = {"scale": 2.0, "first": 2.0, "help": 1.5, "memory_mb": 500.0}

# ------------------------------------------------------------------ catalogues

PROFILES = """\
profiles:
  - id: single-tone
    rate: [0, 0, 0.5]
    harmonic:
      - frequency: 95
        amplitude: [1.2, 0.8, 2.5]
  - id: engine-harmonics
    rate: [0, 0, 2]
    harmonic:
      - {frequency: 60, amplitude: [0.6, 0.5, 1.8], phase: [0, 30, 0]}
      - {frequency: 120, amplitude: [0.4, 0.3, 1.0], phase: [90, 0, 0]}
      - {frequency: 240, amplitude: [0.2, 0.2, 0.5], phase: [0, 180, 45]}
  - id: flat-random
    random:
      psd:
        x1: [[20, 1.2e-3], [2000, 1.2e-3]]
        x2: [[20, 1.2e-3], [2000, 1.2e-3]]
        x3: [[20, 2.5e-3], [2000, 2.5e-3]]
      coherence: [0.5, 0.2]
  - id: shaped-random-mounted
    rate: [0, 0, 20]
    random:
      psd:
        x1: [[20, 4.0e-4], [100, 2.0e-3], [500, 2.0e-3], [2000, 1.25e-4]]
        x2: [[20, 4.0e-4], [100, 2.0e-3], [500, 2.0e-3], [2000, 1.25e-4]]
        x3: [[20, 8.0e-4], [100, 4.0e-3], [500, 4.0e-3], [2000, 2.5e-4]]
    mount: [[10, 1.04], [30, 1.6], [50, 3.5], [70, 1.05], [100, 0.38], [200, 0.11],
            [500, 0.032], [2000, 0.0075]]
  - id: rms-random
    rate: [0, 0, -5]
    random:
      rms: [1.0, 1.0, 1.5]
      coherence: [0.3, -0.2]
  - id: sine-on-random
    rate: [0, 0, 1]
    harmonic:
      - {frequency: 400, amplitude: [0.3, 0.3, 1.5]}
    random:
      psd:
        x3: [[20, 1.0e-3], [2000, 1.0e-3]]
  - id: mounted-tone-manoeuvre
    rate: [0, 0, 90]
    harmonic:
      - {frequency: 180, amplitude: [2.0, 2.0, 6.0], phase: [10, 0, 0]}
    mount: [[20, 1.0], [100, 1.8], [200, 0.5], [1000, 0.05]]
  - id: tones-and-rms
    rate: [0, 0, 3]
    harmonic:
      - {frequency: 25, amplitude: [0.5, 0.2, 1.0]}
      - {frequency: 75, amplitude: [0.1, 0.4, 0.6]}
    random:
      rms: [0.2, 0.2, 0.4]
"""

BANDWIDTHS = (40, 50, 75, 80, 100, 140, 200, 250, 400, 500, 1000, 2000)


def _g(x: float) -> str:
    return f"{x:.4g}"


def _response(fc: float) -> str:
    points = [(0.5, 0.970), (1.0, 0.707), (2.0, 0.243), (4.0, 0.0624), (10.0, 0.01)]
    return "[" + ", ".join(f"[{_g(fc * r)}, {g}]" for r, g in points) + "]"


def sensor_yaml(i: int, rng: random.Random) -> str:
    """One sensor entry, coefficients derived from a nonlinearity figure like the real ones."""
    fs = rng.choice((75, 100, 125, 250, 300, 400, 450, 490, 500, 1000, 2000))
    nl = 10 ** rng.uniform(-5, -2.5)
    sign = lambda: rng.choice((-1.0, 1.0))  # noqa: E731
    coeffs = {
        "k0": sign() * 10 ** rng.uniform(-5, -1),
        "A1": sign() * 10 ** rng.uniform(-6, -3),
        "k2": sign() * 2 * nl / fs,
        "k3": sign() * 4 * nl / fs**2,
        "k4": sign() * 2 * nl / fs**3 * rng.choice((0.0, 1.0)),
        "k5": sign() * 3.06 * nl / fs**4 * rng.choice((0.0, 1.0)),
        "m1": sign() * 10 ** rng.uniform(-4, -2),
        "m2": sign() * 10 ** rng.uniform(-4, -2),
        "m31": sign() * nl / fs,
        "m32": sign() * nl / fs,
    }
    lines = [f"  - id: gen-{i:05d}",
             f"    name: Generated sensor {i} ({'MEMS' if fs <= 500 else 'FOG'})",
             f"    vendor: Vendor {i % 37}",
             f"    range: {fs}"]
    if i % 4 == 3:
        k1 = rng.uniform(5.0, 30.0)
        lines += ["    output_coefficients:", "      unit: mV", f"      K1: {_g(k1)}"]
        for name, value in coeffs.items():
            key = name if name == "A1" else name.upper()
            if value != 0.0:
                lines.append(f"      {key}: {_g(value if name == 'A1' else value * k1)}")
    else:
        lines.append("    coefficients:")
        lines += [f"      {name}: {_g(value)}" for name, value in coeffs.items() if value != 0.0]
    if i % 3 == 0:
        lines.append(f"    response: {_response(rng.choice(BANDWIDTHS))}")
    return "\n".join(lines) + "\n"


def write_catalogue(path: Path, n_sensors: int, seed: int) -> None:
    rng = random.Random(seed + n_sensors)
    with open(path, "w", encoding="utf-8") as f:
        f.write("gyrovib: 1\nunits:\n  rate: deg/s\n")
        f.write(PROFILES)
        f.write("sensors:\n")
        for i in range(n_sensors):
            f.write(sensor_yaml(i, rng))


# ------------------------------------------------------------------ measuring


#: Children run as after ``pip install``: bytecode compiled once and reused
#: (PYTHONDONTWRITEBYTECODE would make every run compile gyrovib's sources
#: again, which the site-packages of numpy and yaml never do).
CHILD_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def compile_bytecode() -> None:
    import gyrovib

    package = Path(gyrovib.__file__).parent
    subprocess.run([PYTHON, "-m", "compileall", "-q", str(package)], check=True,
                   env=CHILD_ENV, stdout=subprocess.DEVNULL)


def run(argv: list[str]) -> tuple[float, float, str]:
    """Wall time (s), peak RSS (MB) and stdout of one subprocess."""
    with tempfile.TemporaryFile() as err:
        start = time.perf_counter()
        proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=err, env=CHILD_ENV)
        out = proc.stdout.read()  # type: ignore[union-attr]
        _, status, usage = os.wait4(proc.pid, 0)  # this child's own rusage
        elapsed = time.perf_counter() - start
        proc.returncode = os.waitstatus_to_exitcode(status)
        proc.stdout.close()  # type: ignore[union-attr]
        if proc.returncode != 0:
            err.seek(0)
            raise SystemExit(f"{' '.join(argv)} failed ({proc.returncode}):\n"
                             f"{err.read().decode()}")
    return elapsed, usage.ru_maxrss / 1024.0, out.decode()


def best(argv: list[str], repeat: int, adjust: bool = False) -> tuple[float, float]:
    """Best wall time of ``repeat`` runs and the largest peak RSS seen.

    With ``adjust``, the child prints seconds to subtract from its wall time.
    """
    times, peak = [], 0.0
    for _ in range(repeat):
        t, rss, out = run(argv)
        if adjust:
            t -= float(out.strip().splitlines()[-1])
        times.append(t)
        peak = max(peak, rss)
    return min(times), peak


FLOOR = """
import json, sys, time, yaml
with open(sys.argv[1], encoding="utf-8") as f:
    data = yaml.load(f, Loader=yaml.CSafeLoader)
t0 = time.perf_counter()
with open(sys.argv[2], encoding="utf-8") as f:
    document = json.load(f)
untimed = time.perf_counter() - t0
with open(sys.argv[3], "w", encoding="utf-8") as f:
    f.write(json.dumps(document, allow_nan=False) + "\\n")
print(untimed)
"""


PHASES = """
import sys, time
t0 = time.perf_counter()
from gyrovib import api
from gyrovib.cli.output import write_output
from gyrovib.render import analysis as render
t1 = time.perf_counter()
catalog = api.load([sys.argv[1]])
t2 = time.perf_counter()
result = api.analyze(catalog)
t3 = time.perf_counter()
text = render.to_json(result)
t4 = time.perf_counter()
write_output(text, sys.argv[2])
t5 = time.perf_counter()
print(t1 - t0, t2 - t1, t3 - t2, t4 - t3, t5 - t4)
"""
PHASE_NAMES = ("import gyrovib.api, render, cli.output", "load (YAML + validation)",
               "analyze", "render JSON", "write the file")


def gyrovib_command() -> list[str]:
    script = Path(PYTHON).with_name("gyrovib")
    return [str(script)] if script.exists() else [PYTHON, "-m", "gyrovib"]


def environment() -> dict[str, str]:
    import numpy
    import yaml

    cpu = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "pyyaml": yaml.__version__,
        "libyaml": str(getattr(yaml, "__with_libyaml__", False)),
        "cpu": cpu,
        "nproc": str(os.cpu_count()),
        "platform": platform.platform(),
    }


def ratio_row(what: str, t: float, floor: float, floor_what: str,
              target: float | None) -> str:
    """A table row; ``target`` None for sizes the target does not speak of."""
    r = t / floor
    if target is None:
        return (f"| {what} | {t * 1000:.0f} ms | {floor_what} | {floor * 1000:.0f} ms "
                f"| {r:.2f} | — | |")
    verdict = "met" if r <= target else "NOT met"
    return (f"| {what} | {t * 1000:.0f} ms | {floor_what} | {floor * 1000:.0f} ms "
            f"| {r:.2f} | ≤ {target} | {verdict} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="only 100 and 1,000 sensors")
    parser.add_argument("--repeat", type=int, default=5, help="runs per measurement (best of)")
    parser.add_argument("--seed", type=int, default=6)
    parser.add_argument("--keep", metavar="DIR", help="keep the catalogues and outputs in DIR")
    args = parser.parse_args()
    sizes = (100, 1_000) if args.quick else (100, 1_000, 10_000)
    gyrovib = gyrovib_command()
    work = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="gyrovib-bench-"))
    work.mkdir(parents=True, exist_ok=True)

    compile_bytecode()
    env = environment()
    print("## Environment\n")
    for key, value in env.items():
        print(f"- {key}: {value}")
    print(f"- runs per measurement: best of {args.repeat} (start-up commands: best of "
          f"{3 * args.repeat})\n")

    rows: list[str] = []
    scale: list[tuple[int, float, float, float]] = []
    for n in sizes:
        catalogue = work / f"catalogue-{n}.yaml"
        write_catalogue(catalogue, n, args.seed)
        out = work / f"gyrovib-{n}.json"
        command = [*gyrovib, "analyze", str(catalogue), "--format", "json", "--output", str(out)]
        t, rss = best(command, args.repeat)
        results = len(json.loads(out.read_text())["results"])
        floor, floor_rss = best([PYTHON, "-c", FLOOR, str(catalogue), str(out),
                                 str(work / "floor.json")], args.repeat, adjust=True)
        scale.append((n, t, floor, rss, floor_rss))
        rows.append(ratio_row(f"analyze, {n:,} sensors ({results:,} results, "
                              f"{catalogue.stat().st_size / 1e6:.1f} MB YAML)",
                              t, floor, "CSafeLoader + json.dumps",
                              TARGETS["scale"] if n == 10_000 else None))

    short = 3 * args.repeat  # start-up times are short and noisy: more runs
    t, _ = best([*gyrovib, "analyze", "--format", "json", "-o", os.devnull], short)
    floor, _ = best([PYTHON, "-c", "import numpy, yaml"], short)
    rows.append(ratio_row("first run: analyze, bundled catalogues", t, floor,
                          "`import numpy, yaml`", TARGETS["first"]))
    t, _ = best([*gyrovib, "--help"], short)
    floor, _ = best([PYTHON, "-c", "import click"], short)
    rows.append(ratio_row("`gyrovib --help`", t, floor, "`import click`", TARGETS["help"]))

    print("## Time against the floor\n")
    print("| command | time | floor | floor time | ratio | target | |")
    print("|---|---:|---|---:|---:|---:|---|")
    print("\n".join(rows))

    print("\n## Growth with size and peak memory\n")
    print("| sensors | results | analyze | per sensor | floor | per sensor (floor) "
          "| peak RSS | peak RSS (floor) |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n, t, floor, rss, floor_rss in scale:
        print(f"| {n:,} | {n * 8:,} | {t * 1000:.0f} ms | {t / n * 1e6:.0f} µs "
              f"| {floor * 1000:.0f} ms | {floor / n * 1e6:.0f} µs | {rss:.0f} MB "
              f"| {floor_rss:.0f} MB |")
    n, t, _, rss, _ = scale[-1]
    if n == 10_000:
        verdict = "met" if rss < TARGETS["memory_mb"] else "NOT met"
        print(f"\nPeak RSS at 10,000 sensors: {rss:.0f} MB (target < "
              f"{TARGETS['memory_mb']:.0f} MB): {verdict}.")
    if len(scale) >= 2:
        (n0, t0, *_), (n1, t1, *_) = scale[-2], scale[-1]
        print(f"Growth {n0:,} → {n1:,} sensors: time × {t1 / t0:.2f} for size × {n1 / n0:.0f} "
              f"(log-log slope {math.log(t1 / t0) / math.log(n1 / n0):.2f}; 1 is linear, "
              "below 1 means fixed start-up cost still weighs).")
    if len(scale) >= 2:
        print("\nMarginal time per added sensor: " + ", ".join(
            f"{a:,} → {b:,}: {(tb - ta) / (b - a) * 1e6:.0f} µs"
            for (a, ta, *_), (b, tb, *_) in itertools.pairwise(scale)) + ".")

    n = sizes[-1]
    phase_argv = [PYTHON, "-c", PHASES, str(work / f"catalogue-{n}.yaml"),
                  str(work / "phases.json")]
    runs = [run(phase_argv) for _ in range(args.repeat)]
    phases = min((tuple(float(x) for x in out.split()) for _, _, out in runs), key=sum)
    print(f"\n## Where the time goes, {n:,} sensors (in-process, best run)\n")
    print("| phase | time |")
    print("|---|---:|")
    for name, seconds in zip(PHASE_NAMES, phases, strict=True):
        print(f"| {name} | {seconds * 1000:.0f} ms |")
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
