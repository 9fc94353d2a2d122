"""``gyrovib allan --format kalibr``: the noise model as Kalibr's ``imu.yaml`` (also read
by OpenVINS and VINS-Fusion; docs/model.md section 15).

Kalibr's IMU noise model takes continuous-time densities in SI units:

* ``gyroscope_noise_density`` [rad/s/√Hz] = N: N [deg/√h] / 60 is N in deg/√s, which is
  deg/s/√Hz (white rate noise of density N has σ²(τ) = N²/τ), times π/180;
* ``gyroscope_random_walk`` [rad/s²/√Hz] = K: K [deg/h/√h] / 216 000 is deg/s/√s, that
  is deg/s²/√Hz, times π/180;
* ``accelerometer_noise_density`` [m/s²/√Hz] and ``accelerometer_random_walk``
  [m/s³/√Hz] likewise from the specific force's velocity random walk and its random
  walk, where the record has one;
* ``update_rate`` [Hz]: the record's rate.

The discrete standard deviation per sample is σ_d = σ_c·√(update_rate) for the white
term and σ_c/√(update_rate) for the random walk — true only of an ideally decimated
stream (Kalibr's noise-model notes): the file carries the continuous values and says so.
One value serves every axis: the largest of the recorded axes (each listed in a comment).
A term the record does not resolve is written as its upper bound, and said to be one.
"""

from __future__ import annotations

import math
import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from gyrovib.api.noise import AllanResult, AxisAllan

DEG = math.pi / 180.0
#: From the reported units to Kalibr's: (figure, factor).
_GYRO = (("gyroscope_noise_density", "arw", DEG / 60.0),
         ("gyroscope_random_walk", "rrw", DEG / 216_000.0))
_ACCEL = (("accelerometer_noise_density", "arw", 1.0 / 60.0),
          ("accelerometer_random_walk", "rrw", 1.0 / 60.0))


def _entry(key: str, name: str, factor: float, axes: tuple[AxisAllan, ...]) -> list[str]:
    figs = [(ax.axis, ax.figures[name]) for ax in axes]
    worst = max(figs, key=lambda p: p[1].upper)
    each = ", ".join(f"{axis} {'≤ ' if f.is_bound else ''}{f.upper * factor:.6g}"
                     for axis, f in figs)
    bound = any(f.is_bound for _, f in figs)
    note = (" an upper bound at 95 % (the record does not resolve it)"
            if worst[1].is_bound else "")
    lines = [f"{key}: {worst[1].upper * factor:.6g}    # axis {worst[0]} (largest):{note}",
             f"#   per axis: {each}"]
    if bound and not worst[1].is_bound:
        lines.append("#   (a '≤' axis is a bound, below the value written)")
    return lines


def to_kalibr(result: AllanResult) -> str:
    """Kalibr's imu.yaml (see the module docstring)."""
    rate = result.fs
    lines = [f"# imu.yaml from gyrovib allan {os.path.basename(result.file)} "
             f"(sha256 {result.sha256[:16]}…, {result.samples} samples at {rate:.6g} Hz)",
             "# continuous-time noise densities (Kalibr's IMU noise model): white terms in",
             "# unit/√Hz, random walks in unit/s/√Hz. Per sample, for an ideally decimated",
             f"# stream only: σ_d = density·√update_rate (√{rate:.6g} = {math.sqrt(rate):.6g})"
             " for the white terms, random_walk/√update_rate for the random walks.",
             "# gyroscope_noise_density = N [deg/√h] / 60 · π/180; gyroscope_random_walk = "
             "K [deg/h/√h] / 216000 · π/180"]
    for key, name, factor in _GYRO:
        lines.extend(_entry(key, name, factor, result.axes))
    if result.accel:
        lines.append("# accelerometer_noise_density = VRW [m/s/√h] / 60; "
                     "accelerometer_random_walk = its random walk [m/s²/√h] / 60")
        for key, name, factor in _ACCEL:
            lines.extend(_entry(key, name, factor, result.accel))
    else:
        lines.append("# accelerometer_noise_density, accelerometer_random_walk: the record has "
                     "no specific force; fill them in from the accelerometer's own log")
    lines.append(f"update_rate: {rate:.6g}")
    return "\n".join(lines) + "\n"
