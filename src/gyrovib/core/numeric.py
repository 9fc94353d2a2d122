"""Brute force of the vibration error: averaging eq. (2) itself (docs/model.md section 7;
docs/numeric.md gives the schemes' reasons and measurements).

No closed form is used here. For every sensor the conversion function of
eq. (2), in rate units,

    Ω_F3(ω) = k0 + k1·(1 + 0.5·A1·sign ω3)·ω3 + Σ_{n=2..5} kn·ω3ⁿ
              + Σ_{i=1,2} mi·ωi + Σ_{i=1,2} m3i·ω3·ωi                     (2)

is evaluated on the rates ``ωi = Ω_Ki + x_i`` seen by the sensor, averaged
over the vibration, and the output at rest ``Ω_F3(Ω_K)`` (same carrier rate, no
vibration) is subtracted (eq. 12, 13):

    Δ_V = <Ω_F3(Ω_K + x)> − Ω_F3(Ω_K)

The vibration ``x`` is drawn from :class:`~gyrovib.core.statistics.Vibration`:
tones ``x_i = Σ_k a_ik·sin(θ_k + φ_ik)`` (``a_ik·exp(jφ_ik)`` the phasor of tone k on
axis i); a Gaussian part ``x3 = σ3·z3``, ``xi = σi·(ρ3i·z3 + √(1 − ρ3i²)·zi)`` from
independent standard normals z; phase-locked groups (docs/model.md section 10)
``x_i = Σ_n |p_ni|·sin(n·θ_g + arg p_ni)``, one phase θ_g each.

Schemes, chosen from the vibration and ``samples`` (evaluations of eq. (2) per sensor):
``grid`` (tones and locked groups only: the mean of 16 randomly shifted product grids of
phases, ``stderr`` their standard deviation over √16, 0 where the rule is exact),
``monte-carlo`` (antithetic pairs ``x``, ``−x``; a locked group's θ_g is shared by the
pair, not negated) and ``none`` (0 exactly). A linear vibration (docs/model.md section 8)
adds the exact average of ``Σ_{j≤k} G_jk·a_j·a_k`` (4 phases per tone, 3-point
Gauss–Hermite per Gaussian axis) to every estimate.

The samples are shared by all sensors and drawn in fixed-size blocks, so a sensor's
estimate does not depend on which others are evaluated with it. Units: whatever rate
unit the coefficients, ``rate`` and the vibration share (gyrovib uses deg/s).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import COEFFICIENTS, COLUMN, Multipliers
from gyrovib.core.harmonics import LockedGroup, group_signal, locked_peak
from gyrovib.core.linear import PAIRS, LinearVibration
from gyrovib.core.statistics import Vibration
from gyrovib.frozen import Frozen
from gyrovib.limits import MIN_SAMPLES

#: Evaluation points per block of the sample stream (fixed: results must not
#: depend on how many sensors share the samples).
BLOCK = 1 << 15
#: Upper bound on the elements of one (sensors × points) array.
MAX_ELEMENTS = 1 << 20
#: Fewest nodes per tone of a product grid: > 5 makes it exact for eq. (2)'s polynomial.
MIN_GRID_NODES = 6
#: Independently shifted copies of the phase grid (their spread gives the stderr):
#: two points each at the fewest samples accepted (:data:`gyrovib.limits.MIN_SAMPLES`).
REPLICATES = MIN_SAMPLES // 2

Progress = Callable[[int], None]


@dataclass(frozen=True, eq=False, repr=False)
class NumericEstimate(Frozen):
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

    def __init__(self, omega3: float, odd: bool = False,
                 acceleration: FloatArray | None = None) -> None:
        self.omega3 = omega3
        self.odd = odd
        self.acceleration = acceleration
        self.sums = np.zeros(7)
        self.count = 0

    def add(self, x: FloatArray) -> None:
        x3 = x[2]
        self.sums += [
            np.sum(np.abs(self.omega3 + x3)),
            np.sum(x3 * x3),
            np.sum(x3**4),
            np.sum(x3 * x[0]),
            np.sum(x3 * x[1]),
            np.sum(x3**3),
            np.sum(x3**5),
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
            m3=scalar(mean[5]) if self.odd else None,
            m5=scalar(mean[6]) if self.odd else None,
            acceleration=self.acceleration,
        )


def _sensor_chunk(points: int) -> int:
    return max(1, MAX_ELEMENTS // max(points, 1))


def _grid_counts(n_tones: int, samples: int) -> int | None:
    """Nodes per tone of the product grid, or None when it would be too coarse."""
    m = round(samples ** (1.0 / n_tones)) + 1
    while m**n_tones > samples:
        m -= 1
    return m if m >= MIN_GRID_NODES else None


def _signals(phasors: NDArray[np.complex128], groups: Sequence[LockedGroup],
             theta: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(independent tones, locked groups) rates, each (3, n), for phases θ (n, K + G)."""
    k = phasors.shape[0]
    tones = _tones(phasors, theta[:, :k]) if k else np.zeros((3, theta.shape[0]))
    locked = np.zeros((3, theta.shape[0]))
    for g_index, g in enumerate(groups):
        locked += group_signal(g.orders, g.phasors, theta[:, k + g_index])
    return tones, locked


def linear_average(g2_sensitivity: ArrayLike, linear: LinearVibration) -> tuple[FloatArray,
                                                                              FloatArray]:
    """Brute-force ``<Σ_{j≤k} G_jk·a_j·a_k>`` (rate, (sensors,)) and the six ⟨a_j·a_k⟩ (g²).

    Product grid of 4 phases per tone × 3-point Gauss–Hermite nodes per axis of
    the correlated Gaussian part: exact for these quadratics (module docstring).
    """
    g = np.asarray(g2_sensitivity, dtype=float)
    amp = linear.amplitudes
    p: NDArray[np.complex128] = (amp * np.exp(1j * np.deg2rad(linear.phases))).astype(complex)
    keep = np.any(amp > 0, axis=1)
    p = p[keep]
    # tones: product grid of 4 phases each
    if p.shape[0]:
        axis = 2.0 * math.pi * np.arange(4) / 4
        mesh = np.meshgrid(*([axis] * p.shape[0]), indexing="ij")
        theta = np.stack([m.ravel() for m in mesh], axis=1)
        tones = _tones(p, theta)
    else:
        tones = np.zeros((3, 1))
    # Gaussian: 3-point Gauss–Hermite (probabilists'): nodes 0, ±√3, weights 2/3, 1/6
    cov = linear.covariance()
    vals, vecs = np.linalg.eigh(cov)
    if np.any(vals < -1e-12 * max(1.0, float(np.max(np.abs(vals))))):
        raise ValueError("the coherences do not form a valid correlation matrix")
    root = vecs * np.sqrt(np.clip(vals, 0.0, None))
    nodes = np.array([-math.sqrt(3.0), 0.0, math.sqrt(3.0)])
    weights = np.array([1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0])
    z = np.stack([m.ravel() for m in np.meshgrid(nodes, nodes, nodes, indexing="ij")])
    wz = np.prod(np.stack([m.ravel() for m in np.meshgrid(weights, weights, weights,
                                                           indexing="ij")]), axis=0)
    gauss = root @ z  # (3, 27)
    a = tones[:, :, None] + gauss[:, None, :]  # (3, T, 27)
    weight = np.broadcast_to(wz[None, :] / tones.shape[1], a.shape[1:])
    moments = np.array([np.sum(weight * a[j] * a[k]) for j, k in PAIRS])
    total: FloatArray = g @ moments
    return total, moments


def simulate(
    coefficients: ArrayLike,
    vibration: Vibration,
    rate: ArrayLike,
    *,
    samples: int,
    rng: np.random.Generator,
    progress: Progress | None = None,
    locked: Sequence[LockedGroup] = (),
    linear: LinearVibration | None = None,
    g2_sensitivity: ArrayLike | None = None,
) -> NumericEstimate:
    """Brute-force Δ_V of eq. (13) by averaging eq. (2) over the vibration.

    ``coefficients``: (sensors, 11), ``rate``: Ω_K (3,), same rate unit as the
    vibration. ``samples``: evaluations of eq. (2) per sensor (at least 16).
    ``rng``: the only source of randomness (grid shifts, phases, normals).
    ``progress`` is called with the number of points evaluated after each block.
    ``locked``: phase-locked harmonic groups (rate units at the sensor);
    ``linear`` with ``g2_sensitivity`` (sensors, 6) in rate/g²: the g² term of
    a linear vibration (docs/model.md section 8).
    """
    estimate = _angular(coefficients, vibration, rate, samples, rng, progress, list(locked))
    if linear is None:
        return estimate
    n = estimate.total.shape[0]
    g = np.zeros((n, 6)) if g2_sensitivity is None else np.asarray(g2_sensitivity, dtype=float)
    if g.shape != (n, 6):
        raise ValueError("g2_sensitivity must have shape (sensors, 6)")
    extra, moments = linear_average(g, linear)
    mu = estimate.multipliers
    return NumericEstimate(
        total=estimate.total + extra, stderr=estimate.stderr,
        multipliers=Multipliers(asymmetry=mu.asymmetry, m2=mu.m2, m4=mu.m4, c31=mu.c31,
                                c32=mu.c32, omega=mu.omega, m3=mu.m3, m5=mu.m5,
                                acceleration=moments),
        scheme=estimate.scheme, points=estimate.points)


def _angular(coefficients: ArrayLike, vibration: Vibration, rate: ArrayLike, samples: int,
             rng: np.random.Generator, progress: Progress | None,
             groups: list[LockedGroup]) -> NumericEstimate:
    """The angular part of :func:`simulate`."""
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
    groups = [g for g in groups if np.any(np.abs(g.phasors) > 0)]
    moments = _Moments(float(omega[2]), odd=bool(groups))
    n_sensors = c.shape[0]

    if phasors.shape[0] == 0 and not random and not groups:
        moments.add(np.zeros((3, 1)))
        if progress is not None:
            progress(samples)
        zero = np.zeros(n_sensors)
        return NumericEstimate(zero, zero.copy(), moments.multipliers(), "none", 1)

    dims = phasors.shape[0] + len(groups)
    m = None if random else _grid_counts(dims, samples // REPLICATES)
    if m is not None:
        counts = [m] * phasors.shape[0] + [max(m, 5 * g.n_max + 1) for g in groups]
        if math.prod(counts) <= max(samples // REPLICATES, 1):
            return _grid(c, phasors, groups, omega, rest, counts, rng, moments, progress)
    return _monte_carlo(c, phasors, groups, sigma, vibration.coherence, omega, rest, samples,
                        rng, moments, progress)


def _grid(c: FloatArray, phasors: NDArray[np.complex128], groups: list[LockedGroup],
          omega: FloatArray, rest: FloatArray, counts: list[int], rng: np.random.Generator,
          moments: _Moments, progress: Progress | None) -> NumericEstimate:
    """Randomly shifted product grids over the tones' phases (see the module docstring)."""
    m = np.asarray(counts, dtype=float)
    per_grid = math.prod(counts)
    shape = tuple(counts)
    replicate_means = np.zeros((c.shape[0], REPLICATES))
    for r in range(REPLICATES):
        shift = np.asarray(rng.uniform(0.0, 2.0 * math.pi / m), dtype=float)
        for start in range(0, per_grid, BLOCK):
            flat = np.arange(start, min(start + BLOCK, per_grid))
            index = np.stack(np.unravel_index(flat, shape), axis=1)  # (n, K + G)
            tones, locked = _signals(phasors, groups,
                                     2.0 * math.pi * index / m[None, :] + shift[None, :])
            x = tones + locked
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
    reach = float(np.sum(np.abs(phasors[:, 2]))) + sum(
        locked_peak(g.orders, g.phasors[:, 2]) for g in groups)
    exact = (c[:, COLUMN["k1"]] * c[:, COLUMN["A1"]] == 0) | (abs(omega[2]) >= reach)
    stderr = np.where(exact, 0.0, spread)
    return NumericEstimate(estimate, stderr, moments.multipliers(), "grid",
                           per_grid * REPLICATES)


def _monte_carlo(c: FloatArray, phasors: NDArray[np.complex128], groups: list[LockedGroup],
                 sigma: FloatArray,
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
        locked = np.zeros((3, n))
        if n_tones or groups:
            theta = rng.uniform(0.0, 2.0 * math.pi, size=(n, n_tones + len(groups)))
            x, locked = _signals(phasors, groups, theta)
        if np.any(sigma > 0):
            x += _correlate(rng.standard_normal(size=(3, n)), sigma, coherence)
        moments.add(locked + x)
        moments.add(locked - x)
        w_plus = omega[:, None] + locked + x
        w_minus = omega[:, None] + locked - x
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
