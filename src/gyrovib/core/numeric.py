"""Brute force of the vibration error: averaging eq. (2) itself (docs/model.md).

No closed form is used here. For every sensor the conversion function of
eq. (2), in rate units,

    Ω_F3(ω) = k0 + k1·(1 + 0.5·A1·sign ω3)·ω3 + Σ_{n=2..5} kn·ω3ⁿ
              + Σ_{i=1,2} mi·ωi + Σ_{i=1,2} m3i·ω3·ωi                     (2)

is evaluated on the rates ``ωi = Ω_Ki + x_i`` seen by the sensor, averaged
over the vibration, and the output at rest ``Ω_F3(Ω_K)`` (same carrier rate, no
vibration) is subtracted (eq. 12, 13):

    Δ_V = <Ω_F3(Ω_K + x)> − Ω_F3(Ω_K)

The vibration ``x`` is drawn from :class:`~gyrovib.core.statistics.Vibration`:

* tones, ``x_i = Σ_k a_ik·sin(θ_k + φ_ik)`` with ``a_ik·exp(jφ_ik)`` the phasor
  of tone k on axis i, averaged over the phases θ_k;
* a Gaussian part with per-axis σ_i and coherence ρ_3i, built as
  ``x3 = σ3·z3``, ``xi = σi·(ρ3i·z3 + √(1 − ρ3i²)·zi)`` from independent
  standard normals z (docs/model.md gives only the 3–i correlations; this choice
  makes x1 and x2 correlate only through x3).

Schemes, chosen from the vibration and the sample budget ``samples`` (the
number of points at which eq. (2) is evaluated per sensor):

``grid``
    Tones only, and 16 product grids of phases θ_k = 2πj/m + u_k with m ≥ 6
    nodes per tone fit in ``samples``; each grid has its own uniform random
    shift u_k ∈ [0, 2π/m), so each grid average is unbiased. The rule is exact
    for the polynomial part of eq. (2) (a trigonometric polynomial of degree
    ≤ 5 in each θ_k, whatever the shift); only the ``|ω3|`` asymmetry term
    varies between grids. The estimate is the mean of the 16 grid averages and
    ``stderr`` their standard deviation over √16; it is 0 where the rule is
    exact: ``k1·A1 = 0`` or ``|Ω_K3| ≥ Σ_k a_3k`` (ω3 never changes sign).
    (A fixed grid compared with its half-grid was tried first: for several
    tones that difference understated the true error by up to 2.5×, because
    the error of a kinked integrand does not fall smoothly with m.)
``monte-carlo``
    Random tone phases (uniform) and/or Gaussian samples, in antithetic pairs
    ``x`` and ``−x`` (phases θ + π, normals −z): both are equally likely, so
    the pair mean is unbiased and every odd term of eq. (2) cancels exactly
    within a pair. ``stderr`` is the sample standard deviation of the pair
    means over √pairs.
``none``
    No vibration reaches x1..x3: the error is 0 exactly.

The samples are shared by all sensors and drawn in fixed-size blocks, so a
sensor's estimate does not depend on which other sensors are evaluated with
it; eq. (2) is evaluated as a (sensors × samples) array in chunks of bounded
size. Units: whatever rate unit the coefficients, ``rate`` and the vibration
share (gyrovib uses deg/s).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core.analysis import COEFFICIENTS, COLUMN, Multipliers
from gyrovib.core.statistics import Vibration
from gyrovib.core.transmissibility import FloatArray

#: Evaluation points per block of the sample stream (fixed: results must not
#: depend on how many sensors share the samples).
BLOCK = 1 << 15
#: Upper bound on the elements of one (sensors × points) array.
MAX_ELEMENTS = 1 << 20
#: Fewest nodes per tone of a product grid: > 5 makes it exact for eq. (2)'s polynomial.
MIN_GRID_NODES = 6
#: Independently shifted copies of the phase grid (their spread gives the stderr).
REPLICATES = 16
#: Fewest evaluation points accepted.
MIN_SAMPLES = 2 * REPLICATES

Progress = Callable[[int], None]


@dataclass(frozen=True)
class NumericEstimate:
    """Brute-force vibration error of several sensors under one vibration.

    ``total`` (sensors,): Δ_V, the average of eq. (2) minus eq. (2) at rest.
    ``stderr`` (sensors,): its standard error (0 where the scheme is exact).
    ``multipliers``: the sample moments of the same points (``<x3²>``,
    ``<x3⁴>``, ``<x3·xi>``, ``½(<|Ω+x3|> − |Ω|)``), shape (), so that
    :func:`gyrovib.core.analysis.vibration_error` gives the term breakdown.
    ``scheme``: ``"grid"``, ``"monte-carlo"`` or ``"none"``; ``points``: the
    number of evaluations of eq. (2) per sensor.
    """

    total: FloatArray
    stderr: FloatArray
    multipliers: Multipliers
    scheme: str
    points: int


def conversion(coefficients: ArrayLike, omega: ArrayLike) -> FloatArray:
    """Eq. (2), ``Ω_F3(ω)``, for every sensor at every rate point.

    ``coefficients``: (sensors, 11) in the order of ``COEFFICIENTS``;
    ``omega``: (3, points), the rates ω1, ω2, ω3. Returns (sensors, points).
    """
    c = np.asarray(coefficients, dtype=float)
    w = np.asarray(omega, dtype=float)
    if c.ndim != 2 or c.shape[1] != len(COEFFICIENTS):
        raise ValueError(f"coefficients must have shape (n, {len(COEFFICIENTS)})")
    w1, w2, w3 = w[0][None, :], w[1][None, :], w[2][None, :]

    def k(name: str) -> FloatArray:
        out: FloatArray = c[:, COLUMN[name]][:, None]
        return out

    out: FloatArray = (
        k("k0")
        + k("k1") * (1.0 + 0.5 * k("A1") * np.sign(w3)) * w3
        + w3 * w3 * (k("k2") + w3 * (k("k3") + w3 * (k("k4") + w3 * k("k5"))))
        + k("m1") * w1
        + k("m2") * w2
        + w3 * (k("m31") * w1 + k("m32") * w2)
    )
    return out


def _correlate(z: FloatArray, sigma: FloatArray, coherence: FloatArray) -> FloatArray:
    """Gaussian rates (3, n) from standard normals z (3, n): see the module docstring."""
    rho = np.clip(coherence, -1.0, 1.0)
    x3 = sigma[2] * z[2]
    x1 = sigma[0] * (rho[0] * z[2] + math.sqrt(1.0 - rho[0] ** 2) * z[0])
    x2 = sigma[1] * (rho[1] * z[2] + math.sqrt(1.0 - rho[1] ** 2) * z[1])
    return np.stack([x1, x2, x3])


def _tones(phasors: NDArray[np.complex128], theta: FloatArray) -> FloatArray:
    """``x_i = Σ_k |p_ik|·sin(θ_k + arg p_ik)`` for phases θ (n, K); returns (3, n)."""
    out: FloatArray = (np.sin(theta) @ phasors.real + np.cos(theta) @ phasors.imag).T
    return out


class _Moments:
    """Running sums of the sample moments behind the term breakdown."""

    def __init__(self, omega3: float) -> None:
        self.omega3 = omega3
        self.sums = np.zeros(5)
        self.count = 0

    def add(self, x: FloatArray) -> None:
        x3 = x[2]
        self.sums += [
            np.sum(np.abs(self.omega3 + x3)),
            np.sum(x3 * x3),
            np.sum(x3**4),
            np.sum(x3 * x[0]),
            np.sum(x3 * x[1]),
        ]
        self.count += x.shape[1]

    def multipliers(self) -> Multipliers:
        mean = self.sums / max(self.count, 1)

        def scalar(value: float) -> FloatArray:
            return np.asarray(float(value))

        return Multipliers(
            asymmetry=scalar(0.5 * (mean[0] - abs(self.omega3)) if self.count else 0.0),
            m2=scalar(mean[1]),
            m4=scalar(mean[2]),
            c31=scalar(mean[3]),
            c32=scalar(mean[4]),
            omega=scalar(self.omega3),
        )


def _sensor_chunk(points: int) -> int:
    return max(1, MAX_ELEMENTS // max(points, 1))


def _grid_counts(n_tones: int, samples: int) -> int | None:
    """Nodes per tone of the product grid, or None when it would be too coarse."""
    m = round(samples ** (1.0 / n_tones)) + 1
    while m**n_tones > samples:
        m -= 1
    return m if m >= MIN_GRID_NODES else None


def simulate(
    coefficients: ArrayLike,
    vibration: Vibration,
    rate: ArrayLike,
    *,
    samples: int,
    rng: np.random.Generator,
    progress: Progress | None = None,
) -> NumericEstimate:
    """Brute-force Δ_V of eq. (13) by averaging eq. (2) over the vibration.

    ``coefficients``: (sensors, 11), ``rate``: Ω_K (3,), same rate unit as the
    vibration. ``samples``: evaluations of eq. (2) per sensor (at least 16).
    ``rng``: the only source of randomness (grid shifts, phases, normals).
    ``progress`` is called with the number of points evaluated after each block.
    """
    c = np.asarray(coefficients, dtype=float)
    if c.ndim != 2 or c.shape[1] != len(COEFFICIENTS):
        raise ValueError(f"coefficients must have shape (n, {len(COEFFICIENTS)})")
    if samples < MIN_SAMPLES:
        raise ValueError(f"samples must be at least {MIN_SAMPLES}")
    omega = np.asarray(rate, dtype=float).reshape(3)
    phasors = vibration.phasors[np.any(np.abs(vibration.phasors) > 0, axis=1)]
    sigma = np.asarray(vibration.sigma, dtype=float)
    random = bool(np.any(sigma > 0))
    rest = conversion(c, omega[:, None])[:, 0]
    moments = _Moments(float(omega[2]))
    n_sensors = c.shape[0]

    if phasors.shape[0] == 0 and not random:
        moments.add(np.zeros((3, 1)))
        if progress is not None:
            progress(samples)
        zero = np.zeros(n_sensors)
        return NumericEstimate(zero, zero.copy(), moments.multipliers(), "none", 1)

    m = None if random else _grid_counts(phasors.shape[0], samples // REPLICATES)
    if m is not None:
        return _grid(c, phasors, omega, rest, m, rng, moments, progress)
    return _monte_carlo(c, phasors, sigma, vibration.coherence, omega, rest, samples, rng,
                        moments, progress)


def _grid(c: FloatArray, phasors: NDArray[np.complex128], omega: FloatArray, rest: FloatArray,
          m: int, rng: np.random.Generator, moments: _Moments,
          progress: Progress | None) -> NumericEstimate:
    """Randomly shifted product grids over the tones' phases (see the module docstring)."""
    n_tones = phasors.shape[0]
    per_grid = m**n_tones
    shape = (m,) * n_tones
    replicate_means = np.zeros((c.shape[0], REPLICATES))
    for r in range(REPLICATES):
        shift = np.asarray(rng.uniform(0.0, 2.0 * math.pi / m, size=n_tones), dtype=float)
        for start in range(0, per_grid, BLOCK):
            flat = np.arange(start, min(start + BLOCK, per_grid))
            index = np.stack(np.unravel_index(flat, shape), axis=1)  # (n, K)
            x = _tones(phasors, 2.0 * math.pi * index / m + shift[None, :])
            moments.add(x)
            w = omega[:, None] + x
            step = _sensor_chunk(w.shape[1])
            for s in range(0, c.shape[0], step):
                d = conversion(c[s : s + step], w) - rest[s : s + step, None]
                replicate_means[s : s + step, r] += d.sum(axis=1)
            if progress is not None:
                progress(flat.size)
    replicate_means /= per_grid
    estimate = replicate_means.mean(axis=1)
    spread = replicate_means.std(axis=1, ddof=1) / math.sqrt(REPLICATES)
    reach = float(np.sum(np.abs(phasors[:, 2])))
    exact = (c[:, COLUMN["k1"]] * c[:, COLUMN["A1"]] == 0) | (abs(omega[2]) >= reach)
    stderr = np.where(exact, 0.0, spread)
    return NumericEstimate(estimate, stderr, moments.multipliers(), "grid",
                           per_grid * REPLICATES)


def _monte_carlo(c: FloatArray, phasors: NDArray[np.complex128], sigma: FloatArray,
                 coherence: FloatArray, omega: FloatArray, rest: FloatArray, samples: int,
                 rng: np.random.Generator, moments: _Moments,
                 progress: Progress | None) -> NumericEstimate:
    """Antithetic Monte Carlo over random phases and Gaussian samples."""
    n_tones = phasors.shape[0]
    pairs = max(2, samples // 2)
    n_sensors = c.shape[0]
    # Chan et al. pairwise update of mean and sum of squared deviations, per sensor.
    mean = np.zeros(n_sensors)
    m2 = np.zeros(n_sensors)
    count = 0
    block_pairs = BLOCK // 2
    for start in range(0, pairs, block_pairs):
        n = min(block_pairs, pairs - start)
        x = np.zeros((3, n))
        if n_tones:
            x += _tones(phasors, rng.uniform(0.0, 2.0 * math.pi, size=(n, n_tones)))
        if np.any(sigma > 0):
            x += _correlate(rng.standard_normal(size=(3, n)), sigma, coherence)
        moments.add(x)
        moments.add(-x)
        w_plus = omega[:, None] + x
        w_minus = omega[:, None] - x
        step = _sensor_chunk(2 * n)
        for s in range(0, n_sensors, step):
            sl = slice(s, s + step)
            pair = 0.5 * (conversion(c[sl], w_plus) + conversion(c[sl], w_minus)) - rest[sl, None]
            b_mean = pair.mean(axis=1)
            b_m2 = np.sum((pair - b_mean[:, None]) ** 2, axis=1)
            delta = b_mean - mean[sl]
            total = count + n
            mean[sl] = mean[sl] + delta * (n / total)
            m2[sl] = m2[sl] + b_m2 + delta**2 * (count * n / total)
        count += n
        if progress is not None:
            progress(2 * n)
    stderr = np.sqrt(m2 / (count - 1) / count)
    return NumericEstimate(mean, stderr, moments.multipliers(), "monte-carlo", 2 * pairs)
