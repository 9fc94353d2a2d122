"""A datasheet part's worst case explained: the coefficient of the worst polynomial that
makes it large, and the datasheet figure that would shrink it most (issue: ADIS16460's
worst polynomial has A1 of 0.14, a 14 % asymmetry, shown only in JSON before)."""

from __future__ import annotations

import numpy as np

import gyrovib
from gyrovib.formatting import fmt
from gyrovib.render.analysis import worst_case_text
from tests.conftest import invoke


def test_the_asymmetry_of_the_worst_polynomial_is_named() -> None:
    result = gyrovib.analyze(sensors="adis16460", profiles=["uav-blade-pass-tone",
                                                             "adis16460-vre-test"])
    a1 = float(result.worst_coefficients[0, 0, 0])
    # the A1 term is the largest of eq. (13) for this polynomial under the tone
    terms = np.abs(result.error.additive_terms[0, 0])
    assert int(np.argmax(terms)) == 0 and abs(a1) > 0.1
    text = worst_case_text(result, 0, 0)
    assert text is not None
    assert f"A1 = {fmt(a1, 2)} (a {fmt(abs(a1) * 100, 2)} % scale-factor asymmetry)" in text
    # no asymmetry is published: that is the figure to ask for
    assert text.endswith("an asymmetry figure (a published bound on |A1| cuts the worst case)")
    # under its VRE test the g² term is all of it: a smaller VRE would shrink it
    vre = worst_case_text(result, 0, 1)
    assert vre is not None and vre.endswith("a smaller VRE")
    # coefficient-form rows have no worst case to explain
    plain = gyrovib.analyze(sensors="generic-rate-mems", profiles="uav-blade-pass-tone")
    assert worst_case_text(plain, 0, 0) is None


def test_tables_and_report_show_it(tmp_path) -> None:
    out = invoke("analyze", "--sensor", "adis16460", "--profile", "uav-blade-pass-tone",
                 env={"COLUMNS": "200"}).stdout
    assert "adis16460: worst case A1 = " in out
    target = tmp_path / "r.html"
    invoke("report", "--sensor", "adis16460", "--profile", "uav-blade-pass-tone",
           "--budget", "10deg/h", "-o", str(target))
    assert "adis16460: worst case A1 = " in target.read_text(encoding="utf-8")

