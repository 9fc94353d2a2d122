"""erfc over arrays: W. J. Cody's rational approximations, evaluated by numpy.

numpy has no error function, and scipy is an optional extra (start-up would
pay for its import). Calling :func:`math.erfc` once per value
(``np.frompyfunc``) costs ~0.1 µs a value in Python objects, which the
E(Ω) kernels pay over arrays of millions of values; this module evaluates the
same function with a few whole-array operations.

W. J. Cody, "Rational Chebyshev approximations for the error function",
Math. Comp. 23 (1969) 631-637, as implemented in his SPECFUN routine CALERF
(netlib, specfun/calerf.f; the coefficients below are copied from it):

* |x| ≤ 0.46875:  erfc(x) = 1 − x·R₁(x²), R₁ of degree (4, 4);
* 0.46875 < |x| ≤ 4:  erfc(|x|) = exp(−x²)·R₂(|x|), R₂ of degree (8, 8);
* |x| > 4:  erfc(|x|) = exp(−x²)/|x| · (1/√π − z·R₃(z)), z = 1/x², R₃ of degree (5, 4);
* x < −0.46875:  erfc(x) = 2 − erfc(|x|).

exp(−x²) is formed as exp(−y²)·exp(−(x−y)(x+y)) with y = x rounded down to a
multiple of 1/16, so that the rounding of x² (an absolute error of up to
x²·2⁻⁵³ in the exponent, i.e. 26²·1.1e-16 = 7.5e-14 relative near the
underflow) does not reach the result. Checked against :func:`math.erfc` on a
dense grid over [−6, 27] (tests/test_special.py): relative error below 1e-15
(a few units in the last place) wherever erfc(x) > 1e-300.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from gyrovib.core._types import FloatArray

_THRESH = 0.46875
#: Past this, erfc(x) < 4.9e-324, the smallest subnormal: 0.
_XMAX = 27.3
_SQRPI = 5.6418958354775628695e-1  # 1/√π

# |x| ≤ 0.46875
_A = (3.16112374387056560e00, 1.13864154151050156e02, 3.77485237685302021e02,
      3.20937758913846947e03, 1.85777706184603153e-1)
_B = (2.36012909523441209e01, 2.44024637934444173e02, 1.28261652607737228e03,
      2.84423683343917062e03)
# 0.46875 < |x| ≤ 4
_C = (5.64188496988670089e-1, 8.88314979438837594e00, 6.61191906371416295e01,
      2.98635138197400131e02, 8.81952221241769090e02, 1.71204761263407058e03,
      2.05107837782607147e03, 1.23033935479799725e03, 2.15311535474403846e-8)
_D = (1.57449261107098347e01, 1.17693950891312499e02, 5.37181101862009858e02,
      1.62138957456669019e03, 3.29079923573345963e03, 4.36261909014324716e03,
      3.43936767414372164e03, 1.23033935480374942e03)
# |x| > 4
_P = (3.05326634961232344e-1, 3.60344899949804439e-1, 1.25781726111229246e-1,
      1.60837851487422766e-2, 6.58749161529837803e-4, 1.63153871373020978e-2)
_Q = (2.56852019228982242e00, 1.87295284992346725e00, 5.27905102951428412e-1,
      6.05183413124413191e-2, 2.33520497626869185e-3)


def _exp_minus_square(y: FloatArray) -> FloatArray:
    """exp(−y²) without the rounding error of y² (Cody's split at a multiple of 1/16)."""
    head = np.trunc(y * 16.0)
    head /= 16.0
    tail = y - head
    tail *= y + head
    np.negative(tail, out=tail)
    np.exp(tail, out=tail)
    head *= head
    np.negative(head, out=head)
    np.exp(head, out=head)
    head *= tail
    return head


def _horner(t: FloatArray, num: tuple[float, ...], den: tuple[float, ...]) -> FloatArray:
    """Cody's ``(((n₀·t + n₁)·t + …)·t + n_k) / (((t + d₁)·t + …)·t + d_k)`` in place:
    ``num`` from the highest degree's coefficient down, ``den`` without its leading 1."""
    p = num[0] * t
    q = t.copy()
    for a, b in zip(num[1:-1], den[:-1], strict=True):
        p += a
        p *= t
        q += b
        q *= t
    p += num[-1]
    q += den[-1]
    p /= q
    return p


def _small(x: FloatArray) -> FloatArray:
    """erfc(x) for |x| ≤ 0.46875 (either sign): 1 − x·R₁(x²)."""
    r = _horner(x * x, (_A[4], *_A[:4]), _B)
    r *= x
    np.subtract(1.0, r, out=r)
    return r


def _middle(y: FloatArray) -> FloatArray:
    """erfc(y) for 0.46875 < y ≤ 4: exp(−y²)·R₂(y)."""
    r = _horner(y, (_C[8], *_C[:8]), _D)
    r *= _exp_minus_square(y)
    return r


def _large(y: FloatArray) -> FloatArray:
    """erfc(y) for 4 < y < 27.3: exp(−y²)/y · (1/√π − z·R₃(z)), z = 1/y²."""
    z = y * y
    np.reciprocal(z, out=z)
    r = _horner(z, (_P[5], *_P[:5]), _Q)
    r *= z
    np.subtract(_SQRPI, r, out=r)
    r /= y
    r *= _exp_minus_square(y)
    return r


#: Values evaluated at a time: the temporaries of a block stay in the CPU's cache.
_BLOCK = 1 << 15


def _erfc_block(x: FloatArray) -> FloatArray:
    """erfc over a 1-D block (see :func:`erfc`)."""
    y = np.abs(x)
    out = np.zeros_like(x)  # |x| ≥ 27.3 (and ±inf): erfc(|x|) underflows to 0
    small = y <= _THRESH
    middle = (y <= 4.0) & ~small
    large = ~(y <= 4.0) & ~(y >= _XMAX)  # NaN falls here and stays NaN
    with np.errstate(under="ignore"):
        for region, part in ((small, _small), (middle, _middle), (large, _large)):
            if region.all():
                out = part(x if part is _small else y)
            elif region.any():
                out[region] = part((x if part is _small else y)[region])
    np.subtract(2.0, out, out=out, where=x < -_THRESH)
    return out


def erfc(x: ArrayLike) -> FloatArray:
    """The complementary error function ``erfc(x) = (2/√π)·∫ₓ^∞ exp(−t²) dt``, elementwise.

    A float array of the shape of ``x``; NaN stays NaN, erfc(−∞) = 2, erfc(∞) = 0.
    Relative error below 1e-15 against :func:`math.erfc` where erfc(x) > 1e-300
    (Cody's approximations, see the module's docstring).
    """
    v = np.asarray(x, dtype=float)
    flat = v.reshape(-1)
    if flat.size <= _BLOCK:
        return _erfc_block(flat).reshape(v.shape)
    out = np.empty_like(flat)
    for start in range(0, flat.size, _BLOCK):
        out[start:start + _BLOCK] = _erfc_block(flat[start:start + _BLOCK])
    result: FloatArray = out.reshape(v.shape)
    return result
