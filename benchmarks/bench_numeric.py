"""Closed form against brute force: time for the same accuracy.

Run on demand (not part of the test suite):

    .venv/bin/python benchmarks/bench_numeric.py [--target 1e-4] [--cap 20000000]

For each profile, one sensor with every eq. (2) coefficient set:

* the closed form (`exact`: core.analysis.profile_multipliers + vibration_error)
  is timed per evaluation (best of several repeats);
* the brute force (core.numeric.simulate) is run with doubling sample counts
  until its relative standard error is at most ``--target``, or the count
  reaches ``--cap``; then the count needed is extrapolated with the Monte
  Carlo law stderr ∝ n^(-1/2) (conservative for the shifted grids, which
  converge faster) and so is the time (linear in n).

Also reported: the time of one 200 000-point run for 1 and for 100 sensors.
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import time

import numpy as np

from gyrovib.core.analysis import profile_multipliers, vibration_error
from gyrovib.core.numeric import simulate
from gyrovib.core.statistics import vibration_at_sensor

# k0 k1 A1 k2 k3 k4 k5 m1 m2 m31 m32 (deg/s powers)
SENSOR = np.array([[0.001, 1.0, 0.02, 2e-3, -1e-4, 3e-5, -2e-6, 1e-3, -1e-3, 1e-3, 5e-4]])

PROFILES = {
    "one tone, Ω_K3 < a": (vibration_at_sensor([(95.0, [1.2, 0.8, 2.5], [0, 30, 0])]),
                        [0.0, 0.0, 0.5]),
    "three tones": (vibration_at_sensor([(60.0, [0.6, 0.5, 1.8], [0, 30, 0]),
                                         (120.0, [0.4, 0.3, 1.0], [90, 0, 0]),
                                         (240.0, [0.2, 0.2, 0.5], [0, 180, 45])]),
                    [0.0, 0.0, 1.0]),
    "random (rms)": (vibration_at_sensor(rms=[1.0, 1.0, 2.5], coherence=[0.6, -0.3]),
                     [0.0, 0.0, 4.0]),
    "sine-on-random": (vibration_at_sensor([(150.0, [0.8, 0.8, 4.0], [0, 0, 0])],
                                           rms=[0.5, 0.5, 1.6]),
                       [0.0, 0.0, 1.0]),
}


def best_time(fn, repeat: int = 5, number: int = 1) -> float:  # type: ignore[no-untyped-def]
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t0) / number)
    return best


def machine() -> str:
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as handle:
            for line in handle:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return (f"{cpu}; nproc {os.cpu_count()}; Python {platform.python_version()}; "
            f"numpy {np.__version__}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--target", type=float, default=1e-4,
                        help="relative standard error wanted (default 1e-4)")
    parser.add_argument("--cap", type=int, default=20_000_000,
                        help="largest sample count actually run (default 2e7)")
    args = parser.parse_args()
    print(f"machine: {machine()}")
    print(f"target relative stderr: {args.target:g}\n")
    head = (f"| profile | closed form | Δ_V exact | numeric n run | rel. stderr | time | "
            f"n for {args.target:g} | time for {args.target:g} | |num−exact|/stderr |")
    print(head)
    print("|" + "---|" * 9)
    for name, (vib, rate) in PROFILES.items():
        closed = best_time(lambda v=vib, r=rate: vibration_error(
            SENSOR, profile_multipliers(v, r[2])), repeat=5, number=20)
        exact = float(vibration_error(SENSOR, profile_multipliers(vib, rate[2])).total[0])
        n = 1_000
        while True:
            t0 = time.perf_counter()
            est = simulate(SENSOR, vib, rate, samples=n, rng=np.random.default_rng(0))
            elapsed = time.perf_counter() - t0
            rel = float(est.stderr[0]) / abs(exact)
            if rel <= args.target or 2 * n > args.cap:
                break
            n *= 2
        if rel <= args.target:
            needed, t_needed, mark = est.points, elapsed, ""
        else:
            factor = (rel / args.target) ** 2
            needed, t_needed, mark = int(est.points * factor), elapsed * factor, " (extrap.)"
        z = abs(float(est.total[0]) - exact) / float(est.stderr[0]) if est.stderr[0] else 0.0
        print(f"| {name} | {closed * 1e3:.3f} ms | {exact:.6g} | {est.points:,} ({est.scheme}) | "
              f"{rel:.2g} | {elapsed:.2f} s | {needed:.3g}{mark} | {t_needed:.3g} s{mark} | "
              f"{z:.2f} |")
    print("\nOne 200 000-point run, random (rms) profile:")
    vib, rate = PROFILES["random (rms)"]
    for n_sensors in (1, 100):
        coeffs = np.repeat(SENSOR, n_sensors, axis=0)
        t = best_time(lambda c=coeffs: simulate(c, vib, rate, samples=200_000,
                                                rng=np.random.default_rng(0)), repeat=3)
        tc = best_time(lambda c=coeffs: vibration_error(c, profile_multipliers(vib, rate[2])),
                       repeat=5, number=20)
        print(f"  {n_sensors:>3} sensors: numeric {t:.3f} s, closed form {tc * 1e3:.3f} ms")


if __name__ == "__main__":
    main()
