"""The bundled ``*-vre-test`` profiles reproduce their data sheets' VRE tests.

A data sheet's vibration rectification (VRE) is measured on a shaker, one axis
at a time: the rectified error per g² of that one axis's vibration. The bundled
test profiles apply the stated level to the tested axis alone, so a part with
its datasheet VRE v errs by exactly v·σ² there (docs/model.md section 8: Δ0(6) =
Σ_j G_jj·⟨a_j²⟩ with ⟨a_3²⟩ = σ², the others 0). The figures, from
/work/shared/data/DATASHEETS.md (the project's record of the public data sheets):

* ADIS16460 (Rev. B, Table 1): VRE ±0.0004 °/s/g² at 5 g rms, 20–2000 Hz →
  0.0004 × 5² = 0.01 °/s;
* ADXRS645 (Rev. C, Table 1): VRE 0.0006 °/s/g² at 25 g rms, 50 Hz–5 kHz →
  0.0006 × 25² = 0.375 °/s.
"""

from __future__ import annotations

import numpy as np
import pytest

import gyrovib

#: part id → (datasheet VRE in deg/s/g², test level σ in g rms): DATASHEETS.md
DATASHEET = {"adis16460": (0.0004, 5.0), "adxrs645": (0.0006, 25.0)}


@pytest.mark.parametrize("part", sorted(DATASHEET))
def test_the_vre_test_profile_gives_vre_times_level_squared(part: str) -> None:
    vre, level = DATASHEET[part]
    result = gyrovib.analyze(sensors=part, profiles=f"{part}-vre-test")
    # a flat PSD S over [f1, f2] written to 6 figures: σ² = S·(f2 − f1) = 25/1980·1980
    # to 5e-6 relative; no angular vibration and no rate, so the worst case is the g²
    # term alone: |v|·σ²
    assert float(result.error.total[0, 0]) == pytest.approx(vre * level**2, rel=1e-5)
    assert float(result.error.extra_terms[0, 0, 0]) == pytest.approx(vre * level**2, rel=1e-5)


def test_every_bundled_vre_test_shakes_one_axis() -> None:
    catalog = gyrovib.load()
    tests = [e for e in catalog.profiles if e.profile.id.endswith("-vre-test")]
    assert {e.profile.id for e in tests} == {f"{part}-vre-test" for part in DATASHEET}
    from gyrovib.api.study.linear import profile_linear

    for entry in tests:
        linear = profile_linear(entry)
        assert linear is not None
        moments = linear.moments()  # ⟨a1²⟩, ⟨a2²⟩, ⟨a3²⟩, then the cross terms
        _, level = DATASHEET[entry.profile.id.removesuffix("-vre-test")]
        np.testing.assert_allclose(moments[:3], [0.0, 0.0, level**2], rtol=1e-5)
        np.testing.assert_array_equal(moments[3:], 0.0)
