"""Statistics of the angular vibration reaching the sensor (docs/model.md).

The vibration about axis i is ``x_i(t)``: a sum of harmonic tones and at most
one Gaussian broadband part. Everything the error of eq. (13)-(15) needs from
it is

* ``M2 = <x3²>``, ``M4 = <x3⁴>`` and ``C3i = <x3·xi>`` (i = 1, 2), and
* ``E(Ω) = <|Ω + x3|> − |Ω|``, the rectified mean behind the asymmetry term.

Tones of different frequencies are averaged as if their phases were
independent and uniform (the brute force of docs/model.md); tones given at
the same frequency are coherent and are first added as phasors.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core._types import FloatArray, Table
from gyrovib.core.mixtures import _contour_excess
from gyrovib.core.special import erfc
from gyrovib.core.transmissibility import loglog_interp, psd_variance
from gyrovib.errors import ModelError
from gyrovib.frozen import Frozen
from gyrovib.progress import advance

SQRT_2_OVER_PI = math.sqrt(2.0 / math.pi)
#: The paper's printed multiplier of A1·a for a tone (eq. 14; docs/model.md).
PAPER_TONE_ASYMMETRY = 0.673
#: The paper's printed multiplier of A1·σ for random vibration (eq. 15).
PAPER_RANDOM_ASYMMETRY = 0.5


@dataclass(frozen=True, eq=False, repr=False)
class Vibration(Frozen):
    """The vibration at the sensor, after transmissibility.

    ``phasors``: complex amplitudes ``a_i·exp(jφ_i)`` of the tones, shape
    (K, 3), one row per distinct frequency. ``sigma``: RMS of the Gaussian part
    per axis, shape (3,). ``coherence``: ρ31, ρ32. ``has_random`` tells whether
    a random part was given at all (the paper's method needs to know).
    """

    phasors: NDArray[np.complex128]
    sigma: FloatArray
    coherence: FloatArray
    has_random: bool

    @property
    def tone_amplitudes(self) -> FloatArray:
        """Amplitude of each tone on the sensitive axis x3."""
        amps: FloatArray = np.abs(self.phasors[:, 2])
        return amps

    @property
    def m2(self) -> float:
        """``<x3²> = Σ a²/2 + σ²``."""
        a = self.tone_amplitudes
        return float(np.sum(a**2) / 2.0 + self.sigma[2] ** 2)

    @property
    def m4(self) -> float:
        """``<x3⁴> = Σ M4c + 3·[(Σ M2c)² − Σ M2c²]`` over independent components."""
        a = self.tone_amplitudes
        s2 = self.sigma[2] ** 2
        parts2 = np.append(a**2 / 2.0, s2)
        own4 = np.sum(3.0 * a**4 / 8.0) + 3.0 * s2**2
        return float(own4 + 3.0 * (np.sum(parts2) ** 2 - np.sum(parts2**2)))

    def cross(self, axis: int) -> float:
        """``C3i = <x3·xi> = Σ ½·a3·ai·cos(φ3 − φi) + ρ3i·σ3·σi`` for axis 1 or 2."""
        p = self.phasors
        tones = 0.5 * float(np.sum((p[:, 2] * np.conj(p[:, axis - 1])).real))
        return tones + float(self.coherence[axis - 1] * self.sigma[2] * self.sigma[axis - 1])


def vibration_at_sensor(
    tones: Sequence[tuple[float, ArrayLike, ArrayLike]] = (),
    *,
    psd: Sequence[Table | None] | None = None,
    rms: ArrayLike | None = None,
    coherence: ArrayLike = (1.0, 1.0),
    gains: Sequence[Table] = (),
) -> Vibration:
    """Build the vibration at the sensor from a profile's description.

    ``tones``: ``(frequency Hz, amplitude per axis, phase per axis in degrees)``.
    ``psd``: per axis a breakpoint table (rate²/Hz) or None; ``rms``: per-axis
    RMS at the sensor (no transmissibility applies); at most one of the two.
    ``gains``: the transmissibility tables ν_j(f) whose product scales a tone's
    amplitude by ν(f) and a PSD by ν(f)² (docs/model.md).
    """
    merged: dict[float, NDArray[np.complex128]] = {}
    for frequency, amplitude, phase in tones:
        amp = np.asarray(amplitude, dtype=float)
        ph = np.deg2rad(np.asarray(phase, dtype=float))
        nu = 1.0
        for gain in gains:
            nu *= float(loglog_interp(gain, frequency))
        phasor = (amp * nu) * np.exp(1j * ph)
        merged[float(frequency)] = merged.get(float(frequency), np.zeros(3, complex)) + phasor
    phasors = (
        np.array([merged[f] for f in sorted(merged)], dtype=complex)
        if merged
        else np.zeros((0, 3), dtype=complex)
    )
    if psd is not None and rms is not None:
        raise ValueError("give the random part as a PSD or as RMS values, not both")
    if psd is not None:
        sigma = np.array(
            [math.sqrt(psd_variance(t, tuple(gains))) if t is not None else 0.0 for t in psd]
        )
    elif rms is not None:
        sigma = np.asarray(rms, dtype=float).copy()
    else:
        sigma = np.zeros(3)
    return Vibration(
        phasors=phasors,
        sigma=sigma,
        coherence=np.asarray(coherence, dtype=float).copy(),
        has_random=psd is not None or rms is not None,
    )


# --------------------------------------------------------------------------- E(Ω)

def folded_normal_excess(omega: ArrayLike, sigma: float) -> FloatArray:
    """``E(Ω) = <|Ω + σZ|> − |Ω|`` for Gaussian Z (folded normal mean).

    ``<|Ω+σZ|> = σ·√(2/π)·exp(−Ω²/2σ²) + Ω·erf(Ω/(σ√2))``, written with erfc
    so that the difference keeps its precision for large |Ω|/σ (:func:`_gauss_kernel`
    at m = |Ω|).
    """
    w = np.abs(np.asarray(omega, dtype=float))
    if sigma <= 0:
        return np.zeros_like(w)
    return _gauss_kernel(w, sigma)


def arcsine_excess(omega: ArrayLike, a: float) -> FloatArray:
    """``E(Ω)`` for one tone ``a·sin θ``: ``(2/π)(Ω·asin(Ω/a) + √(a²−Ω²)) − |Ω|``, 0 if |Ω| ≥ a."""
    w = np.abs(np.asarray(omega, dtype=float))
    if a <= 0:
        return np.zeros_like(w)
    r = np.minimum(w / a, 1.0)
    inside = (2.0 / math.pi) * (w * np.arcsin(r) + a * np.sqrt(1.0 - r * r)) - w
    out: FloatArray = np.where(w < a, inside, 0.0)
    return out


def _phase_nodes(n: int) -> FloatArray:
    """``sin`` of ``n`` equally spaced phases (trapezoidal rule on a period).

    The values to average with equal weights: when 4 divides ``n`` each value
    occurs twice (θ and π − θ), so only the ``n/2`` distinct ones are returned,
    ``±sin θ_k`` for the first quarter period; the mean is the same.
    """
    if n % 4 == 0:
        quarter: FloatArray = np.sin(2.0 * math.pi * (np.arange(n // 4) + 0.5) / n)
        return np.concatenate([quarter, -quarter])
    nodes: FloatArray = np.sin(2.0 * math.pi * (np.arange(n) + 0.5) / n)
    return nodes


def _tone_grid(amplitudes: FloatArray, counts: Sequence[int]) -> FloatArray:
    """All sums ``Σ a_k·sin θ_k`` over the product grid of phases."""
    total = np.zeros(1)
    for a, n in zip(amplitudes, counts, strict=True):
        total = (total[:, None] + a * _phase_nodes(n)[None, :]).ravel()
    return total


def _gauss_kernel(m: FloatArray, sigma: float) -> FloatArray:
    """``<|m + σZ|> − m`` for a *signed* shift ``m``: ``2·E[(−(m + σZ))⁺]``.

    ``σ·√(2/π)·exp(−m²/2σ²) − m·erfc(m/(σ√2))``: both terms are positive when
    m < 0 and the difference of two small positive numbers (relative loss
    ~1/(2u²), u = m/σ√2) when m > 0, so the excess keeps its precision where
    it is tiny instead of being a difference of two numbers near |Ω|.
    """
    with np.errstate(over="ignore"):  # |u| → inf for a subnormal σ: exp(−inf) = 0
        u = m / (sigma * math.sqrt(2.0))
        out: FloatArray = sigma * SQRT_2_OVER_PI * np.exp(-(u**2)) - m * erfc(u)
    return out


def _tone_kernel(m: FloatArray, a: float) -> FloatArray:
    """``<|m + a·sin θ|> − m`` for a signed shift ``m``: 0 for m ≥ a, −2m for m ≤ −a.

    Between, ``(2/π)(m·asin(m/a) + √(a² − m²)) − m``; for m > 0 that is a
    difference of numbers near m whose result vanishes like (a − m)^{3/2}
    (at a = 100 it kept only ~8 digits 1e-3 below the edge), so there it is
    written as the sum of positive terms ``(2/π)((a − m)·t + 2m·(t − atan t))``,
    t = √((a − m)/(a + m)), with t − atan t from its series for small t.
    """
    r = np.clip(m / a, -1.0, 1.0)
    inside = (2.0 / math.pi) * (m * np.arcsin(r) + a * np.sqrt(1.0 - r * r)) - m
    pos = np.clip(m, 0.0, a)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.sqrt((a - pos) / (a + pos))
    t2 = t * t
    series = t * t2 * (1 / 3 - t2 * (1 / 5 - t2 * (1 / 7 - t2 * (1 / 9 - t2 * (1 / 11 - t2 / 13)))))
    rest = np.where(t < 0.1, series, t - np.arctan(t))
    upper = (2.0 / math.pi) * ((a - pos) * t + 2.0 * pos * rest)
    inside = np.where(m > 0, upper, inside)
    out: FloatArray = np.where(m >= a, 0.0, np.where(m <= -a, -2.0 * m, inside))
    return out


#: Beyond this many σ past the tones' reach, E(Ω) underflows (e^-800): it is 0.
_TAIL_SIGMAS = 40.0
#: Most phase-grid nodes per rate for one tone on a Gaussian part.
_MAX_NODES = 1 << 22


def rectified_excess(omega: ArrayLike, amplitudes: ArrayLike, sigma: float) -> FloatArray:
    """``E(Ω) = <|Ω + x3|> − |Ω|`` for tones of ``amplitudes`` plus Gaussian ``sigma``.

    ``omega`` any shape (returned flattened, at least 1-d), ``amplitudes`` (K,),
    ``sigma`` ≥ 0, all in the same rate unit (docs/model.md section 4).

    * no tone, or one tone alone: the closed forms (folded normal, arcsine);
    * one tone on a Gaussian part, or two or three tones alone: the phase mean
      of the signed excess of the remaining component (midpoint grid, or
      Gauss-Legendre split at the kinks; :func:`_grid_on_gauss_excess`,
      :func:`_few_tones_excess`);
    * any other mixture (two or more tones with a Gaussian part, four or more
      tones alone, up to the 64 a profile may hold): one contour integral of
      the moment generating function, :func:`~gyrovib.core.mixtures._contour_excess`.

    Rates that the vibration cannot reach are not computed: for tones alone E
    is exactly 0 once |Ω| ≥ Σa (Ω + x3 never changes sign), and with a
    Gaussian part it underflows to 0 beyond Σa + 40σ.

    Raises :class:`~gyrovib.errors.ModelError` when four or more tones on a
    Gaussian part would need more Bessel values than
    :data:`~gyrovib.core.mixtures._MAX_CONTOUR_VALUES` (a Gaussian part tiny
    against the tones), saying what to change; two or three tones then fall
    back to their phase grid.
    """
    w = np.abs(np.atleast_1d(np.asarray(omega, dtype=float))).ravel()
    a = np.asarray(amplitudes, dtype=float).ravel()
    a = np.sort(a[a > 0])[::-1]
    if sigma * sigma == 0.0:
        # a Gaussian part whose variance underflows (σ below ~1e-162) moves E by at
        # most E|x| = σ·√(2/π) (|·| is 1-Lipschitz): below the smallest normal float
        sigma = 0.0
    if a.size == 0:
        out0: FloatArray = np.zeros_like(w)
        near = w < _TAIL_SIGMAS * sigma  # beyond, E < e^-800·σ underflows to 0
        out0[near] = folded_normal_excess(w[near], sigma)
        return out0
    if sigma <= 0 and a.size == 1:
        return arcsine_excess(w, float(a[0]))
    reach = math.fsum(a.tolist())  # correctly rounded: |Ω| = Σa is "beyond" however summed
    out: FloatArray = np.zeros_like(w)
    # E is 0 (tones alone) or underflows (with σ) beyond this: skip those rates
    live = w < reach + (_TAIL_SIGMAS * sigma if sigma > 0 else 0.0)
    if not live.any():
        return out
    wl = w[live]
    if sigma <= 0 and a.size <= 3:
        out[live] = _few_tones_excess(wl, a)
    elif sigma > 0 and a.size == 1:
        if 1.25 * float(a[0]) * (8.0 / sigma + (float(wl.max()) + float(a[0])) / sigma**2) \
                > _GRID_LIMIT:
            out[live] = _tone_on_gauss_excess(wl, float(a[0]), sigma)
        else:
            out[live] = _grid_on_gauss_excess(wl, a, sigma)
    else:
        try:
            out[live] = _contour_excess(wl, a, sigma)
        except ModelError:
            if a.size > 3:
                raise
            # a Gaussian part so small against two or three tones that the
            # contour would be long: their phase grid instead
            out[live] = _grid_on_gauss_excess(wl, a, sigma)
    return out


def _few_tones_excess(w: FloatArray, a: FloatArray) -> FloatArray:
    """Two or three tones alone (``a`` descending), ``0 ≤ w < Σa``.

    With s = Σ a_k·sin θ_k over all tones but the largest, ``E = <k(w + s)>``
    where ``k`` is the arcsine kernel of the largest tone (signed excess;
    never written as ``<|Ω + x3|> − |Ω|``, so E keeps its relative precision
    in the tails). The mean over the next two tones' phases is Gauss-Legendre
    split at the kernel's kinks (geometric convergence, ~1e-14).
    """
    closed, inner = float(a[0]), float(a[1])
    if a.size == 2:
        return _grid_mean(w, a[:0], [], lambda m: _pair_mean(m, inner, closed),
                          cost=_PAIR_NODES)
    outer = float(a[2])
    return _grid_mean(w, a[:0], [], lambda m: _triple_mean(m, outer, inner, closed),
                      cost=_TRIPLE_NODES)


def _grid_on_gauss_excess(w: FloatArray, a: FloatArray, sigma: float) -> FloatArray:
    """Tones ``a`` on a Gaussian part ``sigma``: ``E = <g(w + Σ a_k·sin θ_k)>``.

    ``g`` is the folded-normal signed excess (:func:`_gauss_kernel`), averaged
    over a product grid of the tones' phases (midpoint rule, exact for
    trigonometric polynomials). The integrand is analytic and the rule
    converges geometrically once a tone has more nodes than its
    ``8·a/σ + (w + Σa)·a/σ²`` (the kernel's width against the tone's swing, and
    the curvature of the exponential tail): 1.25 times that plus 32 nodes give
    ~1e-14 relative. Rates are grouped by grid size (powers of two). Used for
    one tone, and for two or three tones on a Gaussian part too small for the
    contour of :func:`~gyrovib.core.mixtures._contour_excess` (grids capped at :data:`_MAX_NODES`).
    """
    out: FloatArray = np.empty_like(w)
    reach = float(a.sum())
    with np.errstate(over="ignore", divide="ignore"):  # a subnormal σ: capped below
        scale = 8.0 / sigma + (w + reach) / sigma**2
        bucket = np.exp2(np.ceil(np.log2(scale)))
    for level in sorted(set(bucket.tolist())):  # (np.unique imports numpy.ma)
        chosen = bucket == level
        counts = [4 * math.ceil((min(1.25 * level * ak, _MAX_NODES) + 32) / 4) for ak in a]
        total = math.prod(counts)
        if total > _MAX_NODES:
            shrink = (_MAX_NODES / total) ** (1.0 / len(counts))
            counts = [4 * max(8, int(n * shrink) // 4) for n in counts]
        out[chosen] = _grid_mean(w[chosen], a, counts, lambda m: _gauss_kernel(m, sigma))
    return out


#: Phase-grid nodes above which one tone on a Gaussian part is integrated over
#: the Gaussian instead (:func:`_tone_on_gauss_excess`).
_GRID_LIMIT = 1 << 12


def _tone_on_gauss_excess(w: FloatArray, a: float, sigma: float) -> FloatArray:
    """One tone ``a`` on a Gaussian part ``sigma``, ``w ≥ 0``: ``E = ∫ φ(z)·k(w + σz) dz``.

    ``k`` is the tone's signed excess (:func:`_tone_kernel`: 0 for m ≥ a,
    −2m for m ≤ −a, smooth between with (·)^{3/2} edges at ±a) and φ the
    standard normal density; E = <|w + σZ + a·sin θ|> − w with E[σZ] = 0.
    The z-line is cut at the edges (w ± a)/σ and into pieces over which φ
    changes by at most a factor ~e (width 1, or 1/|z| in the tail), each integrated by
    the stretched Gauss-Legendre rule (geometric convergence across the edges,
    ~1e-14). Only where the integrand lives: z ≤ (a − w)/σ (k = 0 beyond), and
    within 45/|z| of that end in the Gaussian's tail, so E keeps its relative
    precision where it is tiny. Cost ~100 pieces × 24 nodes per rate whatever
    σ/a is — the phase grid of :func:`_grid_on_gauss_excess` needs ~a/σ nodes
    (a = 100, σ = 1e-3: 4 million per rate, 91 s for a 401-rate sweep).
    """
    stretch, stretch_weight = stretched_rule()
    out: FloatArray = np.empty_like(w)
    for i, wi in enumerate(w.tolist()):
        if i % 256 == 0:
            advance("E(Ω) of a tone on a random part", i, w.size)
        upper = min(45.0, (a - wi) / sigma)
        # the bulk of the Gaussian in unit pieces, or its tail beyond |upper| > 1
        # (where φ falls by e^{-|upper|·δ} over δ) in pieces of 1/|upper|
        width = 1.0 if upper >= -1.0 else 1.0 / abs(upper)
        lower = -45.0 if upper >= -1.0 else upper - 45.0 * width
        edge = (-a - wi) / sigma
        inner = np.arange(lower + width, upper, width)
        extra = [edge] if lower < edge < upper else []
        edges = np.sort(np.concatenate([[lower, upper], inner, extra]))
        edges = edges[np.concatenate([[True], np.diff(edges) > 0])]  # (np.unique: numpy.ma)
        length = np.diff(edges)[:, None]
        nodes = edges[:-1, None] + length * stretch
        weight = length * stretch_weight
        dens = np.exp(-0.5 * nodes * nodes) / math.sqrt(2.0 * math.pi)
        out[i] = float(np.sum(dens * weight * _tone_kernel(wi + sigma * nodes, a)))
    advance("E(Ω) of a tone on a random part", w.size, w.size)
    return out


#: Gauss-Legendre nodes per piece of :func:`_pieces`.
_GL_N = 24
#: Values one :func:`_pair_mean` / :func:`_triple_mean` argument makes (3 and 5 pieces).
_PAIR_NODES = 3 * _GL_N
_TRIPLE_NODES = 5 * _GL_N * _PAIR_NODES


#: The ``_GL_N``-point Gauss-Legendre nodes and weights on [−1, 1], written out: Newton's
#: method on P_n gives them to the last bit (tests/test_statistics.py checks it).
_GL24_X = (
    -0.9951872199970213, -0.9747285559713095, -0.9382745520027328, -0.8864155270044011,
    -0.820001985973903, -0.7401241915785544, -0.6480936519369755, -0.5454214713888396,
    -0.4337935076260452, -0.3150426796961634, -0.1911188674736163, -0.06405689286260563,
    0.06405689286260563, 0.1911188674736163, 0.3150426796961634, 0.4337935076260452,
    0.5454214713888396, 0.6480936519369755, 0.7401241915785544, 0.820001985973903,
    0.8864155270044011, 0.9382745520027328, 0.9747285559713095, 0.9951872199970213,
)
_GL24_W = (
    0.012341229799987334, 0.02853138862893381, 0.044277438817419676, 0.05929858491543666,
    0.07334648141108027, 0.08619016153195322, 0.09761865210411391, 0.10744427011596562,
    0.11550566805372554, 0.12167047292780338, 0.12583745634682839, 0.12793819534675224,
    0.12793819534675224, 0.12583745634682839, 0.12167047292780338, 0.11550566805372554,
    0.10744427011596562, 0.09761865210411391, 0.08619016153195322, 0.07334648141108027,
    0.05929858491543666, 0.044277438817419676, 0.02853138862893381, 0.012341229799987334,
)


@functools.cache
def stretched_rule() -> tuple[FloatArray, FloatArray]:
    """Gauss-Legendre nodes on [0, 1] mapped by θ = lo + L·(1 − cos πv)/2, which
    makes the (θ − θ*)^(3/2) behaviour at a kink smooth in v; with the Jacobian."""
    x, w = np.array(_GL24_X), np.array(_GL24_W)
    v = (x + 1.0) / 2.0
    return (1.0 - np.cos(math.pi * v)) / 2.0, w / 2.0 * (math.pi / 2.0) * np.sin(math.pi * v)


def _stretched_pieces(
    c: FloatArray, amplitude: float, targets: Sequence[float]
) -> list[tuple[FloatArray, FloatArray]]:
    """Nodes θ and weights over [−π/2, π/2] for the mean over θ of f(c + amplitude·sin θ)
    when f is smooth except at ``targets`` (ascending): the half period is split
    where ``c + amplitude·sin θ`` crosses a target, and each piece gets the
    stretched Gauss-Legendre rule. ``c`` has a trailing axis of length 1.
    """
    half = math.pi / 2.0
    cuts = [np.arcsin(np.clip((t - c) / amplitude, -1.0, 1.0)) for t in targets]
    edges = [np.full_like(c, -half), *cuts, np.full_like(c, half)]
    stretch, stretch_weight = stretched_rule()
    pieces = []
    for lo, hi in itertools.pairwise(edges):
        length = hi - lo
        pieces.append((lo + length * stretch, length * stretch_weight / math.pi))
    return pieces


def _triple_mean(m: FloatArray, outer: float, inner: float, closed: float) -> FloatArray:
    """``<_pair_mean(m + outer·sin θ)>`` over θ: three tones, geometric convergence.

    :func:`_pair_mean` is smooth except where its argument is ±closed ± inner,
    so the outer half period is split there too.
    """
    c = np.asarray(m, dtype=float)[..., None]
    targets = sorted({-closed - inner, -closed + inner, closed - inner, closed + inner})
    total = np.zeros(np.shape(m))
    for theta, weight in _stretched_pieces(c, outer, targets):
        total = total + np.sum(_pair_mean(c + outer * np.sin(theta), inner, closed) * weight,
                               axis=-1)
    out: FloatArray = total
    return out


def _pair_mean(m: FloatArray, inner: float, closed: float) -> FloatArray:
    """``<k(m + inner·sin θ)>`` over θ, ``k`` the arcsine kernel of the ``closed`` tone.

    The kernel has (x)^(3/2) kinks where ``m + inner·sin θ = ±closed``; the
    half period [−π/2, π/2] is split there and each piece integrated by
    Gauss-Legendre in a variable that clusters nodes at both ends, which
    converges geometrically (~1e-14 with 24 nodes per piece).
    """
    c = np.asarray(m, dtype=float)[..., None]
    total = np.zeros(np.shape(m))
    for theta, weight in _stretched_pieces(c, inner, (-closed, closed)):
        total = total + np.sum(_tone_kernel(c + inner * np.sin(theta), closed) * weight,
                               axis=-1)
    out: FloatArray = total
    return out


def _grid_mean(
    w: FloatArray, amplitudes: FloatArray, counts: Sequence[int],
    kernel: Callable[[FloatArray], FloatArray], cost: int = 1,
) -> FloatArray:
    """``mean over the phase grid of kernel(w + Σ a_k·sin θ_k)``, per entry of ``w``.

    ``cost`` is the number of values the kernel makes per argument; rates are
    taken in chunks so that about 4 million values exist at a time.
    """
    shifts = _tone_grid(amplitudes, counts)
    out = np.empty_like(w)
    chunk = max(1, (1 << 22) // (shifts.size * cost))
    for start in range(0, w.size, chunk):
        block = w[start : start + chunk, None] + shifts[None, :]
        out[start : start + chunk] = kernel(block).mean(axis=1)
    return out
