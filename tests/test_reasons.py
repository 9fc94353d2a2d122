"""select's reasons: the library finds what fails as codes and numbers
(SelectionResult.failures, gyrovib.reasons.Failure) and gyrovib/reasons.py words them,
so the JSON's reason, the DataFrame's and the tables' read one text."""

from __future__ import annotations

import json

import pytest

import gyrovib
from gyrovib.cli.options import as_options
from gyrovib.core.synthesis import BOUNDED
from gyrovib.reasons import Failure, Yield, reason, worded
from tests.conftest import invoke


@pytest.fixture(scope="module")
def both() -> object:
    # the bundled catalogues under --criterion both: coefficient, VRE, RMS, datasheet and
    # unverified failures among the cells
    return gyrovib.select(budget="10deg/h", criterion="both")


def test_failures_are_the_results_numbers(both) -> None:
    r = both
    codes = set()
    for i in range(len(r.sensors)):
        for j in range(len(r.profiles)):
            for f in r.failures(i, j):
                codes.add(f.code)
                if f.code == "coefficient":  # |value| against its bound, as checked
                    b = BOUNDED.index(f.names[0])
                    assert f.numbers == (r.values[i, j, b], r.bounds[i, j, b])
                    assert not r.check_pass[i, j, b] and f.unit == r.unit
                elif f.code == "rms":  # Δ_V(RMS) against the budget Δ*
                    assert f.numbers == (r.rms[i, j], r.budget) and not r.rms_pass[i, j]
                elif f.code == "saturated":  # the reach, the range and κ
                    assert f.numbers == (*r.saturation[i, j], r.peak_factor)
                elif f.code == "vre":  # a known effective VRE above its bound, never NaN
                    assert all(v == v for v in f.numbers) and not r.vre_pass[i, j]
                elif f.code == "unverified":  # the figures the cell hangs on
                    assert set(f.names) <= set(r.unknown[i, j]) and r.is_unverified(i, j)
            if r.passed[i, j]:
                assert r.failures(i, j) == ()
    # the probe meets the kinds of failure the bundled catalogues have (no coefficient
    # sensor there gives a g² figure, so none fails its VRE check on a number: that
    # failure is tests/test_linear_api.py's)
    assert {"coefficient", "rms", "nonlinearity", "unverified", "saturated"} <= codes


def test_the_json_and_the_frame_read_the_worded_failures(both) -> None:
    document = json.loads(invoke("select", "--budget", "10deg/h", "--criterion", "both",
                                 "--format", "json").stdout)
    frame = as_options(both).to_frame()  # the command line's copy: options named, as in JSON
    k = failing = 0
    for i, sensor in enumerate(document["sensors"]):
        for j, cell in enumerate(sensor["profiles"]):
            expected = (None if both.passed[i, j]
                        else "; ".join(worded(as_options(both).failures(i, j))))
            shown = frame["reason"].iloc[k]  # a passing row's None: pandas' missing value
            assert cell["reason"] == (shown if isinstance(shown, str) else None) == expected
            failing += expected is not None
            k += 1
    assert failing > 10


def test_wording_of_codes_and_numbers() -> None:
    # the texts written out by hand from the numbers: 4 significant figures (formatting.fmt),
    # a coefficient's unit from its rate power (k2: rate^-1; A1: none)
    k2 = Failure("coefficient", (2.5e-4, 1.23456e-4), ("k2",), "deg/s")
    assert worded([k2]) == ["|k2| = 0.00025 exceeds its bound 0.0001235 (deg/s)^-1"]
    a1 = Failure("coefficient", (0.02, 0.0021992504), ("A1",), "deg/h")
    rms = Failure("rms", (40.4564, 10.0), unit="deg/h")
    assert reason([a1, rms]) == ("|A1| = 0.02 exceeds its bound 0.002199; Δ_V(RMS) = 40.46 "
                                 "deg/h exceeds the budget 10 deg/h")
    assert reason([]) is None
    lot = Yield(0.91234, 0.9, 0.92, "monte-carlo", 2000)
    assert worded([Failure("yield", (0.99,), lot=lot)]) == [
        "yield 0.9123 [0.9, 0.92] (monte-carlo, 2000 draws) is below 0.99"]
    exact = Yield(0.5, float("nan"), float("nan"), "exact", 0)
    assert worded([Failure("yield", (0.9,), lot=exact)]) == ["yield 0.5 (exact) is below 0.9"]


def test_the_tables_reason_is_in_the_catalogues_unit(both) -> None:
    """The tables and JUnit word a coefficient's bound in the catalogue's unit (deg/s),
    the JSON in the output unit (deg/h): the label follows the numbers. k2's bound per
    deg/s is 3600 times its bound per deg/h (k2 multiplies Ω²: 1/(deg/s) = 3600/(deg/h))."""
    i = both.sensors.index("generic-rate-mems")
    j = both.profiles.index("manoeuvre-saturation")
    table = {f.names: f for f in both.failures(i, j, table=True) if f.code == "coefficient"}
    plain = {f.names: f for f in both.failures(i, j) if f.code == "coefficient"}
    assert both.table_unit == "deg/s" and both.unit == "deg/h"
    assert {f.unit for f in table.values()} == {"deg/s"}
    assert {f.unit for f in plain.values()} == {"deg/h"}
    assert table[("k2",)].numbers[1] == pytest.approx(3600 * plain[("k2",)].numbers[1],
                                                      rel=1e-12)
    r = invoke("select", "--budget", "10deg/h", "--criterion", "both", "--format", "junit",
               "--sensor", "generic-rate-mems", "--profile", "manoeuvre-saturation")
    bound = table[("k2",)].numbers[1]  # |k2| = 8e-5 (deg/s)^-1: the bundled catalogue
    assert f"|k2| = 8e-05 exceeds its bound {bound:.4g} (deg/s)^-1" in r.stdout, r.stdout
