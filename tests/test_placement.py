"""Placements (docs/model.md section 12): signed permutations of the axes, checked by hand."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from gyrovib.core import placement as pl
from gyrovib.core.mission import combined_functional, totals

# All 24 proper signed permutations (48 signed permutations, half with det +1).
PROPER = [
    p for perm in itertools.permutations(range(3)) for signs in itertools.product((1, -1), repeat=3)
    if round(np.linalg.det(np.eye(3)[list(perm)] * np.array(signs)[:, None])) == 1
    for p in [pl.Placement(perm, signs)]  # type: ignore[arg-type]
]


def test_there_are_24_rotations() -> None:
    # The rotation group of the cube has order 24.
    assert len(PROPER) == 24


def test_default_maps_everything_to_itself() -> None:
    v = np.array([1.5, -2.0, 3.0])
    assert pl.DEFAULT.is_default
    np.testing.assert_array_equal(pl.DEFAULT.signed(v), v)
    np.testing.assert_array_equal(pl.DEFAULT.phases([10.0, 20.0, 30.0]), [10.0, 20.0, 30.0])
    assert pl.DEFAULT.rate_coherence(0.3, -0.4, 0.5) == (0.3, -0.4, 0.5)


def test_cyclic_permutation_by_hand() -> None:
    # x1 = +Y, x2 = +Z, x3 = +X: sensor axis i reads vehicle axis (Y, Z, X)[i].
    p = pl.parse("x1=+Y, x2=+Z, x3=+X")
    assert isinstance(p, pl.Placement) and p.axis == "X"
    np.testing.assert_array_equal(p.signed([1.0, 2.0, 3.0]), [2.0, 3.0, 1.0])
    np.testing.assert_array_equal(p.phases([0.0, 30.0, 60.0]), [30.0, 60.0, 0.0])
    # Vehicle ρ_ZX = 0.3, ρ_ZY = 0.4, ρ_XY = 0.5. Sensor ρ31 = ρ(X, Y) = 0.5,
    # ρ32 = ρ(X, Z) = 0.3, ρ12 = ρ(Y, Z) = 0.4.
    assert p.rate_coherence(0.3, 0.4, 0.5) == pytest.approx((0.5, 0.3, 0.4))


def test_flipped_axis_by_hand() -> None:
    # x1 = -Y, x2 = +X, x3 = +Z: a quarter turn about Z; x1 is the flipped Y.
    p = pl.parse("x1=-Y,x2=+X,x3=+Z")
    np.testing.assert_array_equal(p.signed([1.0, 2.0, 3.0]), [-2.0, 1.0, 3.0])
    np.testing.assert_array_equal(p.magnitudes([1.0, 2.0, 3.0]), [2.0, 1.0, 3.0])
    # The flipped axis's phase moves by 180 degrees.
    np.testing.assert_array_equal(p.phases([0.0, 30.0, 60.0]), [210.0, 0.0, 60.0])
    # ρ31 = ρ(Z, -Y) = -ρ_ZY = -0.4; ρ32 = ρ(Z, X) = 0.3; ρ12 = ρ(-Y, X) = -0.5.
    assert p.rate_coherence(0.3, 0.4, 0.5) == pytest.approx((-0.4, 0.3, -0.5))


def test_omitted_rho12_is_the_product() -> None:
    # docs/model.md section 12: an omitted ρ12 is ρ31·ρ32.
    p = pl.parse("x1=+Y,x2=+Z,x3=+X")
    assert isinstance(p, pl.Placement)
    assert p.rate_coherence(0.6, 0.5)[0] == pytest.approx(0.3)


def test_triad_puts_x3_on_each_axis() -> None:
    assert [p.axis for p in pl.TRIAD] == ["X", "Y", "Z"]
    assert [str(p) for p in pl.TRIAD] == [
        "x1=+Y,x2=+Z,x3=+X", "x1=+Z,x2=+X,x3=+Y", "x1=+X,x2=+Y,x3=+Z"]
    assert pl.parse("triad") == pl.TRIAD


@pytest.mark.parametrize("text", ["x1=+Y,x2=+X,x3=+Z", "x1=-X,x2=+Y,x3=+Z"])
def test_mirror_images_are_refused(text: str) -> None:
    with pytest.raises(ValueError, match="determinant -1"):
        pl.parse(text)


@pytest.mark.parametrize("text, words", [
    ("x1=+Y,x2=+Y,x3=+X", "different vehicle axes"),
    ("x1=+Y,x2=+Z", "missing x3"),
    ("x1=+Y,x1=+Z,x3=+X", "placed twice"),
    ("x4=+X", "cannot read"),
])
def test_bad_placements_say_why(text: str, words: str) -> None:
    with pytest.raises(ValueError, match=words):
        pl.parse(text)


@given(st.sampled_from(PROPER), st.lists(st.floats(-1e3, 1e3), min_size=3, max_size=3),
       st.lists(st.floats(-180, 180), min_size=3, max_size=3))
def test_mapping_is_the_rotation_matrix(p: pl.Placement, v: list[float], ph: list[float]) -> None:
    # Signed data transform as x = P·V; a tone a·sin(ωt + φ) on a flipped axis is
    # -a·sin(ωt + φ) = a·sin(ωt + φ + 180°), so the phasor a·exp(jφ) maps as P·V too.
    vec = np.array(v)
    np.testing.assert_allclose(p.signed(vec), p.matrix @ vec, atol=0)
    amp = np.abs(vec)
    phasor = amp * np.exp(1j * np.deg2rad(ph))
    mapped = p.magnitudes(amp) * np.exp(1j * np.deg2rad(p.phases(ph)))
    np.testing.assert_allclose(mapped, p.matrix @ phasor, atol=1e-9 * (1 + amp.max()))
    assert p.determinant == pytest.approx(1.0)


@given(st.sampled_from(PROPER), st.integers(0, 2**32 - 1))
def test_correlation_follows_the_samples(p: pl.Placement, seed: int) -> None:
    # The correlation of P·V for samples V is P·R·Pᵀ: checked on the sample
    # correlation itself (the map is exact, so the two agree to rounding).
    rng = np.random.default_rng(seed)
    v = rng.standard_normal((3, 64))
    v[2] += 0.5 * v[0]
    r = np.corrcoef(v)
    np.testing.assert_allclose(p.correlation(r), np.corrcoef(p.matrix @ v), atol=1e-12)
    rho = p.rate_coherence(r[2, 0], r[2, 1], r[0, 1])
    s = np.corrcoef(p.matrix @ v)
    assert rho == pytest.approx((s[2, 0], s[2, 1], s[0, 1]), abs=1e-12)


def test_mission_totals_by_hand() -> None:
    # Two segments, 10 s at Δ = 1 and 30 s at Δ = -2 (RMS 2 and 3):
    # mean (10 - 60)/40 = -1.25; angle -50; mean RMS √((10·4 + 30·9)/40) = √7.75.
    m = totals([10.0, 30.0], [[1.0, -2.0]], [[2.0, 3.0]])
    assert m.mean[0] == pytest.approx(-1.25)
    assert m.angle[0] == pytest.approx(-50.0)
    assert m.rms[0] == pytest.approx(math.sqrt(7.75))
    assert (m.worst_index[0], m.worst_total[0]) == (1, -2.0)
    # deg/h over seconds: 1/3600 deg per (deg/h · s).
    assert totals([3600.0], [[2.0]], [[2.0]], 1 / 3600).angle[0] == pytest.approx(2.0)


@given(st.lists(st.floats(0.1, 1e4), min_size=1, max_size=5),
       st.lists(st.floats(-10, 10), min_size=5, max_size=5), st.floats(0.01, 0.99))
def test_splitting_a_segment_changes_nothing(t: list[float], d: list[float], f: float) -> None:
    n = len(t)
    d = d[:n]
    whole = totals(t, [d], [np.abs(d)])
    split = totals([t[0] * f, t[0] * (1 - f), *t[1:]], [[d[0], d[0], *d[1:]]],
                   [np.abs([d[0], d[0], *d[1:]])])
    assert split.mean[0] == pytest.approx(whole.mean[0], rel=1e-12, abs=1e-12)
    assert split.angle[0] == pytest.approx(whole.angle[0], rel=1e-12, abs=1e-9)
    assert split.rms[0] == pytest.approx(whole.rms[0], rel=1e-12)


def test_combined_functional_is_the_duration_weighted_mean() -> None:
    c = np.arange(2 * 8 * 5, dtype=float).reshape(2, 8, 5)
    out = combined_functional([1.0, 3.0], c)
    np.testing.assert_allclose(out, 0.25 * c[0] + 0.75 * c[1])


@pytest.mark.parametrize("bad", [[], [0.0], [-1.0, 2.0], [math.inf]])
def test_durations_are_checked(bad: list[float]) -> None:
    with pytest.raises(ValueError):
        totals(bad, np.zeros((1, len(bad))), np.zeros((1, len(bad))))
