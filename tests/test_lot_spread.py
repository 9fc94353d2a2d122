"""A lot without a measured spread: its yield is not a measurement (docs/model.md section 14).

Too few units (n ≤ p), a coefficient with σ = 0 (identical units, units that differ
in other coefficients only) or a singular correlation matrix: `fit` warns naming the
lot, and `select --yield` calls the lot `unverified` (JSON `"unknown": ["spread"]`)
where its yield would pass. The lots are made here; what is expected follows from
their construction (identical rows have σ = 0 exactly or to rounding; n units give n − 1
directions of spread).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from gyrovib.core.lot import SPREAD_RTOL, lot_statistics, spread_problem
from tests.conftest import invoke

NAMES = ("k0", "A1", "k2", "k3", "k4", "k5")  # p = 5: k0 does not rectify
BASE = np.array([0.1, 1.6e-3, 3.3e-8, -7.1e-9, 2.5e-12, 8.7e-15])
LEVELS = (-300.0, -200.0, -100.0, -50.0, -20.0, 0.0, 20.0, 50.0, 100.0, 200.0, 300.0)


def spread_units(n: int, seed: int = 1) -> np.ndarray:
    """``n`` units around BASE, each coefficient spread by 10 % independently."""
    rng = np.random.default_rng(seed)
    return BASE * (1.0 + 0.1 * rng.standard_normal((n, BASE.size)))


@pytest.mark.parametrize("copies", [2, 3, 8])
def test_identical_units_have_no_spread(copies: int) -> None:
    """The mean of equal numbers need not be that number (0.1 three times sums to
    0.30000000000000004): σ comes out 0 or a few 1e-17 relative, within SPREAD_RTOL."""
    lot = lot_statistics(np.tile(BASE, (copies, 1)), NAMES)
    assert lot.unmeasured is not None
    assert "no spread in A1, k2, k3, k4, k5" in lot.unmeasured
    assert ("cannot estimate the correlations" in lot.unmeasured) == (copies <= 5)


def test_as_many_units_as_coefficients() -> None:
    """n = p = 5 units that do spread: the sample covariance has rank n − 1 = 4 < 5."""
    lot = lot_statistics(spread_units(5), NAMES)
    assert lot.diagonal and lot.unmeasured is not None
    assert "a lot of 5 units cannot estimate the correlations of 5" in lot.unmeasured
    assert lot_statistics(spread_units(6), NAMES).unmeasured is None  # n = p + 1


def test_units_varying_in_one_coefficient_only() -> None:
    """Seven units that differ in A1 alone, or six equal units and one with another A1:
    every other rectifying coefficient has σ = 0; units that differ in the bias k0 alone
    have no spread in any of them."""
    units = np.tile(BASE, (7, 1))
    units[:, 1] *= np.linspace(0.8, 1.2, 7)
    problem = lot_statistics(units, NAMES).unmeasured
    assert problem is not None and "no spread in k2, k3, k4, k5" in problem
    units = np.tile(BASE, (7, 1))
    units[0, 1] *= 1.1
    problem = lot_statistics(units, NAMES).unmeasured
    assert problem is not None and "no spread in k2, k3, k4, k5" in problem
    units = np.tile(BASE, (7, 1))
    units[:, 0] += np.linspace(-1.0, 1.0, 7)
    assert "no spread in A1, k2, k3, k4, k5" in (lot_statistics(units, NAMES).unmeasured or "")


def test_a_singular_correlation_matrix() -> None:
    """Eight units whose k2 is an exact linear function of A1: every σ > 0, but the
    correlation matrix has a zero eigenvalue (A1 and k2 correlate at ±1)."""
    units = spread_units(8)
    units[:, 2] = 2e-5 * units[:, 1]
    problem = lot_statistics(units, NAMES).unmeasured
    assert problem is not None and "make the covariance singular" in problem
    healthy = spread_units(8)
    assert lot_statistics(healthy, NAMES).unmeasured is None
    # the tolerance is relative: a σ just above SPREAD_RTOL·|μ| is a spread
    mean, sigma = np.array([1.0, 2.0]), np.array([1e-9, 3 * SPREAD_RTOL * 2.0])
    assert spread_problem(mean, sigma, np.eye(2), 5, ("A1", "k2")) == (
        f"no spread in A1 (σ = 0, or within {SPREAD_RTOL:g} of |mean|: the units agree there "
        "to rounding)")


def table(path: Path, units: dict[str, float]) -> Path:
    """A noise-free table of units that share eq. (2) (k0 = 0.1, A1 = 2e-3, k2 = 3e-6,
    k3 = -4e-9), each with its own output offset (mV) on K1 = 25 mV per deg/s."""
    rows = ["unit,rate,output"]
    for name, offset in units.items():
        for w in LEVELS:
            u = offset + 25.0 * (0.1 + w + 1e-3 * abs(w) + 3e-6 * w**2 - 4e-9 * w**3)
            rows += [f"{name},{w:g},{u!r}", f"{name},{w:g},{u + 0.01!r}"]
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return path


@pytest.mark.parametrize("offsets", [{"a": 0.0, "b": 0.0}, {"a": 0.0, "b": 0.0, "c": 0.0},
                                     {"a": 0.0, "b": 1.0, "c": -2.0, "d": 0.5, "e": 3.0}])
def test_fit_warns_naming_the_lot(tmp_path: Path, offsets: dict[str, float]) -> None:
    """Two or three identical units; or five units that differ in their offset only (k0):
    the rectifying coefficients agree to rounding, the fit warns on standard error."""
    path = table(tmp_path / "twins.csv", offsets)
    result = invoke("fit", path, "--order", "3", "--format", "json")
    assert result.exit_code == 0, result.stderr
    assert "gyrovib: warning: lot 'lot-twins': " in result.stderr
    assert "no spread in A1, k2, k3" in result.stderr
    assert "select with --yield calls it unverified" in result.stderr
    assert json.loads(result.stdout)["warnings"] == [
        line.removeprefix("gyrovib: warning: ") for line in result.stderr.splitlines()]


LOT = """\
gyrovib: 1
sensors:
  - id: lot-flat
    lot:
      units: {units}
      mean: {{A1: 1.0e-3, k2: 2.0e-3}}
      sigma: {{A1: {s1}, k2: {s2}}}
profiles:
  - id: random-x3
    rate: [0, 0, 0]
    random:
      psd:
        x3: [[20, 1.0e-3], [2020, 1.0e-3]]
"""


def select(tmp_path: Path, *args: object, units: int = 10, s1: float = 0.0,
           s2: float = 0.0) -> dict:
    path = tmp_path / "lot.yaml"
    path.write_text(LOT.format(units=units, s1=s1, s2=s2), encoding="utf-8")
    result = invoke("select", path, "--criterion", "worst", "--yield", 0.99,
                    "--format", "json", *args)
    assert result.exit_code in (0, 1), result.stderr
    document = json.loads(result.stdout)
    return document["sensors"][0]["profiles"][0] | {"stderr": result.stderr,
                                                    "exit": result.exit_code}


def test_a_catalogue_lot_without_spread_is_unverified(tmp_path: Path) -> None:
    """σ = 0 for every coefficient: Δ_V = k2·σ3² = 2e-3·2 = 4e-3 deg/s (test_yield_select's
    closed form) within Δ* = 6e-3, so the yield is 1 — but not a measurement."""
    cell = select(tmp_path, "--budget", 6e-3)
    assert cell["yield"]["value"] == 1.0
    assert cell["status"] == "unverified" and cell["pass"] is False
    assert cell["unknown"] == ["spread"]
    assert "is not a measurement" in cell["reason"] and "no spread in A1, k2" in cell["reason"]
    assert "lot 'lot-flat'" in cell["stderr"] and cell["exit"] == 1
    assumed = select(tmp_path, "--budget", 6e-3, "--assume-unknown", "zero")
    assert assumed["status"] == "pass" and assumed["pass"] is True and assumed["unknown"] == []
    for fmt in ("table", "markdown", "junit"):  # every renderer takes the unknown "spread"
        for more in ((), ("--assume-unknown", "zero")):
            shown = invoke("select", tmp_path / "lot.yaml", "--budget", 6e-3, "--criterion",
                           "worst", "--yield", 0.99, "--format", fmt, *more)
            assert shown.exit_code == (0 if more else 1), shown.stderr
    table = invoke("select", tmp_path / "lot.yaml", "--budget", 6e-3, "--criterion", "worst",
                   "--yield", 0.99, "--format", "markdown")
    assert "| lot-flat | the lot's spread, not measured" in table.stdout  # what settles it


def test_analyze_words_the_lot_s_note_as_select_s_option(tmp_path: Path) -> None:
    # the note of a lot without spread advises select's yield; the library words it
    # yield_target (its argument), the command line --yield, on analyze as on select
    path = tmp_path / "lot.yaml"
    path.write_text(LOT.format(units=10, s1=0.0, s2=0.0), encoding="utf-8")
    for fmt in ("table", "json"):
        result = invoke("analyze", path, "--format", fmt)
        assert result.exit_code == 0, result.stderr
        assert "lot 'lot-flat'" in result.stderr and "select with --yield" in result.stderr
        assert "yield_target" not in result.stderr + result.stdout


def test_a_catalogue_lot_of_too_few_units_is_unverified(tmp_path: Path) -> None:
    """Two units for two coefficients with a spread (n ≤ p): the diagonal is used, with a
    warning, and the yield (P(|2·k2| ≤ 6e-3) ≈ 1 for σ(k2) = 1e-4) is unverified."""
    cell = select(tmp_path, "--budget", 6e-3, units=2, s1=1e-4, s2=1e-4)
    assert cell["yield"]["value"] > 0.99
    assert cell["status"] == "unverified" and cell["unknown"] == ["spread"]
    assert "a lot of 2 units cannot estimate the correlations of 2" in cell["reason"]
    measured = select(tmp_path, "--budget", 6e-3, units=3, s1=1e-4, s2=1e-4)
    assert measured["status"] == "pass" and measured["unknown"] == []


def test_a_lot_that_fails_on_its_mean_still_fails(tmp_path: Path) -> None:
    """Δ_V = 4e-3 deg/s at the mean against Δ* = 3e-3: yield 0 with no spread; the verdict
    on the given figures is a failure, as for an unpublished figure (one rule)."""
    cell = select(tmp_path, "--budget", 3e-3)
    assert cell["yield"]["value"] == 0.0
    assert cell["status"] == "fail" and cell["unknown"] == ["spread"]
