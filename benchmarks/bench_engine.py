"""Engine benchmark: E(Ω) for many tones, and rate sweeps (docs/performance.md).

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_engine.py
    python benchmarks/bench_engine.py --before /path/to/old/checkout

Every measurement is the wall-clock time of a fresh subprocess, best of
``--repeat`` runs, with its peak resident memory (``ru_maxrss``), as in
bench_scale.py. With ``--before DIR`` (a checkout or ``git archive`` of an
older gyrovib: ``DIR/src`` and ``DIR/catalogs``) each command is also run on
that code, in the same run, under a ``--limit-mb`` address-space limit and a
``--timeout``, so that a run out of memory or time is reported, not waited for.

Targets:

* **mixtures**: ``gyrovib analyze`` of 8 sensors (8 distinct frequency
  responses, so the profile statistics are computed 8 times) on a profile of
  64 tones plus a PSD, and on one of 16 tones alone: each within 3x the
  first-run time of ``gyrovib analyze`` on the bundled catalogues, and under
  400 MB peak. The smaller mixtures of the issue (7 tones + random, 8 tones
  alone) are measured too, since the old code can finish some of them.
* **sweep**: ``gyrovib sweep --sensor adxrs453 --rate-range -500:500:N
  --format csv -o /dev/null`` over the bundled profiles at N = 20,000 rates
  within 2x the same sweep at N = 2,000 (most rates beyond the vibration's
  reach). Measured end to end and at the library level (``api.sweep`` in a
  fresh process, with its import), the two sizes (and both versions) taken in
  turn in every repeat, so that the machine's load drifts alike over all four.
  The sensor is coefficient-form (``--sweep-sensor`` picks another): a
  datasheet sensor's worst case is one envelope programme per profile and
  rate, whose cost grows with the rates however the rest is written.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PYTHON = sys.executable
TARGETS = {"mixtures": 3.0, "memory_mb": 400.0, "sweep": 2.0}
CHILD_ENV = {k: v for k, v in os.environ.items()
             if k not in ("PYTHONDONTWRITEBYTECODE", "PYTHONPATH")}

# ------------------------------------------------------------------ catalogue


def _tones(n: int, scale: float, seed: int) -> str:
    """``n`` tones from 20 Hz to 2 kHz, amplitudes on x3 spread over 0.2..1 × scale."""
    lines = []
    for k in range(n):
        f = 20.0 * 100.0 ** (k / max(1, n - 1))
        a3 = scale * (0.2 + 0.8 * ((k * 7919 + seed) % n) / n)
        lines.append(f"      - {{frequency: {f:.6g}, amplitude: [{0.5 * a3:.6g}, "
                     f"{0.4 * a3:.6g}, {a3:.6g}], phase: [0, {(37 * k) % 360}, 0]}}")
    return "\n".join(lines)


def profiles_yaml() -> str:
    psd = """    random:
      psd:
        x1: [[20, 1.5e-4], [2000, 1.5e-4]]
        x2: [[20, 1.5e-4], [2000, 1.5e-4]]
        x3: [[20, 2.5e-4], [2000, 2.5e-4]]"""
    out = ["profiles:"]
    for pid, n, scale, random_part, rate in (
        ("tones64-random", 64, 0.3, True, 2.0),
        ("tones16", 16, 0.5, False, 1.0),
        ("tones7-random", 7, 0.8, True, 1.0),
        ("tones8", 8, 0.8, False, 1.0),
    ):
        out += [f"  - id: {pid}", f"    rate: [0, 0, {rate}]", "    harmonic:",
                _tones(n, scale, n)]
        if random_part:
            out.append(psd)
    return "\n".join(out) + "\n"


def sensors_yaml(n: int = 8) -> str:
    """``n`` sensors, each with its own 2-pole roll-off (bandwidth 100 Hz .. 2 kHz)."""
    out = ["sensors:"]
    points = [(0.5, 0.970), (1.0, 0.707), (2.0, 0.243), (4.0, 0.0624), (10.0, 0.01)]
    for i in range(n):
        fc = 100.0 * 20.0 ** (i / max(1, n - 1))
        table = ", ".join(f"[{fc * r:.6g}, {g}]" for r, g in points)
        out += [f"  - id: mix-{i}", "    range: 2000", "    coefficients:",
                "      k1: 1.0", f"      A1: {1e-3 * (1 + i)}", "      k2: 1.0e-6",
                "      k3: -1.0e-9", "      m31: 5.0e-7", "      m32: -5.0e-7",
                f"    response: [{table}]"]
    return "\n".join(out) + "\n"


# ------------------------------------------------------------------ measuring


class Failed(Exception):
    """A child that ran out of memory or time, or failed."""


def run(argv: list[str], env: dict[str, str], limit_mb: float | None,
        timeout: float) -> tuple[float, float, float]:
    """Wall time (s), peak RSS (MB) and CPU time (user + system, s) of one subprocess."""

    def limit() -> None:
        if limit_mb is not None:
            size = int(limit_mb * 2**20)
            resource.setrlimit(resource.RLIMIT_AS, (size, size))

    with tempfile.TemporaryFile() as err:
        start = time.perf_counter()
        proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=err, env=env,
                                preexec_fn=limit)
        deadline = start + timeout
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if time.perf_counter() > deadline:
                proc.kill()
                os.wait4(proc.pid, 0)
                raise Failed(f"timed out after {timeout:.0f} s")
            time.sleep(0.005)
        elapsed = time.perf_counter() - start
        code = os.waitstatus_to_exitcode(status)
        if code != 0:
            err.seek(0)
            text = err.read().decode(errors="replace")
            if "MemoryError" in text or "memory" in text.lower() or code < 0:
                raise Failed(f"out of memory (limit {limit_mb:.0f} MB)")
            raise Failed(f"failed ({code}): {text.strip().splitlines()[-1:]}")
    return elapsed, usage.ru_maxrss / 1024.0, usage.ru_utime + usage.ru_stime


def best(argv: list[str], env: dict[str, str], repeat: int, limit_mb: float | None = None,
         timeout: float = 600.0) -> tuple[float, float, float]:
    """Best wall time, peak RSS and best CPU time of ``repeat`` runs. On a shared
    machine the CPU time is the steadier of the two times."""
    times, cpus, peak = [], [], 0.0
    for _ in range(repeat):
        t, rss, cpu = run(argv, env, limit_mb, timeout)
        times.append(t)
        cpus.append(cpu)
        peak = max(peak, rss)
        if t > 10.0:  # one slow run is enough
            break
    return min(times), peak, min(cpus)


def fmt(result: tuple[float, float, float] | str) -> tuple[str, str]:
    if isinstance(result, str):
        return result, "—"
    return f"{result[0] * 1000:.0f} ms (cpu {result[2] * 1000:.0f})", f"{result[1]:.0f} MB"


SWEEP_LIBRARY = """
import sys
import numpy as np
from gyrovib import api
catalog = api.load([])
api.sweep(catalog, np.linspace(-500, 500, int(sys.argv[1])), sensors=[sys.argv[2]])
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per measurement (best of)")
    parser.add_argument("--before", metavar="DIR", help="also run the gyrovib in DIR/src")
    parser.add_argument("--limit-mb", type=float, default=2048.0,
                        help="address-space limit of the --before runs")
    parser.add_argument("--timeout", type=float, default=120.0, help="per --before run (s)")
    parser.add_argument("--only", choices=["all", "mixtures", "sweep"], default="all",
                        help="measure only these targets (the first run always)")
    parser.add_argument("--sweep-sensor", default="adxrs453",
                        help="bundled sensor of the sweeps (default: coefficient-form adxrs453)")
    args = parser.parse_args()

    work = Path(tempfile.mkdtemp(prefix="gyrovib-engine-"))
    catalogue = work / "mixtures.yaml"
    catalogue.write_text("gyrovib: 1\nunits:\n  rate: deg/s\n" + profiles_yaml()
                         + sensors_yaml(), encoding="utf-8")
    gyrovib = [PYTHON, "-m", "gyrovib"]
    subprocess.run([PYTHON, "-m", "compileall", "-q", str(Path(__file__).parents[1] / "src")],
                   check=True, env=CHILD_ENV, stdout=subprocess.DEVNULL)
    versions: dict[str, dict[str, str]] = {"after": CHILD_ENV}
    if args.before:
        src = str(Path(args.before).resolve() / "src")
        subprocess.run([PYTHON, "-m", "compileall", "-q", src], check=True,
                       env=CHILD_ENV, stdout=subprocess.DEVNULL)
        versions["before"] = {**CHILD_ENV, "PYTHONPATH": src}

    measured: dict[tuple[str, str], tuple[float, float, float] | str] = {}

    def measure(key: str, argv: list[str], repeat: int) -> None:
        for version, env in versions.items():
            limit = args.limit_mb if version == "before" else None
            timeout = args.timeout if version == "before" else 600.0
            try:
                measured[(key, version)] = best(argv, env, repeat, limit, timeout)
            except Failed as exc:
                measured[(key, version)] = str(exc)

    def measure_interleaved(commands: dict[str, list[str]], repeat: int) -> None:
        """Best of ``repeat`` rounds, each round running every command on every version."""
        runs: dict[tuple[str, str], list[tuple[float, float, float]]] = {}
        for _ in range(repeat):
            for key, argv in commands.items():
                for version, env in versions.items():
                    if isinstance(measured.get((key, version)), str):
                        continue  # failed once: reported, not retried
                    limit = args.limit_mb if version == "before" else None
                    timeout = args.timeout if version == "before" else 600.0
                    try:
                        runs.setdefault((key, version), []).append(
                            run(argv, env, limit, timeout))
                    except Failed as exc:
                        measured[(key, version)] = str(exc)
        for k, got in runs.items():
            if not isinstance(measured.get(k), str):
                measured[k] = (min(t for t, _, _ in got), max(r for _, r, _ in got),
                               min(c for _, _, c in got))

    short = max(args.repeat, 9)
    measure("first run", [*gyrovib, "analyze", "--format", "json", "-o", os.devnull], short)
    mixtures = ("tones64-random", "tones16", "tones7-random", "tones8")
    for pid in mixtures if args.only in ("all", "mixtures") else ():
        measure(pid, [*gyrovib, "analyze", str(catalogue), "--profile", pid,
                      "--format", "json", "-o", os.devnull], args.repeat)
    if args.only in ("all", "sweep"):
        sweeps: dict[str, list[str]] = {}
        for n in (2000, 20000):
            sweeps[f"sweep {n}"] = [*gyrovib, "sweep", "--sensor", args.sweep_sensor,
                                    "--rate-range", f"-500:500:{n}", "--format", "csv",
                                    "-o", os.devnull]
            sweeps[f"api.sweep {n}"] = [PYTHON, "-c", SWEEP_LIBRARY, str(n), args.sweep_sensor]
        measure_interleaved(sweeps, args.repeat)

    print(f"Python {sys.version.split()[0]}, nproc {os.cpu_count()}\n")
    print("| measurement | version | time | peak RSS | ratio | target | |")
    print("|---|---|---:|---:|---:|---:|---|")
    for version in versions:
        first = measured[("first run", version)]
        t, rss = fmt(first)
        print(f"| first run: analyze, bundled catalogues | {version} | {t} | {rss} | 1 | | |")
        for pid, n in (("tones64-random", "64 tones + PSD"), ("tones16", "16 tones alone"),
                       ("tones7-random", "7 tones + PSD"), ("tones8", "8 tones alone")):
            if (pid, version) not in measured:
                continue
            got = measured[(pid, version)]
            t, rss = fmt(got)
            if isinstance(got, str) or isinstance(first, str):
                print(f"| analyze, 8 sensors, {n} | {version} | {t} | {rss} | — "
                      "| ≤ 3.0 | not met |")
                continue
            ratio = got[0] / first[0]
            ok = ratio <= TARGETS["mixtures"] and got[1] < TARGETS["memory_mb"]
            print(f"| analyze, 8 sensors, {n} | {version} | {t} | {rss} | {ratio:.2f} "
                  f"(cpu {got[2] / first[2]:.2f}) | ≤ 3.0, < 400 MB | "
                  f"{'met' if ok else 'not met'} |")
        for label, key in ((f"sweep --sensor {args.sweep_sensor}, CSV", "sweep"),
                           ("api.sweep", "api.sweep")):
            if (f"{key} 2000", version) not in measured:
                continue
            small, big = measured[(f"{key} 2000", version)], measured[(f"{key} 20000", version)]
            for n, got in ((2000, small), (20000, big)):
                t, rss = fmt(got)
                if n == 2000:
                    print(f"| {label}, {n:,} rates | {version} | {t} | {rss} | 1 | | |")
                elif isinstance(got, str) or isinstance(small, str):
                    print(f"| {label}, {n:,} rates | {version} | {t} | {rss} | — | ≤ 2.0 | |")
                else:
                    ratio = got[0] / small[0]
                    ok = "met" if ratio <= TARGETS["sweep"] else "not met"
                    print(f"| {label}, {n:,} rates | {version} | {t} | {rss} | {ratio:.2f} "
                          f"(cpu {got[2] / small[2]:.2f}) | ≤ 2.0 | {ok} |")
    print(f"\n(catalogue: {catalogue}; ratios: against the first run, or the 2,000-rate sweep, "
          "of the same version in this run)")


if __name__ == "__main__":
    main()
