"""An independent brute-force evaluation of docs/model.md, for the tests.

It averages the conversion function eq. (2) itself over the vibration and
subtracts eq. (2) at rest (docs/model.md). Nothing here uses gyrovib's
closed forms:

* the polynomial and cross terms are averaged over a uniform grid of tone
  phases (16 per tone: exact for trigonometric polynomials of degree < 16)
  and Gauss-Hermite nodes for the Gaussian part (exact to degree 2n-1);
* the asymmetry term |ω3| has a kink, so its average is taken with adaptive
  quadrature (scipy.integrate.quad) split at the kink, over the arcsine law
  of a tone's value and/or the normal law of the Gaussian part, with a
  uniform phase grid over any further tones.
"""

from __future__ import annotations

import itertools
import math
import warnings
from collections.abc import Mapping, Sequence

import numpy as np
from scipy import integrate

COEFFS = ("k0", "k1", "A1", "k2", "k3", "k4", "k5", "m1", "m2", "m31", "m32")


def conversion(c: Mapping[str, float], w1, w2, w3):
    """Eq. (2): Ω_F3 for rates ω1, ω2, ω3 (arrays)."""
    k = {name: c.get(name, 1.0 if name == "k1" else 0.0) for name in COEFFS}
    return (
        k["k0"]
        + k["k1"] * (1 + 0.5 * k["A1"] * np.sign(w3)) * w3
        + k["k2"] * w3**2 + k["k3"] * w3**3 + k["k4"] * w3**4 + k["k5"] * w3**5
        + k["m1"] * w1 + k["m2"] * w2 + k["m31"] * w3 * w1 + k["m32"] * w3 * w2
    )


def _tone_samples(tones: Sequence[tuple[Sequence[float], Sequence[float]]], n: int):
    """x (3, N) over the product grid of n uniform phases per tone; weights 1/N."""
    if not tones:
        return np.zeros((3, 1))
    grids = [2 * math.pi * (np.arange(n) + 0.5) / n for _ in tones]
    mesh = np.array(list(itertools.product(*grids))).T  # (K, N)
    x = np.zeros((3, mesh.shape[1]))
    for k, (amp, phase) in enumerate(tones):
        for axis in range(3):
            x[axis] += amp[axis] * np.sin(mesh[k] + math.radians(phase[axis]))
    return x


def _gauss_samples(sigma: Sequence[float], rho: Sequence[float], n: int = 8):
    """Gaussian x (3, M) with weights (M,), x3 = σ3 z3, xi = σi(ρ z3 + √(1−ρ²) zi)."""
    z, w = np.polynomial.hermite_e.hermegauss(n)
    w = w / w.sum()
    z3, z1, z2 = (a.ravel() for a in np.meshgrid(z, z, z, indexing="ij"))
    weight = np.einsum("i,j,k->ijk", w, w, w).ravel()
    s1, s2, s3 = sigma
    r1, r2 = rho
    x = np.array([
        s1 * (r1 * z3 + math.sqrt(max(0.0, 1 - r1 * r1)) * z1),
        s2 * (r2 * z3 + math.sqrt(max(0.0, 1 - r2 * r2)) * z2),
        s3 * z3,
    ])
    return x, weight


def _mean_abs_tone(y: float, a: float) -> float:
    """<|y + a·sin θ|> by quadrature over the arcsine law of u = a·sin θ."""
    if a == 0:
        return abs(y)
    f = lambda u: abs(y + u)  # noqa: E731
    pts = [-y] if -a < -y < a else []
    edges = [-a, *pts, a]
    total = 0.0
    for lo, hi in itertools.pairwise(edges):
        # u = a·sin θ over θ in [-π/2, π/2] covers the arcsine law once
        val, _ = integrate.quad(
            lambda t: f(a * math.sin(t)), math.asin(lo / a), math.asin(hi / a),
            epsabs=1e-14, epsrel=1e-13, limit=200,
        )
        total += val
    return total / math.pi


def _mean_abs_gauss(y: float, s: float) -> float:
    """<|y + s·Z|> by quadrature over the normal law on [-40, 40], split at the kink."""
    if s == 0:
        return abs(y)
    pdf = lambda z: math.exp(-0.5 * z * z) / math.sqrt(2 * math.pi)  # noqa: E731
    kink = min(max(-y / s, -40.0), 40.0)
    edges = sorted({-40.0, kink, 0.0, 40.0})
    total = 0.0
    for lo, hi in itertools.pairwise(edges):
        sign = 1.0 if y + s * 0.5 * (lo + hi) >= 0 else -1.0
        val, _ = integrate.quad(lambda z, sign=sign: sign * (y + s * z) * pdf(z), lo, hi,
                                epsabs=1e-16, epsrel=1e-13, limit=200)
        total += val
    return total


def mean_abs(omega3: float, amplitudes: Sequence[float], sigma3: float, n_grid: int = 64) -> float:
    """<|Ω + x3|> for tones of ``amplitudes`` (independent phases) plus Gaussian σ3."""
    amps = [a for a in amplitudes if a > 0]
    if not amps:
        return _mean_abs_gauss(omega3, sigma3)
    if sigma3 > 0:
        shifts = _tone_samples([((0, 0, a), (0, 0, 0)) for a in amps], n_grid)[2]
        return float(np.mean([_mean_abs_gauss(omega3 + s, sigma3) for s in shifts]))
    last, others = amps[-1], amps[:-1]
    shifts = _tone_samples([((0, 0, a), (0, 0, 0)) for a in others], n_grid)[2]
    return float(np.mean([_mean_abs_tone(omega3 + s, last) for s in shifts]))


def vibration_error(
    coefficients: Mapping[str, float],
    omega: Sequence[float],
    tones: Sequence[tuple[Sequence[float], Sequence[float]]] = (),
    sigma: Sequence[float] = (0.0, 0.0, 0.0),
    rho: Sequence[float] = (1.0, 1.0),
    n_grid: int = 64,
) -> float:
    """Δ_V: <eq. (2)> − eq. (2) at rest, by brute force.

    ``tones``: (amplitude per axis, phase per axis in degrees) at the sensor,
    of distinct frequencies. ``sigma``/``rho``: the Gaussian part at the sensor.
    """
    c = dict(coefficients)
    a1 = c.pop("A1", 0.0)
    xt = _tone_samples(tones, 16)
    xg, wg = _gauss_samples(sigma, rho)
    x = xt[:, :, None] + xg[:, None, :]
    weight = np.broadcast_to(wg[None, :] / xt.shape[1], x.shape[1:])
    w1, w2, w3 = (omega[i] + x[i] for i in range(3))
    poly = float(np.sum(weight * conversion(c, w1, w2, w3)))
    rest = float(conversion(c, np.array(omega[0]), np.array(omega[1]), np.array(omega[2])))
    k1 = c.get("k1", 1.0)
    amps3 = [math.hypot(0, a[2]) for a, _ in tones]
    asym = 0.5 * k1 * a1 * (mean_abs(omega[2], amps3, sigma[2], n_grid) - abs(omega[2]))
    return poly - rest + asym


# ---------------------------------------------------------------- E(Ω) to ~1e-13
#
# Nested adaptive quadrature over the tones' phases, each level split where its
# integrand has a kink, with the one-tone excess in closed form innermost (tones
# only) or the folded-normal excess (with a Gaussian part) written without
# subtraction, so that tiny tail values keep their relative precision.


def _signed_tone_excess(m: float, a: float) -> float:
    """<|m + a·sin θ|> − m for a signed m (0 for m ≥ a, −2m for m ≤ −a)."""
    if m >= a:
        return 0.0
    if m <= -a:
        return -2.0 * m
    return (2 / math.pi) * (m * math.asin(m / a) + math.sqrt(a * a - m * m)) - m


def _signed_gauss_excess(m: float, s: float) -> float:
    """<|m + s·Z|> − m = 2·E[(−(m + sZ))⁺] for a signed m."""
    from scipy import special

    u = m / (s * math.sqrt(2))
    return s * math.sqrt(2 / math.pi) * math.exp(-u * u) - m * special.erfc(u)


def _phase_mean(f, c: float, a: float, kinks: Sequence[float], epsrel: float = 1e-13) -> float:
    """(1/π)∫ f(c + a·sin θ) dθ over [−π/2, π/2], split where the argument hits a kink."""
    cuts = sorted(math.asin((k - c) / a) for k in kinks if -1 < (k - c) / a < 1)
    edges = [-math.pi / 2, *cuts, math.pi / 2]
    total = 0.0
    with warnings.catch_warnings():  # quad's round-off notes at this tolerance
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        for lo, hi in itertools.pairwise(edges):
            val, _ = integrate.quad(lambda t: f(c + a * math.sin(t)), lo, hi,
                                    epsabs=0, epsrel=epsrel, limit=200)
            total += val
    return total / math.pi


def excess(omega: float, amplitudes: Sequence[float], sigma: float,
           epsrel: float = 1e-13) -> float:
    """E(Ω) = <|Ω + x3|> − |Ω| for up to three tones (tones only) or one or two
    tones plus a Gaussian part, by nested quadrature (``epsrel`` per level)."""
    w = abs(omega)
    amps = sorted((a for a in amplitudes if a > 0), reverse=True)
    if sigma > 0:
        if len(amps) == 1:
            return _phase_mean(lambda m: _signed_gauss_excess(m, sigma), w, amps[0], [])
        a1, a2 = amps
        return _phase_mean(
            lambda c: _phase_mean(lambda m: _signed_gauss_excess(m, sigma), c, a2, []),
            w, a1, [])
    a1 = amps[0]
    if len(amps) == 2:
        return _phase_mean(lambda m: _signed_tone_excess(m, a1), w, amps[1], [-a1, a1],
                           epsrel)
    a2, a3 = amps[1], amps[2]
    return _phase_mean(
        lambda c: _phase_mean(lambda m: _signed_tone_excess(m, a1), c, a2, [-a1, a1], epsrel),
        w, a3, [-a1 - a2, -a1 + a2, a1 - a2, a1 + a2], epsrel)


# ------------------------------------------------- E(Ω) for many tones, two ways
#
# Independent of gyrovib's contour integral: docs/model.md section 4's real-axis
# form by QUADPACK's Fourier-integral routine (QAWF), good where E is not tiny,
# and the phase average of the folded-normal excess on a product grid of
# phases (brute force of eq. (2) averaged over the tones' phases; spectral for
# a Gaussian part, so also good in the far tail).


def excess_characteristic(omega: float, amplitudes: Sequence[float], sigma: float) -> float:
    """E(Ω) = (2/π)∫₀^∞ cos(Ωt)·(1 − Π J0(a t)·exp(−σ²t²/2))/t² dt, Ω ≠ 0 (docs/model.md §4:
    ⟨|Ω + X|⟩ − |Ω| with the 1 − cos(Ωt) of |Ω| subtracted under the integral)."""
    from scipy import special

    a = np.asarray(amplitudes, dtype=float)
    m2 = float(np.sum(a * a) / 2 + sigma * sigma)

    def f(t: float) -> float:
        if t < 1e-6:  # (1 − φ(t))/t² → M2/2
            return m2 / 2
        phi = float(np.prod(special.j0(a * t))) * math.exp(-0.5 * sigma * sigma * t * t)
        return (1.0 - phi) / (t * t)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        val, _ = integrate.quad(f, 0, np.inf, weight="cos", wvar=abs(omega), limlst=200,
                                epsabs=1e-13)  # 1e-15 trips QAWF's round-off exit
    return 2 / math.pi * val


def excess_phase_grid(omega: float, amplitudes: Sequence[float], sigma: float, n: int) -> float:
    """E(Ω) = ⟨2·E[(−(|Ω| + s + σZ))⁺]⟩ over n uniform phases per tone (s = Σ a sin θ).

    The folded-normal excess is written without subtraction, so tiny tail
    values keep their relative precision; the midpoint rule on a period
    converges geometrically for this analytic integrand."""
    from scipy import special

    shifts = np.zeros(1)
    theta = 2 * math.pi * (np.arange(n) + 0.5) / n
    for a in amplitudes:
        shifts = (shifts[:, None] + a * np.sin(theta)[None, :]).ravel()
    m = abs(omega) + shifts
    u = m / (sigma * math.sqrt(2))
    kernel = sigma * math.sqrt(2 / math.pi) * np.exp(-u * u) - m * special.erfc(u)
    return float(np.mean(kernel))


def excess_four_tones(omega: float, amplitudes: Sequence[float]) -> float:
    """E(Ω) for four tones alone: the smallest tone's phase by adaptive quadrature
    (split where the three-tone excess has kinks, ±a1 ± a2 ± a3) over :func:`excess`.

    Three nested levels, each to 1e-10 relative (1e-13 took ten times longer, 12 s for
    Ω = 3.6 of (1.5, 1.2, 0.7, 0.3), and changed the result by 1e-13 relative)."""
    a1, a2, a3, a4 = sorted(amplitudes, reverse=True)
    kinks = sorted({x * a1 + y * a2 + z * a3 for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)})

    def three(c: float) -> float:
        # the signed three-tone excess <|c + x|> − c, for c of either sign
        return excess(c, [a1, a2, a3], 0.0, epsrel=1e-10) + abs(c) - c

    return _phase_mean(three, abs(omega), a4, kinks, epsrel=1e-10)
