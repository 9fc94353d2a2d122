"""Rate-table data to the coefficients of eq. (1) and (2), with their uncertainty.

docs/model.md section 14. A unit is turned at known rates Ω about its sensitive
axis x3 (optionally with known cross rates ω1, ω2) and its mean output U is
recorded. Eq. (1) is linear in its parameters θ:

    U = K0 + K1·Ω + h·|Ω| + Σ_{n=2..N} Kn·Ωⁿ [+ M1·ω1 + M2·ω2 + M31·Ω·ω1 + M32·Ω·ω2]

with h = ½·K1·A1 (the sign-dependent scale factor K1·(1 + ½A1·sign Ω)·Ω is
K1·Ω + h·|Ω|). Ordinary least squares gives θ̂ and

    Cov(θ̂) = s²·(XᵀX)⁻¹,   s² = RSS/(n − p),

computed block by block (O(p²) memory beside the points) on a scaled design: rates
over their largest magnitude, columns normalised (:func:`_scaling`, :func:`_factor`),
the output over a power of two (:func:`_output_scale`), the scales undone on θ̂ and its
covariance; rates whose powers leave 1e±100 are refused (:func:`_check_magnitude`), as
are results that are not finite or whose variance underflowed (docs/rate-table.md).

Eq. (2) follows by division by K1: k0 = K0/K1, A1 = 2h/K1, kn = Kn/K1,
mi = Mi/K1, m3i = M3i/K1 (k1 = 1 exactly), with the delta-method covariance
J·Cov(θ̂)·Jᵀ, J the Jacobian of that map at θ̂:

    ∂c_j/∂(numerator_j) = f_j/K1 (f = 2 for A1, else 1),   ∂c_j/∂K1 = −c_j/K1.

The rates are in one rate unit (any), the output in one output unit (any):
the eq. (2) coefficients come out in the rate unit (kn in rate^(1−n)) and do
not depend on the output unit at all.

The model is identifiable only when the data separate its columns: rates of
both signs (else |Ω| = ±Ω and A1 is lost in K1), at least as many distinct
|Ω| levels as the even part K0 + h|Ω| + K2Ω² + K4Ω⁴ has parameters (2 + ⌊N/2⌋)
and as many distinct nonzero levels as the odd part K1Ω + K3Ω³ + K5Ω⁵ has
(⌈N/2⌉), and more points than parameters (n > p, so that s² exists).
:class:`IdentificationError` names what the data lack.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import polynomial as P
from numpy.typing import ArrayLike, NDArray

from gyrovib.core._types import FloatArray
from gyrovib.errors import ModelError
from gyrovib.frozen import Frozen

#: The highest power of Ω in eq. (1).
MAX_ORDER = 5
DEFAULT_ORDER = 5
#: |t| below this is flagged "not significant" (docs/model.md section 14), never dropped.
SIGNIFICANT_T = 2.0
#: A scaled design matrix whose condition number exceeds this does not identify the model.
MAX_CONDITION = 1e10


class IdentificationError(ModelError):
    """The rate-table data cannot identify the model of eq. (1): the message names
    what the data lack (rates of one sign, too few |Ω| levels, too few points)."""


def raw_names(order: int, cross: Sequence[int] = ()) -> tuple[str, ...]:
    """The parameters θ of eq. (1) fitted at ``order``: K0, K1, h, K2..KN, then for
    each cross axis i in ``cross`` (1, 2): Mi, then M3i."""
    names = ["K0", "K1", "h", *(f"K{n}" for n in range(2, order + 1))]
    names += [f"M{i}" for i in cross] + [f"M3{i}" for i in cross]
    return tuple(names)


def rate_names(order: int, cross: Sequence[int] = ()) -> tuple[str, ...]:
    """The eq. (2) coefficients the fit gives (k1 = 1 exactly, not listed): k0, A1,
    k2..kN, then mi and m3i for each cross axis i in ``cross``."""
    names = ["k0", "A1", *(f"k{n}" for n in range(2, order + 1))]
    names += [f"m{i}" for i in cross] + [f"m3{i}" for i in cross]
    return tuple(names)


@dataclass(frozen=True, eq=False, repr=False)
class Nonlinearity(Frozen):
    """The fitted eq. (2) curve's deviation from a straight line over [−R, R], in %FS.

    With ω1 = ω2 = 0, p(ω) = k0 + ω + ½A1|ω| + Σ kn·ωⁿ; ``least_squares_max`` is
    100·max|p − L|/R for L the least-squares line of p over uniform ω in [−R, R]
    ("best-fit straight line"), ``endpoint_max`` the same for the line through
    p(−R) and p(R) ("terminal-based"); ``range`` is R (the largest |Ω| tested),
    in the rate unit. docs/model.md sections 11 and 14.
    """

    least_squares_max: float
    endpoint_max: float
    range: float


@dataclass(frozen=True, eq=False, repr=False)
class RateFit(Frozen):
    """The fit of one unit (docs/model.md section 14).

    ``names``/``values``/``covariance``: the eq. (2) coefficients (rate units,
    kn in rate^(1−n), m3i in 1/rate; k1 = 1 exactly, not among them), their
    covariance; ``sigma`` the standard uncertainties, ``correlation`` the
    correlation matrix (NaN where a σ is 0), ``t`` = value/σ.
    ``raw_names``/``raw_values``/``raw_covariance``: θ of eq. (1) in output
    units (K1 in output per rate, h = ½K1·A1); ``raw_sigma`` their standard
    uncertainties (finite even where a variance of outputs near 1e300 would not
    be). ``residuals`` = U − Û per point
    (output units), at the rates ``rates``; ``residual_rms`` = √(RSS/n);
    ``residual_sigma`` s = √(RSS/(n−p)).
    """

    order: int
    names: tuple[str, ...]
    values: FloatArray
    covariance: FloatArray
    raw_names: tuple[str, ...]
    raw_values: FloatArray
    raw_covariance: FloatArray
    rates: FloatArray
    residuals: FloatArray
    residual_rms: float
    residual_sigma: float
    nonlinearity: Nonlinearity
    points: int
    raw_sigma: FloatArray

    @property
    def sigma(self) -> FloatArray:
        """Standard uncertainties of :attr:`values`."""
        out: FloatArray = np.sqrt(np.clip(np.diag(self.covariance), 0.0, None))
        return out

    @property
    def correlation(self) -> FloatArray:
        """Correlation matrix of :attr:`values` (NaN in the rows of a zero σ)."""
        s = self.sigma
        with np.errstate(divide="ignore", invalid="ignore"):
            out: FloatArray = self.covariance / np.outer(s, s)
        np.fill_diagonal(out, np.where(s > 0, 1.0, np.nan))
        return out

    @property
    def t(self) -> FloatArray:
        """t = value/σ of each coefficient (±inf where σ = 0 and the value is not)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            out: FloatArray = self.values / self.sigma
        return out

    @property
    def significant(self) -> NDArray[np.bool_]:
        """|t| ≥ 2 per coefficient (docs/model.md section 14: smaller is "not significant")."""
        out: NDArray[np.bool_] = np.abs(self.t) >= SIGNIFICANT_T
        return out

    @property
    def scale_factor(self) -> float:
        """K1, output units per rate unit."""
        return float(self.raw_values[1])

    @property
    def scale_factor_sigma(self) -> float:
        """Standard uncertainty of K1."""
        return float(self.raw_sigma[1])

    def value(self, name: str) -> float:
        """One eq. (2) coefficient by name."""
        return float(self.values[self.names.index(name)])


def _levels(ordered: FloatArray, scale: float) -> FloatArray:
    """The distinct values of ``ordered`` (sorted, ≥ 0), those within 1e-9·scale merged."""
    if ordered.size == 0:
        return ordered
    keep = np.concatenate([[True], np.diff(ordered) > 1e-9 * scale])
    out: FloatArray = ordered[keep]
    return out


def _sign_problem(rate: FloatArray) -> str | None:
    """Why the rates cannot separate A1 from K1 (all of one sign), or None."""
    positive, negative = bool(np.any(rate > 0)), bool(np.any(rate < 0))
    if positive and negative:
        return None
    sign = "positive" if positive else "negative" if negative else "zero"
    wanted = "negative" if positive else "positive" if negative else "nonzero"
    return (f"every rate is {sign}: the asymmetry A1 (the |Ω| term) needs rates of both "
            f"signs; add runs at {wanted} rates")


def _level_problems(rate: FloatArray, order: int) -> list[str]:
    """Why the distinct |Ω| levels are too few for the even or the odd part at ``order``."""
    scale = float(np.max(np.abs(rate))) if rate.size else 0.0
    if not scale > 0:
        return []
    magnitudes = np.abs(rate)
    magnitudes.sort()  # in place: one copy of the rates, however many
    levels = _levels(magnitudes, scale)
    nonzero = levels[levels > 1e-9 * scale]
    even = ["K0", "h", *(f"K{k}" for k in range(2, order + 1, 2))]
    odd = [f"K{k}" if k > 1 else "K1" for k in range(1, order + 1, 2)]
    problems = []
    if levels.size < len(even):
        problems.append(
            f"order {order} needs at least {len(even)} distinct |Ω| levels (zero counts) for "
            f"the even part ({', '.join(even)}); the table has {levels.size}: add rates at "
            "other magnitudes, or fit a lower order")
    if nonzero.size < len(odd):
        problems.append(
            f"order {order} needs at least {len(odd)} distinct nonzero |Ω| levels for the odd "
            f"part ({', '.join(odd)}); the table has {nonzero.size}: add rates at other "
            "magnitudes, or fit a lower order")
    return problems


def check_identifiable(rate: FloatArray, order: int, p: int) -> None:
    """Raise :class:`IdentificationError` unless the rates can identify eq. (1) at ``order``
    with ``p`` parameters (both signs, enough |Ω| levels, n > p)."""
    n = rate.size
    sign = _sign_problem(rate)
    problems = ([] if sign is None else [sign]) + _level_problems(rate, order)
    if n <= p:
        problems.append(
            f"{n} point{'s' if n != 1 else ''} for {p} parameters: the fit needs more points "
            "than parameters (n > p) to estimate its uncertainty; repeat runs or add rates")
    if problems:
        raise IdentificationError("; ".join(problems))


#: Each scale undone on θ (R^−n, 1/max|ωi|, …) must stay within 10^±this, so that
#: its square times a variance as small as round-off (1e-32 of the output's square)
#: stays a normal double (about 1e±308): at R = 1e30 and order 5 the variance of
#: k5 of a near noise-free table underflowed to σ = 0.
MAX_DECADES = 100.0


def _check_magnitude(scale: float, order: int, column: str) -> None:
    """Raise :class:`IdentificationError` when ``scale``^±``order`` leaves 10^±
    :data:`MAX_DECADES`: the coefficient of the ``order``-th power of ``column``
    and its variance would not be double-precision numbers."""
    decades = -math.log10(scale) * order
    if abs(decades) <= MAX_DECADES:
        return
    if column == "rate":
        scaling = (f"at order {order} the fitted coefficients scale as its powers up to "
                   f"{order} (10^{decades:.0f})")
        remedy = "are the rates in the stated rate unit? (or fit a lower order)"
    else:
        scaling = f"the cross-axis coefficients scale as its inverse (10^{decades:.0f})"
        remedy = "are the cross rates in the stated rate unit?"
    raise IdentificationError(
        f"the largest |{column}| is {scale:.3g}: {scaling} and their variances as the "
        f"square of that, beyond double precision (about 1e±308); {remedy}")


#: Rows of the design matrix formed at once: the fit holds this many rows × p floats and
#: the (p + 1) × (p + 1) triangle R, never the n × p matrix (docs/performance.md).
BLOCK_ROWS = 1 << 16


@dataclass(frozen=True)
class _Scaling:
    """How the design is scaled: Ω over ``rate`` (its largest |Ω|), ωi over ``cross[i]``;
    ``unscale`` the factor of each parameter before the columns are normalised."""

    rate: float
    cross: FloatArray | None
    unscale: FloatArray


def _scaling(rate: FloatArray, order: int, cross: FloatArray | None,
             axes: tuple[int, ...]) -> _Scaling:
    """The scales of the design (:class:`_Scaling`), refusing those beyond double precision
    and a cross rate that never varies."""
    scale = float(np.max(np.abs(rate)))
    _check_magnitude(scale, order, "rate")
    unscale = [1.0, 1.0 / scale, 1.0 / scale, *(scale ** (-k) for k in range(2, order + 1))]
    if cross is None:
        return _Scaling(scale, None, np.asarray(unscale))
    cross_scale = np.max(np.abs(cross), axis=0)
    if np.any(cross_scale == 0):
        missing = [f"rate_x{i}" for i, s in zip(axes, cross_scale, strict=True) if s == 0]
        raise IdentificationError(
            f"{', '.join(missing)} is zero in every row: the cross-axis terms need runs "
            "with a cross rate; drop the column or add such runs")
    for i, s in zip(axes, cross_scale, strict=True):
        _check_magnitude(float(s), 1, f"rate_x{i}")
        _check_magnitude(scale * float(s), 1, f"rate|·|rate_x{i}")
    unscale += [1.0 / float(s) for s in cross_scale]
    unscale += [1.0 / (scale * float(s)) for s in cross_scale]
    return _Scaling(scale, cross_scale, np.asarray(unscale))


def _rows(rate: FloatArray, order: int, cross: FloatArray | None, scaling: _Scaling
          ) -> FloatArray:
    """The scaled design of these points, transposed (p, n) and before the columns are
    normalised: rows 1, x, |x|, x²…x^N, then yi and x·yi per cross axis (x = Ω/R,
    yi = ωi/max|ωi|)."""
    x = rate / scaling.rate
    columns = [np.ones_like(x), x, np.abs(x)]
    power = x
    for _ in range(2, order + 1):
        power = power * x  # products, not x**k: numpy's pow is ~100 times slower
        columns.append(power)
    if cross is not None and scaling.cross is not None:
        y = cross / scaling.cross
        columns += [y[:, i] for i in range(y.shape[1])]
        columns += [x * y[:, i] for i in range(y.shape[1])]
    return np.stack(columns)


def _blocks(rate: FloatArray, v: FloatArray, order: int, cross: FloatArray | None,
            scaling: _Scaling) -> Iterator[tuple[FloatArray, FloatArray]]:
    """The scaled design (before normalisation, transposed: :func:`_rows`) and v,
    :data:`BLOCK_ROWS` points at a time."""
    for start in range(0, rate.size, BLOCK_ROWS):
        stop = start + BLOCK_ROWS
        w = None if cross is None else cross[start:stop]
        yield _rows(rate[start:stop], order, w, scaling), v[start:stop]


def _householder(rate: FloatArray, v: FloatArray, order: int, cross: FloatArray | None,
                 scaling: _Scaling) -> tuple[FloatArray, FloatArray]:
    """R (p × p) and Qᵀv of the QR factorisation of X, by Householder QR of [X | v] block by
    block: R of [R_previous; block] is R of every row so far. Householder QR does not
    depend on the scale of the columns, so X is normalised afterwards, on R."""
    r: FloatArray = np.zeros((0, 0))
    for rows, values in _blocks(rate, v, order, cross, scaling):
        block = np.vstack([rows, values]).T
        stacked = block if r.size == 0 else np.vstack([r, block])
        r = np.asarray(np.linalg.qr(stacked, mode="r"), dtype=float)  # mode "r": R alone
    p = r.shape[1] - 1
    return r[:p, :p], r[:p, p]


def _gram(rate: FloatArray, v: FloatArray, order: int, cross: FloatArray | None,
          scaling: _Scaling, right: FloatArray | None = None) -> tuple[FloatArray, FloatArray]:
    """AᵀA and Aᵀv for A = X·``right`` (X the scaled design; X itself when None), summed
    block by block."""
    p = len(scaling.unscale)
    gram = np.zeros((p, p))
    moment = np.zeros(p)
    for rows, values in _blocks(rate, v, order, cross, scaling):
        a = rows if right is None else right.T @ rows  # Aᵀ, (p, block)
        gram += a @ a.T
        moment += a @ values
    return gram, moment


def _cholesky_qr(rate: FloatArray, v: FloatArray, order: int, cross: FloatArray | None,
                 scaling: _Scaling) -> tuple[FloatArray, FloatArray] | None:
    """R (p × p) and Qᵀv of X = Q·R by CholeskyQR2 (two passes of matrix products, the
    blocks formed anew): R1 the Cholesky factor of D⁻¹·XᵀX·D⁻¹ (D the column norms of
    X), R2 that of the same product of X·D⁻¹·R1⁻¹; R = R2·R1·D, Qᵀv = R2⁻ᵀ·(X·D⁻¹·R1⁻¹)ᵀv.
    As accurate as Householder QR while the scaled design's condition number is below
    about 1e7 (Yamamoto et al. 2015); None beyond, for :func:`_householder`."""
    p = len(scaling.unscale)
    gram, _ = _gram(rate, v, order, cross, scaling)
    diagonal = np.sqrt(np.diag(gram))
    diagonal[diagonal == 0] = 1.0
    try:
        r1 = np.linalg.cholesky(gram / np.outer(diagonal, diagonal)).T
        right = np.linalg.inv(r1 * diagonal)  # X·right = X·D⁻¹·R1⁻¹, near orthogonal
        gram2, moment = _gram(rate, v, order, cross, scaling, right)
        r2 = np.linalg.cholesky(gram2).T
    except np.linalg.LinAlgError:
        return None
    if not (np.all(np.isfinite(r2)) and np.linalg.norm(gram2 - np.eye(p)) < 1e-2):
        return None
    return np.asarray((r2 @ r1) * diagonal, dtype=float), np.linalg.solve(r2.T, moment)


def _factor(rate: FloatArray, v: FloatArray, order: int, cross: FloatArray | None,
            scaling: _Scaling) -> tuple[FloatArray, FloatArray, FloatArray]:
    """R of the scaled design with normalised columns, Qᵀv and the column norms."""
    quick = _cholesky_qr(rate, v, order, cross, scaling)
    if quick is None:
        r, qtv = _householder(rate, v, order, cross, scaling)
    else:
        r, qtv = quick
    norms = np.linalg.norm(r, axis=0)
    norms[norms == 0] = 1.0
    return r / norms, qtv, norms


def _residuals(rate: FloatArray, v: FloatArray, order: int, cross: FloatArray | None,
               scaling: _Scaling, beta: FloatArray) -> FloatArray:
    """v − X·β per point, block by block (X the scaled design before normalisation)."""
    out = np.empty_like(v)
    start = 0
    for rows, values in _blocks(rate, v, order, cross, scaling):
        out[start:start + values.size] = values - beta @ rows
        start += values.size
    return out


def _inputs(rate: ArrayLike, output: ArrayLike, order: int, cross: ArrayLike | None,
            cross_axes: Sequence[int] | None
            ) -> tuple[FloatArray, FloatArray, FloatArray | None, tuple[int, ...]]:
    """The points as float arrays, checked: Ω (n,), U (n,), ω (n, k) or None, the axes."""
    omega = np.asarray(rate, dtype=float).ravel()
    u = np.asarray(output, dtype=float).ravel()
    if omega.shape != u.shape:
        raise ValueError("rate and output must have the same length")
    if not (isinstance(order, int | np.integer) and 1 <= order <= MAX_ORDER):
        raise IdentificationError(f"the order must be 1 to {MAX_ORDER} (eq. 1), not {order!r}")
    if not (np.all(np.isfinite(omega)) and np.all(np.isfinite(u))):
        raise IdentificationError("the rates and outputs must be finite numbers")
    if cross is None:
        return omega, u, None, ()
    w = np.asarray(cross, dtype=float).reshape(omega.size, -1)
    axes = tuple(cross_axes) if cross_axes is not None else tuple(range(1, w.shape[1] + 1))
    if len(axes) != w.shape[1] or not set(axes) <= {1, 2} or len(set(axes)) != len(axes):
        raise ValueError("cross must have one column per axis of cross_axes (1, 2)")
    if not np.all(np.isfinite(w)):
        raise IdentificationError("the cross rates must be finite numbers")
    return omega, u, w, axes


def _output_scale(u: FloatArray) -> float:
    """A power of two near the largest |U| (exact division): RSS neither overflows nor
    underflows; eq. (2) is a ratio and does not see the scale."""
    top = float(np.max(np.abs(u)))
    return math.ldexp(1.0, math.frexp(top)[1] - 1) if top > 0 else 1.0


def fit_rate_table(rate: ArrayLike, output: ArrayLike, order: int = DEFAULT_ORDER,
                   cross: ArrayLike | None = None,
                   cross_axes: Sequence[int] | None = None) -> RateFit:
    """Least-squares fit of eq. (1) to one unit's rate-table points (docs/model.md section 14).

    ``rate``: Ω per point (n,), any rate unit; ``output``: mean output U (n,),
    any output unit; ``cross``: (n, k) applied cross rates in the rate unit about
    the axes ``cross_axes`` (default 1..k; e.g. ``(2,)`` for ω2 alone), or None
    (no cross-axis terms); ``order``: N, 1 to 5.
    Returns the eq. (2) coefficients with their delta-method covariance
    (see the module docstring). Raises :class:`IdentificationError` when the
    data cannot identify the model.
    """
    omega, u, w, axes = _inputs(rate, output, order, cross, cross_axes)
    names_raw = raw_names(order, axes)
    p = len(names_raw)
    check_identifiable(omega, order, p)
    scaling = _scaling(omega, order, w, axes)
    out_scale = _output_scale(u)
    v = u / out_scale
    r, qtv, norms = _factor(omega, v, order, w, scaling)
    _check_rank(r, names_raw)
    beta = np.linalg.solve(r, qtv)
    scaled_residuals = _residuals(omega, v, order, w, scaling, beta / norms)
    n = omega.size
    rss = float(scaled_residuals @ scaled_residuals)
    s2 = rss / (n - p)
    r_inv = np.linalg.solve(r, np.eye(p))
    factor = scaling.unscale / norms
    theta = beta * factor
    cov_theta = s2 * (r_inv @ r_inv.T) * np.outer(factor, factor)
    values, covariance = to_rate_form(theta, cov_theta, order, axes, out_scale)
    _check_finite(values, covariance, s2)
    with np.errstate(over="ignore"):
        raw_values = theta * out_scale
        raw_covariance = cov_theta * out_scale * out_scale  # inf beyond ~1e154
        raw_sigma = np.sqrt(np.clip(np.diag(cov_theta), 0.0, None)) * out_scale
    return RateFit(
        order=order,
        names=rate_names(order, axes),
        values=values,
        covariance=covariance,
        raw_names=names_raw,
        raw_values=raw_values,
        raw_covariance=raw_covariance,
        rates=omega,
        residuals=scaled_residuals * out_scale,
        residual_rms=float(np.sqrt(rss / n)) * out_scale,
        residual_sigma=float(np.sqrt(s2)) * out_scale,
        nonlinearity=nonlinearity(values, rate_names(order, axes), scaling.rate),
        points=n,
        raw_sigma=raw_sigma,
    )


def _check_finite(values: FloatArray, covariance: FloatArray, s2: float) -> None:
    """Refuse coefficients or variances that are not finite doubles, or variances that
    underflowed to 0 where the residuals are not 0."""
    lost = s2 > 0 and bool(np.any(np.diag(covariance) < np.finfo(float).tiny))
    if lost or not (np.all(np.isfinite(values)) and np.all(np.isfinite(covariance))):
        raise IdentificationError(
            "the coefficients or their variances are not finite double-precision numbers "
            "(rates or outputs of extreme magnitude); are the columns in the stated "
            "units?")


def _check_rank(r: FloatArray, names: tuple[str, ...]) -> None:
    """Raise when the scaled design matrix is (numerically) rank deficient, naming the
    parameters that the data cannot tell apart (the null direction's main entries).
    ``r``: the R of its QR factorisation (the same singular values and directions)."""
    _, singular, vt = np.linalg.svd(r, full_matrices=False)
    small = singular <= singular[0] / MAX_CONDITION
    if not np.any(small):
        return
    groups = []
    for vector in vt[small]:
        null = np.abs(vector)
        groups.append(", ".join(n for n, v in zip(names, null, strict=True)
                                if v > 0.1 * null.max()))
    raise IdentificationError(
        "the rates do not separate the terms " + "; nor ".join(sorted(groups)) + " of eq. (1) "
        "(their columns are linearly dependent on these points): add runs at other rates or "
        "cross rates, or fit a lower order")


def to_rate_form(theta: FloatArray, cov_theta: FloatArray, order: int,
                 axes: Sequence[int] = (), output_scale: float = 1.0
                 ) -> tuple[FloatArray, FloatArray]:
    """Eq. (1) parameters θ (:func:`raw_names` order) to the eq. (2) coefficients
    (:func:`rate_names` order) by division by K1, with the covariance J·Cov(θ)·Jᵀ.
    θ may be in output units over ``output_scale`` (only the message of a K1 that
    is not significant uses it: eq. (2) does not depend on it)."""
    k1 = float(theta[1])
    sigma_k1 = float(np.sqrt(max(cov_theta[1, 1], 0.0)))
    if k1 == 0.0 or not np.isfinite(k1) or abs(k1) < SIGNIFICANT_T * sigma_k1:
        raise IdentificationError(
            f"the output does not follow the rate (K1 = {k1 * output_scale:.4g} ± "
            f"{sigma_k1 * output_scale:.3g}): eq. (2) divides by K1; check the rate and "
            "output columns")
    numerators = [0, *range(2, theta.size)]  # K0, h, K2..KN, M…: all but K1
    factors = np.ones(len(numerators))
    factors[1] = 2.0  # A1 = 2h/K1
    values = factors * theta[numerators] / k1
    jac = np.zeros((len(numerators), theta.size))
    jac[np.arange(len(numerators)), numerators] = factors / k1
    jac[:, 1] = -values / k1
    covariance = jac @ cov_theta @ jac.T
    covariance = 0.5 * (covariance + covariance.T)
    return values, covariance


def _moment_line(coefficients: FloatArray, kink: float) -> tuple[float, float]:
    """The least-squares line a + b·u of q(u) = Σ c_n uⁿ + kink·|u| over uniform u ∈ [−1, 1]:
    a = ½∫q, b = (3/2)∫u·q (∫uⁿ = 2/(n+1) for even n, ∫|u| = 1, ∫u|u| = 0)."""
    n = np.arange(coefficients.size)
    even = n % 2 == 0
    mean = float(np.sum(coefficients[even] / (n[even] + 1))) + 0.5 * kink
    slope = 1.5 * float(np.sum(coefficients[~even] * 2.0 / (n[~even] + 2)))
    return mean, slope


def _max_abs_piecewise(coefficients: FloatArray, kink: float, line: tuple[float, float]
                       ) -> float:
    """max over u ∈ [−1, 1] of |q(u) − a − b·u|, q as in :func:`_moment_line`: on each half
    the residual is a polynomial, so its maximum is at ±1, 0 or a root of its derivative."""

    best = 0.0
    for side in (1.0, -1.0):
        poly = coefficients.copy()
        poly[0] -= line[0]
        poly[1] += side * kink - line[1]  # |u| = side·u on this half
        candidates = [0.0, side]
        deriv = P.polyder(poly)
        if deriv.size > 1 and np.any(deriv[1:] != 0):
            roots = P.polyroots(P.polytrim(deriv))
            real = roots[np.abs(roots.imag) <= 1e-9].real
            candidates += [float(v) for v in real if 0.0 <= side * v <= 1.0]
        best = max(best, float(np.max(np.abs(P.polyval(np.asarray(candidates), poly)))))
    return best


def nonlinearity(values: ArrayLike, names: Sequence[str], span: float) -> Nonlinearity:
    """The nonlinearity in %FS of the eq. (2) curve p(ω) = k0 + ω + ½A1|ω| + Σ kn·ωⁿ
    (cross rates 0) over [−R, R], R = ``span`` (see :class:`Nonlinearity`).

    In u = ω/R, q(u) = p(R·u)/R = k0/R + u + ½A1|u| + Σ kn·R^(n−1)·uⁿ; the deviation
    from a line, in %FS, is 100·max|q − L| — exactly, from the critical points of
    the residual on each half (it is a polynomial there).
    """
    c = np.asarray(values, dtype=float)
    coefficient = dict(zip(names, c, strict=True))
    poly = np.zeros(MAX_ORDER + 1)
    poly[0] = coefficient.get("k0", 0.0) / span
    poly[1] = 1.0
    for k in range(2, MAX_ORDER + 1):
        if f"k{k}" in coefficient:  # R^(k−1) of an absent term may overflow (R ~ 1e100)
            poly[k] = coefficient[f"k{k}"] * span ** (k - 1)
    kink = 0.5 * coefficient.get("A1", 0.0)
    ls = _moment_line(poly, kink)
    q_plus = float(np.sum(poly)) + kink
    q_minus = float(np.sum(poly * (-1.0) ** np.arange(poly.size))) + kink
    endpoint = (0.5 * (q_plus + q_minus), 0.5 * (q_plus - q_minus))
    return Nonlinearity(
        least_squares_max=100.0 * _max_abs_piecewise(poly, kink, ls),
        endpoint_max=100.0 * _max_abs_piecewise(poly, kink, endpoint),
        range=float(span),
    )
