"""Breakpoint fit benchmark: the cost of one axis's random-PSD fit (docs/performance.md).

Run on demand (it is not part of the test suite)::

    python benchmarks/bench_breakpoints.py

One axis of `gyrovib profile` fits its random PSD once
(:func:`gyrovib.core.breakpoints.fit_breakpoints`: candidates, pair costs,
the dynamic programme, the variance-constrained levels). The spectra are
a plateau 2–150 Hz with a resonance at 80 Hz and an anti-alias
roll-off, scattered as a 60-window Welch estimate, over f_c = 5 Hz … fs/2 at
Δf = 0.5 Hz: 240 bins at fs = 250 Hz, 990 at 1 kHz and 7990 at 8 kHz. Each
line reports the median and the largest of ``--repeat`` timings, with the
shape figures of the fit.
"""

from __future__ import annotations

import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "src"))

import numpy as np  # noqa: E402

from gyrovib.core.breakpoints import fit_breakpoints, shape_figures  # noqa: E402


def spectrum(fs: float, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    f = np.arange(5.0, fs / 2, 0.5)
    plateau = 0.01 / (1 + (2 / f) ** 8) / (1 + (f / 150) ** 8)
    resonance = 0.3 / (1 + ((f - 80) / 2) ** 2)
    true = (plateau + resonance) / (1 + (f / (0.42 * fs)) ** 16)
    return f, true * rng.chisquare(120, f.size) / 120


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=20)
    args = parser.parse_args()
    rng = np.random.default_rng(30)
    print(f"{'fs':>6} {'bins':>5} {'B':>3} {'median ms':>10} {'max ms':>8} {'shape dB':>9} "
          f"{'off 3 dB':>9}")
    for fs in (250.0, 1000.0, 8000.0):
        f, psd = spectrum(fs, rng)
        for count in (4, 12, 40):
            fit_breakpoints(f, psd, count)  # warm
            times = []
            for _ in range(args.repeat):
                t0 = time.perf_counter()
                table = fit_breakpoints(f, psd, count)
                times.append(time.perf_counter() - t0)
            db, off = shape_figures(f, psd, table)
            print(f"{fs:>6g} {f.size:>5} {count:>3} {1e3 * np.median(times):>10.2f} "
                  f"{1e3 * max(times):>8.2f} {db:>9.2f} {100 * off:>8.1f}%")


if __name__ == "__main__":
    main()
