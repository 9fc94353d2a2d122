"""`analyze` for sensors with ``uncertainty`` or a ``lot``: u(Δ_V) = √(gᵀΣg) (docs/model.md
section 14) in every format.

The expected u is built by hand here: g_i is Δ_V of a sensor whose only coefficient is
the unit vector e_i (k1 = 1) minus Δ_V of the sensor with none, each from its own
`analyze` run (Δ_V is linear in the coefficients); Σ = diag(σ)·R·diag(σ) written out
from the sigma and correlation pairs of the file.
"""

from __future__ import annotations

import io
import json
from pathlib import Path

import numpy as np
import pytest

from gyrovib import api
from tests.conftest import invoke

PROFILES = """\
profiles:
  - id: cruise
    rate: [0, 0, 30]
    harmonic:
      - frequency: 120
        amplitude: [0.5, 0.5, 40]
    random:
      psd:
        x1: [[20, 1.0e-3], [2000, 1.0e-3]]
        x3: [[20, 1.0e-2], [2000, 1.0e-2]]
      coherence: [0.5, 0.0]
  - id: hover
    rate: [0, 0, -5]
    harmonic:
      - frequency: 80
        amplitude: [2, 0, 25]
"""

COEFFICIENTS = {"A1": 1.2e-3, "k2": 3.1e-5, "k3": -2.0e-7, "k4": 4.0e-10, "k5": 1.0e-12,
                "m31": 2.0e-6}
SIGMA = {"A1": 1.0e-4, "k2": 2.0e-6, "k3": 1.5e-8, "k4": 1.0e-10, "k5": 5.0e-13,
         "m31": 1.0e-6}
PAIRS = {"A1 k2": 0.3, "k3 k5": -0.6, "k2 k4": 0.2}


def _mapping(values: dict[str, float]) -> str:
    return "{" + ", ".join(f"{k}: {v!r}" for k, v in values.items()) + "}"


def catalogue(rate_unit: str = "deg/s") -> str:
    return (f"gyrovib: 1\nunits: {{rate: {rate_unit}}}\nsensors:\n"
            f"  - id: unit-1\n    coefficients: {_mapping(COEFFICIENTS)}\n"
            f"    uncertainty:\n      sigma: {_mapping(SIGMA)}\n"
            f"      correlation: {_mapping(PAIRS)}\n"
            f"  - id: plain\n    coefficients: {_mapping(COEFFICIENTS)}\n"
            f"  - id: lot-1\n    lot:\n      units: 20\n      mean: {_mapping(COEFFICIENTS)}\n"
            f"      sigma: {_mapping(SIGMA)}\n      correlation: {_mapping(PAIRS)}\n"
            + PROFILES)


def by_hand_covariance() -> np.ndarray:
    names = list(SIGMA)
    s = np.array([SIGMA[n] for n in names])
    r = np.eye(len(names))
    for pair, rho in PAIRS.items():
        a, b = pair.split()
        r[names.index(a), names.index(b)] = r[names.index(b), names.index(a)] = rho
    return np.outer(s, s) * r


def by_hand_g(tmp_path: Path, unit: str) -> np.ndarray:
    """g (profiles, coefficients): Δ_V of each unit vector minus Δ_V of no coefficient."""
    sensors = "".join(f"  - id: e-{n}\n    coefficients: {{{n}: 1.0}}\n" for n in SIGMA)
    path = tmp_path / "unit-vectors.yaml"
    path.write_text("gyrovib: 1\nsensors:\n  - id: zero\n    coefficients: {}\n" + sensors
                    + PROFILES, encoding="utf-8")
    result = invoke("analyze", path, "--format", "json", "--unit", unit)
    assert result.exit_code == 0, result.stderr
    total = {(r["sensor"], r["profile"]): r["total"]
             for r in json.loads(result.stdout)["results"]}
    return np.array([[total[(f"e-{n}", p)] - total[("zero", p)] for n in SIGMA]
                     for p in ("cruise", "hover")])


@pytest.mark.parametrize("unit", ["deg/s", "deg/h"])
def test_u_is_the_quadratic_form_built_by_hand(tmp_path: Path, unit: str) -> None:
    path = tmp_path / "c.yaml"
    path.write_text(catalogue(), encoding="utf-8")
    result = invoke("analyze", path, "--format", "json", "--unit", unit)
    assert result.exit_code == 0, result.stderr
    rows = {(r["sensor"], r["profile"]): r for r in json.loads(result.stdout)["results"]}
    g = by_hand_g(tmp_path, unit)
    expected = np.sqrt(np.einsum("pi,ij,pj->p", g, by_hand_covariance(), g))
    assert np.all(expected > 0)
    for sensor in ("unit-1", "lot-1"):
        got = [rows[(sensor, p)]["uncertainty"]["total"] for p in ("cruise", "hover")]
        np.testing.assert_allclose(got, expected, rtol=1e-9)
    assert "uncertainty" not in rows[("plain", "cruise")]
    assert rows[("lot-1", "cruise")]["lot_mean"] is True
    assert "lot_mean" not in rows[("unit-1", "cruise")]
    # the lot is analysed at its mean: the same Δ_V as the unit with those coefficients
    assert rows[("lot-1", "hover")]["total"] == rows[("plain", "hover")]["total"]


def test_u_does_not_depend_on_the_file_rate_unit(tmp_path: Path) -> None:
    """The same sensor written in rad/s (each coefficient and σ converted as its rate
    power) has the same u in deg/s."""
    scale = 180.0 / np.pi  # deg/s per rad/s: c[rad/s] = c[deg/s]·scale^(-p)
    power = {"A1": 0, "k2": -1, "k3": -2, "k4": -3, "k5": -4, "m31": -1}

    def convert(values: dict[str, float]) -> dict[str, float]:
        return {k: v * scale ** (-power[k]) for k, v in values.items()}

    rad = (f"gyrovib: 1\nunits: {{rate: rad/s}}\nsensors:\n  - id: unit-1\n"
           f"    coefficients: {_mapping(convert(COEFFICIENTS))}\n"
           f"    uncertainty:\n      sigma: {_mapping(convert(SIGMA))}\n"
           f"      correlation: {_mapping(PAIRS)}\n")
    (tmp_path / "s.yaml").write_text(rad, encoding="utf-8")
    (tmp_path / "p.yaml").write_text("gyrovib: 1\n" + PROFILES, encoding="utf-8")
    (tmp_path / "d.yaml").write_text(catalogue(), encoding="utf-8")
    a = api.analyze(api.load([tmp_path / "s.yaml", tmp_path / "p.yaml"]))
    b = api.analyze(api.load([tmp_path / "d.yaml"]), sensors=["unit-1"])
    assert a.uncertainty is not None and b.uncertainty is not None
    np.testing.assert_allclose(a.error.total, b.error.total, rtol=1e-9)
    np.testing.assert_allclose(a.uncertainty, b.uncertainty, rtol=1e-9)


def test_every_format_carries_u(tmp_path: Path) -> None:
    path = tmp_path / "c.yaml"
    path.write_text(catalogue(), encoding="utf-8")
    result = api.analyze(api.load([path]))
    assert result.uncertainty is not None and np.isnan(result.uncertainty[1]).all()
    frame = result.to_frame()
    u = result.uncertainty.T.reshape(-1)  # profiles outermost, as the JSON
    np.testing.assert_allclose(frame["uncertainty_total"], u, equal_nan=True)
    assert list(frame["lot_mean"][:3]) == [False, False, True]
    import pandas

    csv = pandas.read_csv(io.StringIO(invoke("analyze", path, "--format", "csv").stdout))
    np.testing.assert_allclose(csv["uncertainty_total"], u, rtol=1e-15, equal_nan=True)
    table = invoke("analyze", path, env={"COLUMNS": "200"}).stdout
    assert "u(Δ_V)" in table and "lot-1 (lot)" in table
    assert f"{u[0]:.2g}" in table
    markdown = invoke("analyze", path, "--format", "markdown").stdout
    assert "| u(Δ_V) |" in markdown and f"| {u[0]:.2g} |" in markdown


def test_numeric_method_reports_the_closed_form_u(tmp_path: Path) -> None:
    path = tmp_path / "c.yaml"
    path.write_text(catalogue(), encoding="utf-8")
    exact = api.analyze(api.load([path]))
    numeric = api.analyze(api.load([path]), method="numeric", samples=2000)
    assert exact.uncertainty is not None and numeric.uncertainty is not None
    np.testing.assert_allclose(numeric.uncertainty, exact.uncertainty, rtol=1e-12)


def test_a_small_lot_uses_the_diagonal_and_warns(tmp_path: Path) -> None:
    """units 3 ≤ 6 coefficients: Σ = diag(σ²), the correlations dropped, a warning."""
    path = tmp_path / "c.yaml"
    path.write_text(catalogue().replace("units: 20", "units: 3"), encoding="utf-8")
    result = invoke("analyze", path, "--format", "json")
    assert result.exit_code == 0, result.stderr
    assert "gyrovib: warning: lot 'lot-1': a lot of 3 units" in result.stderr
    rows = {(r["sensor"], r["profile"]): r for r in json.loads(result.stdout)["results"]}
    g = by_hand_g(tmp_path, "deg/s")
    diagonal = np.diag(np.diag(by_hand_covariance()))
    expected = np.sqrt(np.einsum("pi,ij,pj->p", g, diagonal, g))
    got = [rows[("lot-1", p)]["uncertainty"]["total"] for p in ("cruise", "hover")]
    np.testing.assert_allclose(got, expected, rtol=1e-9)
