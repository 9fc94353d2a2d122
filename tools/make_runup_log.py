"""Write docs/examples/runup-quad.npz: a SYNTHETIC run-up test of a made-up quadcopter.

Not a measurement: the vehicle on a stand, its motors stepped off, idle, 40, 60 and
80 % and back down to off (15 s a step, 2 s ramps between), logged at 200 Hz, so that
docs/runup.md can show `gyrovib runup` on a file whose truth is known:

* the blade-pass tone at 40 + 50·throttle Hz: linear vibration of 2.5·throttle g
  amplitude on each axis (random phases per step), angular vibration about every
  axis of 3·throttle² deg/s amplitude (the frame's rocking grows faster than the
  thrust's shaking), plus broadband parts of a fifth of each;
* the z gyro rectifies with a g² sensitivity (VRE) of 0.02 deg/s/g² on every axis and
  no angular nonlinearity (k2 = 0); its bias drifts by 2e-5 deg/s each second
  (warming up); white noise of 0.005 deg/s/√Hz (0.3 deg/√h) on every gyro axis;
* the Earth's rate, 0.004 deg/s, about z; gravity, 1 g, along z.

One seeded numpy Generator makes every number; columns stored as float32 under the
names gx, gy, gz (deg/s) and ax, ay, az (g) in a compressed .npz:

    python tools/make_runup_log.py            # rewrites the file
    python tools/make_runup_log.py --check    # exit 1 if the file differs
"""

from __future__ import annotations

import io
import sys
from pathlib import Path

import numpy as np

SEED = 20261206
FS = 200.0
STEP = 15.0           # s
RAMP = 2.0            # s
THROTTLE = (0.0, 0.1, 0.4, 0.6, 0.8, 0.6, 0.4, 0.0)
VRE = 0.02            # deg/s/g²
DRIFT = 2e-5          # deg/s/s
ARW = 0.005           # deg/s/√Hz
EARTH = 0.004         # deg/s

ROOT = Path(__file__).resolve().parent.parent
TARGET = ROOT / "docs" / "examples" / "runup-quad.npz"


def _throttle() -> np.ndarray:
    parts = []
    for k, level in enumerate(THROTTLE):
        if k:
            parts.append(np.linspace(THROTTLE[k - 1], level, round(RAMP * FS)))
        parts.append(np.full(round(STEP * FS), level))
    return np.concatenate(parts)


def make() -> bytes:
    g = np.random.default_rng(SEED)
    thr = _throttle()
    n = thr.size
    t = np.arange(n) / FS
    phase = 2 * np.pi * np.cumsum(40.0 + 50.0 * thr) / FS
    tone = np.sin(phase[:, None] + g.uniform(0, 2 * np.pi, 3))
    accel = 2.5 * thr[:, None] * (tone + 0.2 * g.standard_normal((n, 3)))
    accel[:, 2] += 1.0
    rock = 3.0 * thr[:, None] ** 2 * (np.sin(phase[:, None] + g.uniform(0, 2 * np.pi, 3))
                                       + 0.2 * g.standard_normal((n, 3)))
    gyro = rock + ARW * np.sqrt(FS) * g.standard_normal((n, 3))
    gyro[:, 2] += EARTH + DRIFT * t + VRE * np.sum(accel**2, axis=1)
    out = io.BytesIO()
    columns = np.column_stack([gyro, accel]).astype(np.float32)
    np.savez_compressed(out, **{name: columns[:, k] for k, name in
                                enumerate(("gx", "gy", "gz", "ax", "ay", "az"))})
    return out.getvalue()


def main() -> None:
    data = make()
    if "--check" in sys.argv[1:]:
        old = np.load(TARGET) if TARGET.exists() else None
        new = np.load(io.BytesIO(data))
        same = old is not None and all(np.array_equal(old[k], new[k]) for k in new.files)
        sys.exit(0 if same else 1)
    TARGET.write_bytes(data)
    print(f"wrote {TARGET.relative_to(ROOT)} ({len(data)} bytes)")


if __name__ == "__main__":
    main()
