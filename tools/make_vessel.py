"""Write the SYNTHETIC vessel scenario of docs/vessel.md into a directory.

Nothing here is a measurement. A 12 m uncrewed surface vessel is made up so
that the path from logs to a purchase can be walked (and timed, and tested)
on files whose truth is known. One seeded numpy Generator makes every number:

* ``static.npz``: a static log, ``--static-hours`` (4) at 10 Hz of the z-axis
  rate (column ``gz``): white rate noise of N = 0.02 deg/√h, a rate random walk
  of K = 0.05 deg/h/√h and a constant bias (as tools/make_static_log.py builds
  the GX-100's);
* ``rough-sea.npz``: ``--minutes`` (10) of rate about X, Y, Z (columns ``gx``,
  ``gy``, ``gz``, deg/s) at ``--fs`` (800) Hz in a rough sea: the carrier is
  roll (about 10 deg/s rms), pitch and yaw swell at 0.08–0.2 Hz plus a slow yaw
  drift; the vibration is a diesel at 1,800 rpm (30 Hz, orders 1–6, one fixed
  phase per order), a 3-blade propeller's blade-pass at 36 Hz with its second
  harmonic, wave slams (a 9.39 Hz hull mode ringing down after random impacts)
  and broadband hull noise;
* ``candidates.gyrovib.yaml``: four made-up candidate gyros, their coefficients
  and noise figures (the FOG's are the static log's truth);
* ``voyage.gyrovib.yaml``: a 20-segment mission of 4 h (``--segments``) flown
  on the profile ``rough-sea-fitted`` that ``gyrovib profile rough-sea.npz``
  writes: transits, turns at their own yaw rate, loiters.

Usage::

    python tools/make_vessel.py DIR [--minutes 10] [--fs 800] [--static-hours 4]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

SEED = 20261206
N_ARW = 0.02        # deg/√h, the FOG's angle random walk
K_RRW = 0.05        # deg/h/√h, its rate random walk
BIAS = 0.005        # deg/s
ENGINE_HZ = 30.0    # 1,800 rpm
ENGINE = [(1, 0.30), (2, 0.22), (3, 0.15), (4, 0.10), (5, 0.08), (6, 0.12)]  # order, deg/s
BLADE_HZ = 36.0
SLAM_HZ = 9.39


def static_log(g: np.random.Generator, hours: float) -> dict[str, np.ndarray]:
    fs = 10.0
    n = int(hours * 3600 * fs)
    white = g.standard_normal(n) * (N_ARW / 60.0) * math.sqrt(fs)
    walk = np.cumsum(g.standard_normal(n)) * (K_RRW / 216_000.0) * math.sqrt(1.0 / fs)
    return {"gz": (BIAS + white + walk).astype(np.float32)}


def _swell(g: np.random.Generator, t: np.ndarray, rms: float, band: tuple[float, float],
           lines: int = 6) -> np.ndarray:
    """A narrow-band sea: ``lines`` sines of random frequency in ``band`` and phase."""
    f = g.uniform(*band, size=lines)
    phase = g.uniform(0.0, 2.0 * math.pi, size=lines)
    amp = rms * math.sqrt(2.0 / lines)
    return np.sum(amp * np.sin(2.0 * math.pi * f[:, None] * t[None, :] + phase[:, None]),
                  axis=0)


def _slams(g: np.random.Generator, t: np.ndarray, fs: float) -> np.ndarray:
    """Ring-downs of the 9.39 Hz hull mode after impacts every 6 s on average."""
    out = np.zeros(t.size)
    at = np.cumsum(g.exponential(6.0, size=int(t[-1] / 6.0) + 20))
    ring = np.arange(int(3.0 * fs)) / fs
    shape = np.exp(-ring / 0.5) * np.sin(2.0 * math.pi * SLAM_HZ * ring)
    for start in at[at < t[-1]]:
        k = int(start * fs)
        piece = shape[: t.size - k] * g.uniform(1.0, 3.0)
        out[k:k + piece.size] += piece
    return out


def rough_sea(g: np.random.Generator, minutes: float, fs: float) -> dict[str, np.ndarray]:
    t = np.arange(int(minutes * 60 * fs)) / fs
    roll = _swell(g, t, 10.0, (0.08, 0.16))
    pitch = _swell(g, t, 4.0, (0.10, 0.20))
    yaw = _swell(g, t, 1.5, (0.05, 0.12)) + 0.8 * np.sin(2.0 * math.pi * t / 240.0)
    cols = [roll, pitch, yaw]
    mix = np.array([[0.6, 0.5, 1.0], [0.4, 1.0, 0.6], [1.0, 0.7, 0.5]])  # axis weights
    phases = g.uniform(0.0, 360.0, size=(len(ENGINE), 3))
    for k, (order, amp) in enumerate(ENGINE):
        for axis in range(3):
            cols[axis] = cols[axis] + amp * mix[axis, 0] * np.sin(
                2.0 * math.pi * order * ENGINE_HZ * t + np.deg2rad(phases[k, axis]))
    for order, amp in ((1, 0.25), (2, 0.10)):
        phase = g.uniform(0.0, 2.0 * math.pi)
        for axis in range(3):
            cols[axis] = cols[axis] + amp * mix[axis, 1] * np.sin(
                2.0 * math.pi * order * BLADE_HZ * t + phase)
    slam = _slams(g, t, fs)
    for axis in range(3):
        cols[axis] = cols[axis] + mix[axis, 2] * slam + 0.15 * g.standard_normal(t.size)
    return {name: c.astype(np.float64) for name, c in zip(("gx", "gy", "gz"), cols,
                                                          strict=True)}


CANDIDATES = """\
# SYNTHETIC: four made-up candidate heading gyros for the vessel scenario of
# docs/vessel.md (tools/make_vessel.py). No part here exists; the coefficients and
# noise figures are illustrative. usv-fog's noise is the truth of the synthetic
# static log static.npz (gyrovib allan reads it back).
gyrovib: 1
units: {rate: deg/s}
sensors:
  - id: usv-mems-a
    name: consumer MEMS gyro (made up)
    range: 500
    coefficients: {A1: 2.0e-3, k2: 4.0e-4, k3: 2.0e-6, m31: 1.0e-4, m32: -1.0e-4}
    noise: {arw: 0.3 deg/sqrt(h), bias_instability: 5 deg/h, rrw: 2 deg/h/sqrt(h),
            bias_repeatability: 0}
  - id: usv-mems-b
    name: industrial MEMS gyro (made up)
    range: 300
    coefficients: {A1: 2.0e-4, k2: 3.0e-5, k3: -1.0e-7, m31: 2.0e-5, m32: 2.0e-5}
    noise: {arw: 0.1 deg/sqrt(h), bias_instability: 1.5 deg/h, rrw: 0.5 deg/h/sqrt(h),
            bias_repeatability: 0}
  - id: usv-tactical
    name: tactical MEMS gyro (made up)
    range: 400
    coefficients: {A1: 2.0e-5, k2: 4.0e-6, k3: -2.0e-9, m31: 1.0e-6, m32: -1.0e-6}
    noise: {arw: 0.05 deg/sqrt(h), bias_instability: 0.3 deg/h, rrw: 0.4 deg/h/sqrt(h),
            bias_repeatability: 0}
  - id: usv-fog
    name: small FOG (made up)
    range: 500
    coefficients: {A1: 2.0e-6, k2: 1.0e-7, k3: 1.0e-10}
    noise: {arw: %(arw)s deg/sqrt(h), bias_instability: 0.05 deg/h,
            rrw: %(rrw)s deg/h/sqrt(h), bias_repeatability: 0}
"""


def voyage(segments: int, hours: float) -> str:
    """A mission of ``segments`` segments over ``hours``: transit, turn, loiter in turn."""
    lines = ["# SYNTHETIC: a made-up 4 h voyage of the vessel of docs/vessel.md",
             "# (tools/make_vessel.py), flown on the profile fitted to rough-sea.npz.",
             "gyrovib: 1", "units: {rate: deg/s}", "missions:", "  - id: voyage",
             "    placement: triad", "    segments:"]
    each = hours * 3600.0 / segments
    for s in range(segments):
        kind = s % 4
        if kind == 3:
            rate, dur = "[0, 0, %g]" % (3.0 if s % 8 == 3 else -3.0), each * 0.25
        elif kind == 2:
            rate, dur = "[0, 0, 0]", each * 1.25
        else:
            rate, dur = "[0, 0, 0.2]", each * 1.25
        lines.append(f"      - {{profile: rough-sea-fitted, duration: {dur:.6g}, "
                     f"rate: {rate}}}")
    # the durations above add up to hours·3600 for any multiple of 4 segments
    return "\n".join(lines) + "\n"


def write(directory: Path, minutes: float = 10.0, fs: float = 800.0,
          static_hours: float = 4.0, segments: int = 20, hours: float = 4.0) -> None:
    g = np.random.default_rng(SEED)
    directory.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(directory / "static.npz", **static_log(g, static_hours))
    np.savez(directory / "rough-sea.npz", **rough_sea(g, minutes, fs))
    (directory / "candidates.gyrovib.yaml").write_text(
        CANDIDATES % {"arw": N_ARW, "rrw": K_RRW}, encoding="utf-8")
    (directory / "voyage.gyrovib.yaml").write_text(voyage(segments, hours), encoding="utf-8")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("directory", type=Path)
    p.add_argument("--minutes", type=float, default=10.0)
    p.add_argument("--fs", type=float, default=800.0)
    p.add_argument("--static-hours", type=float, default=4.0)
    p.add_argument("--segments", type=int, default=20)
    a = p.parse_args()
    write(a.directory, a.minutes, a.fs, a.static_hours, a.segments)
    print(f"wrote the synthetic vessel scenario to {a.directory}")


if __name__ == "__main__":
    main()
