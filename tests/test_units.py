"""The same catalogue written in deg/s, deg/h, rad/s or rpm gives the same results."""

from __future__ import annotations

import json
import math

import pytest

from gyrovib import units

# deg/s per unit (docs/model.md): deg/h 1/3600, rad/s 180/π, rpm 6
SCALES = {"deg/s": 1.0, "deg/h": 1 / 3600, "rad/s": 180 / math.pi, "rpm": 6.0}

BASE = {  # deg/s values; converted per docs/model.md: kn[U] = kn[deg/s]·s^(n−1)
    "A1": 1e-3, "k2": 1e-4, "k3": -2e-6, "k4": 3e-7, "k5": -1e-9, "m31": 1e-4, "m32": -2e-4,
}
POWER = {"A1": 0, "k2": 1, "k3": 2, "k4": 3, "k5": 4, "m31": 1, "m32": 1}


def catalogue(unit: str) -> str:
    s = SCALES[unit]
    coeffs = ", ".join(f"{k}: {v * s ** POWER[k]!r}" for k, v in BASE.items())
    rate = lambda x: repr(x / s)  # noqa: E731
    psd = lambda x: repr(x / s**2)  # noqa: E731
    return f"""
gyrovib: 1
units: {{rate: {unit}}}
sensors:
  - id: s
    range: {rate(500.0)}
    coefficients: {{{coeffs}}}
profiles:
  - id: tone
    rate: [0, 0, {rate(1.5)}]
    harmonic: [{{frequency: 80, amplitude: [{rate(1.0)}, {rate(0.5)}, {rate(2.0)}]}}]
  - id: mix
    rate: [{rate(1.0)}, 0, {rate(-3.0)}]
    harmonic: [{{frequency: 80, amplitude: [0, 0, {rate(2.0)}]}}]
    random:
      psd:
        x1: [[20, {psd(1e-3)}], [2000, {psd(1e-3)}]]
        x3: [[20, {psd(2e-3)}], [2000, {psd(5e-4)}]]
      coherence: [0.3, 1]
    mount: [[20, 1], [500, 0.2]]
"""


def _analyze(run, path, unit):
    result = run("analyze", path, "--format", "json", "--unit", unit)
    assert result.exit_code == 0, result.output
    return json.loads(result.output)["results"]


@pytest.mark.parametrize("file_unit", ["deg/h", "rad/s", "rpm"])
@pytest.mark.parametrize("out_unit", ["deg/s", "deg/h"])
def test_file_unit_does_not_change_results(run, write, file_unit, out_unit):
    ref = _analyze(run, write(catalogue("deg/s"), "ref.yaml"), out_unit)
    other = _analyze(run, write(catalogue(file_unit), "other.yaml"), out_unit)
    for a, b in zip(ref, other, strict=True):
        for key in ("additive", "multiplicative", "total", "rms"):
            assert b[key] == pytest.approx(a[key], rel=1e-9, abs=1e-300)
        assert b["rate"] == pytest.approx(a["rate"], rel=1e-12, abs=1e-12)


def test_output_unit_scales_rates_and_coefficients(run, write):
    path = write(catalogue("deg/s"))
    ds = _analyze(run, path, "deg/s")
    dh = _analyze(run, path, "deg/h")
    for a, b in zip(ds, dh, strict=True):
        # a rate in deg/h is 3600× its value in deg/s
        assert b["total"] == pytest.approx(a["total"] * 3600, rel=1e-12)
        assert b["rms"] == pytest.approx(a["rms"] * 3600, rel=1e-12)
        # Δ(q) carries rate^(1−q): Δ(2)[deg/h] = Δ(2)[deg/s]/3600
        q_ds, q_dh = a["multiplicative_coefficients"], b["multiplicative_coefficients"]
        assert q_dh["q1"] == pytest.approx(q_ds["q1"], rel=1e-12)
        assert q_dh["q2"] == pytest.approx(q_ds["q2"] / 3600, rel=1e-12)
        assert q_dh["q3"] == pytest.approx(q_ds["q3"] / 3600**2, rel=1e-12)


def test_parse_rate_accepts_units_and_refuses_nonsense():
    assert units.parse_rate("36deg/h", "deg/s") == pytest.approx(0.01)  # 36/3600
    assert units.parse_rate("0.01 deg/s", "deg/h") == pytest.approx(0.01)
    assert units.parse_rate("2", "rpm") == pytest.approx(12.0)  # 2·6 deg/s
    for bad in ("abc", "1 furlong/s", "nan", "1e999"):
        with pytest.raises(units.OptionError):
            units.parse_rate(bad, "deg/s")


def test_one_reading_of_a_quantity_for_the_command_line_and_the_notebook():
    # units.quantity is the one reading of "a number with a unit": --budget and the
    # notebook's budget= give the same deg/s (36 deg/h = 0.01 deg/s, by hand)
    from gyrovib import notebook
    from gyrovib.cli.options import parse_budget

    for text in ("36deg/h", "36 deg/h", "0.01"):
        cli_value = parse_budget(text, "deg/s")
        assert cli_value == notebook._quantity("budget", text, "deg/s", True)
        assert cli_value == pytest.approx(0.01, rel=1e-15)
    assert units.quantity(0.01, "deg/s") == notebook._quantity("budget", 0.01, "deg/s")
    with pytest.raises(units.NotPositive):
        units.quantity("-36deg/h", "deg/s", positive=True)
    assert units.quantity("-36deg/h", "deg/s") == pytest.approx(-0.01, rel=1e-15)
