"""The rectified mean of a mixture of tones and a Gaussian part by one contour integral.

``E(Ω) = <|Ω + x3|> − |Ω|`` (docs/model.md section 4) for two or more tones with a
Gaussian part, or four or more tones alone: the inverse Laplace transform of
the moment generating function ``M(s) = e^{σ²s²/2}·Π I0(a_k·s)`` on a line
``Re s = α`` through the saddle point (:func:`_contour_excess`), with the
modified Bessel functions I0, I1 computed here (no scipy at start-up).
:func:`gyrovib.core.statistics.rectified_excess` chooses between this and the
closed forms.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from numpy.typing import NDArray

from gyrovib.core._types import FloatArray
from gyrovib.errors import ModelError
from gyrovib.progress import advance

#: Most Bessel-function values one group of rates may need on the contour of
#: :func:`_contour_excess` (K tones × nodes); about 1 µs each.
_MAX_CONTOUR_VALUES = 1 << 23
#: Relative tolerances of the contour quadrature with a Gaussian part and for
#: tones alone: of the trapezoidal rule (cheap: h shrinks with log(1/tol)), and
#: of truncating the tones' algebraic tail (nodes grow like tol^(-1/(K/2+1))).
#: docs/model.md section 4 asks 1e-9 and 1e-6; the tests hold 1e-9 and 1e-7.
_CONTOUR_TOL_RANDOM = 1e-13
_TRUNCATION_TOL_RANDOM = 1e-11
_CONTOUR_TOL_TONES = 1e-10
_TRUNCATION_TOL_TONES = 1e-9


#: Below this |z| the modified Bessel functions come from the trapezoidal rule
#: on (1/π)∫₀^π e^{z·cos θ}(1, cos θ) dθ, with N + 1 nodes for |z| up to each
#: bound of :data:`_BESSEL_TIERS` (error ~I_{2N}(|z|)/I0(|z|) ~ (|z|/2)^{2N}/(2N)!
#: < 1e-16); above,
#: from the Hankel expansion with :data:`_HANKEL_TERMS` terms (error
#: ~30!/(2|z|)^30 < 1e-18). Written here so that the engine need not import
#: scipy.special (a quarter of a second at start-up).
_BESSEL_SWITCH = 25.0
_BESSEL_TIERS = ((4.0, 12), (12.0, 20), (_BESSEL_SWITCH, 32))
_HANKEL_TERMS = 30


def _trapezoid(n: int) -> tuple[FloatArray, FloatArray]:
    """cos θ_j and weights of the trapezoidal rule on [0, π] with n + 1 nodes, mean 1."""
    weights = np.full(n + 1, 1.0 / n)
    weights[[0, -1]] *= 0.5
    cos: FloatArray = np.cos(math.pi * np.arange(n + 1) / n)
    return cos, weights


_RULES = {n: _trapezoid(n) for _, n in _BESSEL_TIERS}
_COS, _TRAPEZOID = _RULES[_BESSEL_TIERS[-1][1]]


def _hankel(nu: int) -> FloatArray:
    """Coefficients c_k of I_ν(z) ~ e^z/√(2πz)·Σ c_k z^-k: c_k = c_{k−1}·((2k−1)² − 4ν²)/(8k)."""
    c = np.ones(_HANKEL_TERMS)
    for k in range(1, _HANKEL_TERMS):
        c[k] = c[k - 1] * ((2 * k - 1) ** 2 - 4 * nu * nu) / (8 * k)
    return c


_HANKEL_0, _HANKEL_1 = _hankel(0), _hankel(1)


def _series(c: FloatArray, inv: NDArray[np.complex128] | FloatArray) -> NDArray[np.complex128]:
    """Σ c_k·inv^k by Horner's rule."""
    total = np.zeros_like(inv) + c[-1]
    for ck in c[-2::-1]:
        total = total * inv + ck
    out: NDArray[np.complex128] = total
    return out


def _log_i0e(z: NDArray[np.complexfloating]) -> NDArray[np.complex128]:
    """``log(I0(z)·e^{−Re z})`` for complex z with Re z ≥ 0 and Im z ≥ 0 (any shape).

    I0 has no zeros off the imaginary axis, so the logarithm is finite for
    Re z > 0. Large |z|: DLMF 10.40.5, ``I0(z) = e^z/√(2πz)·Σc_k z^-k
    + i·e^{−z}/√(2πz)·Σ(−1)^k c_k z^-k`` (0 ≤ arg z < π/2).
    """
    out = np.empty(z.shape, dtype=complex)
    size = np.abs(z)
    lower = -1.0
    for bound, n in _BESSEL_TIERS:
        tier = (size > lower) & (size <= bound)
        lower = bound
        zs = z[tier]
        if zs.size:
            # θ and π − θ pair up: e^{−z·cos θ} = 1/e^{z·cos θ}, one exponential for two
            cos, weights = _RULES[n]
            half = n // 2
            # (real exp, cos and sin: numpy vectorises those, not the complex exp)
            x = zs.real[..., None] * cos[:half]
            y = zs.imag[..., None] * cos[:half]
            turn = np.cos(y) + 1j * np.sin(y)
            scale = np.exp(-zs.real)[..., None]
            values = ((np.exp(x) * scale) * turn + (np.exp(-x) * scale) * turn.conj()
                      ) @ weights[:half] + weights[half] * scale[..., 0]
            out[tier] = np.log(values)
    small = size <= _BESSEL_SWITCH
    zl = z[~small]
    if zl.size:
        inv = 1.0 / zl
        lead = _series(_HANKEL_0, inv)
        other = 1j * np.exp(-2.0 * zl) * _series(_HANKEL_0, -inv)
        out[~small] = (1j * zl.imag - 0.5 * np.log(2.0 * math.pi * zl)
                       + np.log(lead + other))
    return out


def _i0e_i1e(x: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``I0(x)·e^{−x}`` and ``I1(x)·e^{−x}`` for real x ≥ 0 (any shape)."""
    i0 = np.empty_like(x)
    i1 = np.empty_like(x)
    small = x <= _BESSEL_SWITCH
    xs = x[small]
    if xs.size:
        kernel = np.exp(xs[..., None] * (_COS - 1.0))
        i0[small] = kernel @ _TRAPEZOID
        i1[small] = kernel @ (_TRAPEZOID * _COS)
    xl = x[~small]
    if xl.size:
        inv = 1.0 / xl
        root = 1.0 / np.sqrt(2.0 * math.pi * xl)
        i0[~small] = root * _series(_HANKEL_0, inv).real
        i1[~small] = root * _series(_HANKEL_1, inv).real
    tiny = x < 0.01  # I1's rule cancels there (∫cos θ = 0): its series, error < x⁷/18432
    xt = x[tiny]
    i1[tiny] = (xt / 2.0 + xt**3 / 16.0 + xt**5 / 384.0) * np.exp(-xt)
    return i0, i1


_TABLE_STEP = 1.0 / 80.0


@functools.cache
def _bessel_table() -> tuple[FloatArray, FloatArray, FloatArray]:
    """x on [0, 25] in steps of 1/80, with log(I0(x)e^−x) and I1(x)/I0(x) there."""
    x = np.arange(0.0, _BESSEL_SWITCH + _TABLE_STEP / 2, _TABLE_STEP)
    i0, i1 = _i0e_i1e(x)
    return x, np.log(i0), i1 / i0


def _log_i0e_ratio(x: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Approximate ``log(I0(x)·e^{−x})`` and ``I1(x)/I0(x)`` for real x ≥ 0, to ~1e-5.

    Enough to place the contour of :func:`_contour_excess` (its saddle point
    and step), which needs neither to be exact: linear interpolation in a
    table below x = 25, three terms of the Hankel expansion above.
    """
    grid, log_i0, ratio = _bessel_table()
    inside = x <= _BESSEL_SWITCH
    big = np.where(inside, _BESSEL_SWITCH, x)
    inv = 1.0 / big
    far_log = -0.5 * np.log(2.0 * math.pi * big) + np.log1p(inv / 8.0 + 9.0 / 128.0 * inv * inv)
    far_ratio = 1.0 - inv / 2.0 - inv * inv / 8.0 - inv**3 / 8.0
    near = np.where(inside, x, 0.0)
    out_log: FloatArray = np.where(inside, np.interp(near, grid, log_i0), far_log)
    out_ratio: FloatArray = np.where(inside, np.interp(near, grid, ratio), far_ratio)
    return out_log, out_ratio


def _log_mgf_real(alpha: FloatArray, a: FloatArray, sigma: float) -> FloatArray:
    """``log M(α) = σ²α²/2 + Σ log I0(a_k·α)`` for real α > 0, to ~1e-5 per tone
    (:func:`_log_i0e_ratio`; it places the contour, it does not weigh it)."""
    x = alpha[..., None] * a
    out: FloatArray = 0.5 * sigma**2 * alpha**2 + np.sum(_log_i0e_ratio(x)[0] + x, axis=-1)
    return out


def _saddle(w: FloatArray, a: FloatArray, sigma: float) -> FloatArray:
    """The α > 0 minimising ``φ(α) = log M(α) − α·w − 2·log α``, per rate, to ~1 %.

    ``φ'(α) = g(α) − w`` with ``g(α) = σ²α + Σ a_k·I1(a_kα)/I0(a_kα) − 2/α``,
    which increases (φ is convex) and does not depend on w: g is tabulated
    once on a geometric grid of α (64 points per octave) from ``√(2/M2)``
    (where g ≤ 0, since I1/I0(x) ≤ x/2) to where g passes the largest w (for
    tones alone w < Σa, the limit of g), and inverted by interpolation. The
    contour only needs to pass near the saddle (the loss is ~φ''·δα²/2).
    """

    def g(alpha: FloatArray) -> FloatArray:
        ratio = _log_i0e_ratio(alpha[:, None] * a)[1]
        out: FloatArray = sigma**2 * alpha + ratio @ a - 2.0 / alpha
        return out

    m2 = float(np.sum(a * a) / 2.0 + sigma**2)
    lo = math.sqrt(2.0 / m2)
    hi = 2.0 * lo
    top = float(w.max())
    while float(g(np.array([hi]))[0]) < top:
        hi *= 2.0
    octaves = math.log2(hi / lo)
    grid = np.geomspace(lo, hi, max(2, math.ceil(64 * octaves) + 1))
    values = np.maximum.accumulate(g(grid))  # monotone despite the table's ~1e-5
    out: FloatArray = np.exp(np.interp(w, values, np.log(grid)))
    return out


def _contour_excess(w: FloatArray, a: FloatArray, sigma: float) -> FloatArray:
    """E(Ω) for any tones ``a`` and Gaussian ``sigma`` by one contour integral.

    With X = Σ a_k·sin θ_k + σZ symmetric, ``E(Ω) = 2·<(X − w)⁺>`` (w = |Ω|),
    and since the ramp ``y⁺`` is the inverse Laplace transform of ``1/s²``,

        E(Ω) = (1/π) ∫ Re[ M(s)·e^{−s·w} / s² ] du,   s = α + iu, u ∈ (−∞, ∞),

    for any α > 0, with the moment generating function
    ``M(s) = <e^{sX}> = e^{σ²s²/2}·Π I0(a_k·s)`` (I0(a·s) = J0(i·a·s): the
    characteristic function of docs/model.md section 4 turned by 90°). On α = 0
    this is the integral ``(2/π)∫(1 − Re φ(t))/t² dt`` of docs/model.md; moving
    the line to the saddle point α* of ``|M(α)e^{−αw}/α²|`` removes the
    oscillation that makes that form lose all relative precision where E is
    small: the integrand is then a non-oscillating bump whose height is the
    size of E, so E keeps its relative precision in the tails (down to
    underflow), and the ``1/t²`` tail of the real-axis form never appears.

    Quadrature: the integrand is analytic in u except at u = iα (s = 0), so the
    trapezoidal rule converges geometrically; with the strip |Im u| < α/2 its
    relative error is ``exp(Δ − π·α/h)``, Δ the growth of the integrand's
    envelope on that strip's edges (log M at α/2 and 3α/2 against α*), and h
    is chosen from it. The nodes go out until the envelope, which decays like
    ``e^{−σ²u²/2}·u^{−K/2−2}``, leaves a tail below the tolerance. Rates whose
    saddles are close (the loss ``φ(α) − φ(α*) < 1``) share one contour and
    its Bessel values; each rate then costs one cosine per node.
    """
    tol = _CONTOUR_TOL_RANDOM if sigma > 0 else _CONTOUR_TOL_TONES
    cut = _TRUNCATION_TOL_RANDOM if sigma > 0 else _TRUNCATION_TOL_TONES
    out: FloatArray = np.empty_like(w)
    alpha_star = _saddle(w, a, sigma)
    order = np.argsort(alpha_star, kind="stable")
    ws, al = w[order], alpha_star[order]
    best = _log_mgf_real(al, a, sigma) - al * ws - 2.0 * np.log(al)  # φ(α*) per rate
    power = a.size / 2.0 + 2.0  # algebraic decay of the envelope for tones alone
    start = 0
    while start < ws.size:
        advance("E(Ω) of mixed tones", start, ws.size)
        alpha = float(al[start])
        rest = slice(start, ws.size)

        def phi(x: float, rest: slice = rest) -> FloatArray:
            lm = float(_log_mgf_real(np.array([x]), a, sigma)[0])
            out_: FloatArray = lm - x * ws[rest] - 2.0 * math.log(x) - best[rest]
            return out_

        share = phi(alpha) < 1.0
        stop = start + int(np.argmin(share)) if not share.all() else ws.size
        stop = max(stop, start + 1)
        group = slice(start, stop)
        growth = max(float(np.max(phi(0.5 * alpha, group))),
                     float(np.max(phi(1.5 * alpha, group))), 0.0)
        h = math.pi * 0.5 * alpha / (growth + math.log(1.0 / tol) + 3.0)
        # Bessel values on the contour, in blocks, until the tail is negligible
        logs: list[NDArray[np.complex128]] = []
        count, mass, first = 0, 0.0, 0.0
        block = 64
        while True:
            u = h * np.arange(count, count + block)
            s = alpha + 1j * u
            z = s[:, None] * a
            log_f = (0.5 * sigma**2 * s * s
                     + np.sum(_log_i0e(z) + alpha * a, axis=-1)
                     - 2.0 * np.log(s))
            logs.append(log_f)
            if count == 0:
                first = float(log_f[0].real)
            envelope = np.exp(log_f.real - first)
            mass += float(envelope.sum())
            count += block
            last = float(envelope[-1])
            if last < cut and last * u[-1] / (power - 1.0) < cut * h * mass:
                break
            # where the nodes will have to reach: the Gaussian factor's cut-off,
            # or where the tones' algebraic tail C·u^-p drops below the tolerance
            reach_gauss = (math.sqrt(2.0 * (math.log(1.0 / cut) + 10.0)) / sigma
                           if sigma > 0 else math.inf)
            reach_tones = u[-1] * max(1.0, last / (cut * min(1.0, h * mass / u[-1]))
                                      ) ** (1.0 / (power - 1.0))
            if min(reach_gauss, reach_tones) / h * a.size > _MAX_CONTOUR_VALUES:
                raise ModelError(
                    f"E(Ω) for {a.size} tones (largest {a[0]:.4g}) on a random part of "
                    f"RMS {sigma:.4g} would need more than {_MAX_CONTOUR_VALUES} Bessel "
                    "values: the random part is too small against the tones to matter "
                    "yet too large to drop; drop it, or merge the smallest tones"
                )
            block = min(2 * block, 4096)  # (block, K, 16) trapezoid arrays: ≤ 70 MB
        log_f = np.concatenate(logs)
        nodes = h * np.arange(log_f.size)
        weight = np.exp(log_f.real - first)
        weight[0] *= 0.5
        phase = log_f.imag
        chunk = max(1, (1 << 20) // log_f.size)
        for lo in range(start, stop, chunk):
            hi = min(stop, lo + chunk)
            wc = ws[lo:hi]
            total = np.cos(phase[None, :] - nodes[None, :] * wc[:, None]) @ weight
            with np.errstate(under="ignore"):
                out[order[lo:hi]] = (2.0 * h / math.pi) * np.exp(first - alpha * wc) * total
        start = stop
    advance("E(Ω) of mixed tones", ws.size, ws.size)
    return out
