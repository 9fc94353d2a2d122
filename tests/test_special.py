"""gyrovib.core.special.erfc against the reference, math.erfc (the C library's erfc),
value by value."""

import math

import numpy as np
import pytest

from gyrovib.core.special import _BLOCK, erfc

#: The bound of the module's docstring: W. J. Cody's approximations evaluated in
#: double precision, a few units in the last place.
REL = 1e-15


def _reference(x: np.ndarray) -> np.ndarray:
    return np.array([math.erfc(v) for v in x.tolist()])


def _grid() -> np.ndarray:
    """A dense grid over every branch and its edges: x ≤ −0.46875 (2 − erfc|x|),
    |x| ≤ 0.46875, (0.46875, 4], (4, 27.3) up to the underflow, tiny |x|."""
    return np.concatenate([
        np.linspace(-6.5, 27.5, 400_001),          # step 8.5e-5
        np.linspace(-0.47, 0.47, 20_001),          # both sides of the first break
        np.linspace(3.99, 4.01, 20_001),           # the second break
        np.linspace(25.5, 26.6, 20_001),           # erfc ≈ 1e-285 … 1e-309
        np.geomspace(1e-300, 1e-3, 2_001), -np.geomspace(1e-300, 1e-3, 2_001),
        np.nextafter(np.array([0.46875, 0.46875, 4.0, 4.0]),
                     np.array([0.0, 1.0, 0.0, 5.0])),
    ])


def test_erfc_matches_math_erfc_on_a_dense_grid() -> None:
    x = _grid()
    ref = _reference(x)
    got = erfc(x)
    normal = ref > 1e-300
    rel = np.abs(got[normal] - ref[normal]) / ref[normal]
    assert rel.max() <= REL, (rel.max(), x[normal][np.argmax(rel)])
    # where erfc(x) ≤ 1e-300 (subnormal results, then 0) the absolute error is tiny
    assert np.abs(got[~normal] - ref[~normal]).max() <= 1e-300


def test_erfc_random_points_and_shapes() -> None:
    rng = np.random.default_rng(20)
    x = rng.uniform(-8.0, 28.0, size=(300, 7))
    ref = _reference(x.ravel()).reshape(x.shape)
    got = erfc(x)
    assert got.shape == x.shape
    normal = ref > 1e-300
    assert np.all(np.abs(got - ref)[normal] <= REL * ref[normal])


def test_erfc_across_blocks_equals_one_call_per_value() -> None:
    # arrays longer than a block are evaluated block by block: same values
    x = np.linspace(-3.0, 6.0, 2 * _BLOCK + 17)
    whole = erfc(x)
    assert np.array_equal(whole, np.concatenate([erfc(x[i:i + 1000])
                                                 for i in range(0, x.size, 1000)]))


@pytest.mark.parametrize(("x", "expected"), [
    (0.0, 1.0), (-0.0, 1.0), (math.inf, 0.0), (-math.inf, 2.0), (40.0, 0.0), (-40.0, 2.0),
    (1e-320, 1.0),
])
def test_erfc_special_values(x: float, expected: float) -> None:
    value = erfc(x)
    assert value.shape == ()
    assert float(value) == expected


def test_erfc_nan_stays_nan_and_the_others_are_untouched() -> None:
    got = erfc(np.array([math.nan, 1.0, -math.nan, -2.0]))
    assert np.isnan(got[0]) and np.isnan(got[2])
    assert got[1] == pytest.approx(math.erfc(1.0), rel=REL)
    assert got[3] == pytest.approx(math.erfc(-2.0), rel=REL)


def test_erfc_of_one_branch_only() -> None:
    # a whole array in one branch takes the no-indexing path: same values
    for lo, hi in ((-0.4, 0.4), (0.5, 3.9), (4.5, 26.0), (-3.9, -0.5)):
        x = np.linspace(lo, hi, 1001)
        ref = _reference(x)
        assert np.all(np.abs(erfc(x) - ref) <= REL * ref)
