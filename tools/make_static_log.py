"""Write docs/examples/static-gx100.npz: a SYNTHETIC static log of the made-up GX-100.

Not a measurement: two hours at 10 Hz of the z-axis rate of a part at rest,
made of the three noises of docs/model.md section 15 plus a constant bias, so
that docs/error-budget.md can show `gyrovib allan` on a file whose truth is known:

* white rate noise of angle random walk N = 0.05 deg/√h (σ = N·√fs per sample,
  N in deg/√s);
* a first-order Gauss-Markov bias of 0.3 deg/h rms and 300 s correlation time
  (it makes the flat bottom a bias instability reads);
* a rate random walk of K = 0.3 deg/h/√h (steps of K·√τ0, K in deg/s/√s);
* a bias of 0.02 deg/s.

One seeded numpy Generator makes every number; the column is stored as float32
under the name ``gz`` (a compressed .npz):

    python tools/make_static_log.py            # rewrites the file
    python tools/make_static_log.py --check    # exit 1 if the file differs
"""

from __future__ import annotations

import io
import sys
from pathlib import Path

import numpy as np

SEED = 20261206
FS = 10.0
HOURS = 2.0
N_ARW = 0.05          # deg/√h
GM_RMS = 0.3          # deg/h
GM_TIME = 300.0       # s
K_RRW = 0.3           # deg/h/√h
BIAS = 0.02           # deg/s

ROOT = Path(__file__).resolve().parent.parent
TARGET = ROOT / "docs" / "examples" / "static-gx100.npz"


def make() -> bytes:
    g = np.random.default_rng(SEED)
    n = int(HOURS * 3600 * FS)
    tau0 = 1.0 / FS
    white = g.standard_normal(n) * (N_ARW / 60.0) * np.sqrt(FS)
    walk = np.cumsum(g.standard_normal(n)) * (K_RRW / 216_000.0) * np.sqrt(tau0)
    a = np.exp(-tau0 / GM_TIME)
    drive = g.standard_normal(n) * (GM_RMS / 3600.0) * np.sqrt(1.0 - a * a)
    markov = np.empty(n)
    markov[0] = g.standard_normal() * GM_RMS / 3600.0
    for k in range(1, n):  # x_k = a·x_{k-1} + w_k: stationary with the rms above
        markov[k] = a * markov[k - 1] + drive[k]
    rate = (BIAS + white + walk + markov).astype(np.float32)
    out = io.BytesIO()
    np.savez_compressed(out, gz=rate)
    return out.getvalue()


def main() -> None:
    data = make()
    if "--check" in sys.argv[1:]:
        same = TARGET.exists() and np.array_equal(np.load(TARGET)["gz"],
                                                  np.load(io.BytesIO(data))["gz"])
        sys.exit(0 if same else 1)
    TARGET.write_bytes(data)
    print(f"wrote {TARGET.relative_to(ROOT)} ({len(data)} bytes)")


if __name__ == "__main__":
    main()
