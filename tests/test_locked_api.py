"""Phase-locked harmonics through the library and the CLI (docs/model.md section 10).

The closed forms of core/harmonics.py are checked against brute force in
test_harmonics.py; here the wiring is: the catalogue's ``harmonics:`` groups
reach the exact method (odd terms k3·M3, k5·M5 in ``additive_terms``), the
numeric method (one period, averaged by brute force), the bounds (the parts of
section 10), ``phase: worst`` (``worst_phases``) and the paper's refusal.
"""

from __future__ import annotations

import json
import math
import textwrap
from pathlib import Path
from typing import Any

import pytest

import gyrovib
from tests.conftest import invoke as run

# orders 1 and 2 on x3 only, a1 = 2, a2 = 1 deg/s, φ1 = 0, φ2 = 90°:
# M3 = −¾·a1²·a2·sin(φ2 − 2φ1) = −¾·4·1·1 = −3 (deg/s)³ (docs/model.md section 10)
GROUP = """\
    harmonics:
      fundamental: 20
      orders:
        - {order: 1, amplitude: [0.5, 0.0, 2.0], phase: [30, 0, 0]}
        - {order: 2, amplitude: [0.0, 0.3, 1.0], phase: [0, 45, 90]}
"""
# every coefficient of eq. (2) that acts, so every term of eq. (13)-(16) is exercised
SENSOR = """
sensors:
  - id: s
    range: 500
    coefficients: {A1: 1.0e-3, k2: 2.0e-4, k3: 1.0e-5, k4: -3.0e-7, k5: 1.0e-8,
                   m31: 1.0e-4, m32: -2.0e-4}
"""


def write(tmp_path: Path, profiles: str, sensors: str = SENSOR) -> str:
    path = tmp_path / "cat.yaml"
    path.write_text("gyrovib: 1\n" + textwrap.dedent(profiles) + textwrap.dedent(sensors))
    return str(path)


def profiles(rate: float, extra: str = "", group: str = GROUP, name: str = "g") -> str:
    """A profile (YAML at column 0): rate Ω_K3, the group, and ``extra`` keys."""
    return (f"profiles:\n  - id: {name}\n    rate: [0, 0, {rate}]\n"
            + textwrap.dedent(group).replace("\n", "\n    ").rstrip(" ").join(["    ", ""])
            + textwrap.indent(textwrap.dedent(extra).strip("\n") + "\n", "    "))


def rows(path: str, *args: str) -> list[Any]:
    result = run("analyze", path, "--format", "json", *args)
    assert result.exit_code == 0, result.stderr
    out: list[Any] = json.loads(result.stdout)["results"]
    return out


@pytest.mark.parametrize(("phi1", "phi2"), [(0, 90), (30, 90), (10, 200), (45, 0)])
def test_m3_of_orders_one_and_two_reaches_the_k3_term(tmp_path: Path, phi1: float,
                                                      phi2: float) -> None:
    # additive_terms.k3 = k3·M3 with M3 = −¾·a1²·a2·sin(φ2 − 2φ1) on x3 (a1 = 2, a2 = 1)
    group = GROUP.replace("phase: [30, 0, 0]", f"phase: [30, 0, {phi1}]").replace(
        "phase: [0, 45, 90]", f"phase: [0, 45, {phi2}]")
    row = rows(write(tmp_path, profiles(0.5, group=group)))[0]
    m3 = -0.75 * 4.0 * 1.0 * math.sin(math.radians(phi2 - 2 * phi1))
    assert row["additive_terms"]["k3"] == pytest.approx(1e-5 * m3, rel=1e-12, abs=1e-20)


@pytest.mark.parametrize("rate", [0.5, 5.0])  # inside and outside the peak (< 3 deg/s)
@pytest.mark.parametrize("tone", [False, True])
def test_exact_agrees_with_brute_force_over_one_period(tmp_path: Path, rate: float,
                                                       tone: bool) -> None:
    # Brute force (core/numeric.py) averages eq. (2) over the group's period on the phase
    # grid; with an independent tone it averages over the product grid of both phases.
    extra = """
    harmonic:
      - frequency: 33
        amplitude: [0.2, 0.1, 0.7]
    """ if tone else ""
    path = write(tmp_path, profiles(rate, extra))
    exact = rows(path)[0]
    numeric = rows(path, "--method", "numeric", "--samples", "400000")[0]
    # the moments of a trigonometric polynomial are exact on the phase grid; the rectified
    # mean <|Ω + x3|> has kinks, so with an independent tone its grid average carries the
    # reported standard error (~4e-6 relative here): 6 of them on top of 1e-7
    slack = 6.0 * numeric["stderr"]
    for key in ("k3", "k5", "k2", "k4", "m31", "m32"):
        assert numeric["additive_terms"][key] == pytest.approx(
            exact["additive_terms"][key], rel=1e-7, abs=1e-18), key
    for key in ("total", "additive"):
        assert numeric[key] == pytest.approx(exact[key], rel=1e-7, abs=slack), key
    assert numeric["additive_terms"]["A1"] == pytest.approx(
        exact["additive_terms"]["A1"], rel=1e-7, abs=slack)
    assert numeric["multiplicative"] == pytest.approx(exact["multiplicative"], rel=1e-7)
    if not tone:  # the group alone: one period on a fine grid, its stderr at rounding level
        assert numeric["stderr"] <= 1e-9 * abs(exact["total"])
        assert numeric["total"] == pytest.approx(exact["total"], rel=1e-7)


def test_worst_phase_is_searched_and_reported(tmp_path: Path) -> None:
    # only k3, Ω = 0: Δ_V = k3·M3 with |M3| = ¾·a1²·a2·|sin ψ| largest at ψ = 90° or 270°
    group = GROUP.replace("phase: [0, 45, 90]", "phase: worst")
    path = write(tmp_path, profiles(0.0, group=group, name="w"), """
    sensors:
      - id: s
        coefficients: {k3: 1.0e-5}
    """)
    row = rows(path)[0]
    # a1 = 2, a2 = 1 (GROUP): max |M3| = ¾·4·1 = 3 (deg/s)³ -> |k3·M3| = 1e-5·3 = 3e-5 deg/s
    assert abs(row["additive_terms"]["k3"]) == pytest.approx(3.0e-5, rel=1e-9)
    (found,) = row["worst_phases"]
    assert set(found) == {"2"}
    assert min(abs(found["2"] - 90.0), abs(found["2"] - 270.0)) < 1e-3
    assert run("analyze", path, "--method", "numeric").exit_code == 2


def test_datasheet_part_under_unknown_phases_bounds_every_phase(tmp_path: Path) -> None:
    # a spec-form part's worst case under `phase: worst` takes each multiplier at its
    # largest over the phases (docs/model.md sections 10, 11), so it is at least its worst
    # case at any written phase of order 2 (here 0°, 45°, …, 315° on all axes)
    part = """
    sensors:
      - id: p
        specs:
          range: 100
          nonlinearity: {value: 0.5, unit: '%FS', fit: least-squares, measure: max}
    """
    group = GROUP.replace("phase: [0, 45, 90]", "phase: worst")
    worst = rows(write(tmp_path, profiles(0.5, group=group, name="w"), part))[0]
    assert worst["source"] == "specs" and "worst_phases" not in worst
    for phase in range(0, 360, 45):
        fixed = GROUP.replace("phase: [0, 45, 90]", f"phase: [{phase}, {phase}, {phase}]")
        row = rows(write(tmp_path, profiles(0.5, group=fixed, name="f"), part))[0]
        assert abs(worst["total"]) >= abs(row["total"]) * (1 - 1e-9)


def test_paper_method_refuses_locked_groups_at_the_profile(tmp_path: Path) -> None:
    path = write(tmp_path, profiles(0.5))
    result = run("analyze", path, "--method", "paper")
    assert result.exit_code == 2
    assert f"{path}:" in result.stderr and "phase-locked" in result.stderr
    assert run("select", path, "--budget", "0.01", "--method", "paper").exit_code == 2


def test_bounds_carry_the_parts_of_section_10(tmp_path: Path) -> None:
    path = write(tmp_path, profiles(0.5))
    doc = json.loads(run("bounds", path, "--budget", "0.01", "--format", "json").stdout)
    parts = doc["profiles"][0]["parts"]
    for name in ("k3_additive", "k3_linear", "k4_linear", "k5_additive", "k5_quadratic"):
        assert name in parts
    bounds = doc["profiles"][0]["bounds"]
    assert bounds["k3"] == min(parts["k3_additive"], parts["k3_linear"])
    # k3_additive = α_k3·Δ*/|M3| with α_k3 = c_A/‖(w, 1, 1)‖ = 0.83205/√(3.5 + 2) (M5 ≠ 0 too)
    c_a = 1.5 / math.hypot(1.0, 1.5)
    assert parts["k3_additive"] == pytest.approx(c_a / math.sqrt(5.5) * 0.01 / 3.0, rel=1e-9)
    plain = json.loads(run("bounds", write(tmp_path, """
    profiles:
      - id: t
        rate: [0, 0, 1]
        harmonic:
          - {frequency: 10, amplitude: [0, 0, 1]}
    """), "--budget", "0.01", "--format", "json").stdout)
    assert set(plain["profiles"][0]["parts"]) == {"k4_additive", "k4_multiplicative",
                                                  "k5_linear", "k5_cubic"}


def test_bundled_rotor_shows_the_k3_term() -> None:
    result = gyrovib.analyze(profiles="rotor-harmonics")
    assert result.locked == (True,)
    k3 = result.error.extra_terms[..., 1]
    assert (k3 != 0).any()
    table = run("analyze", "--profile", "rotor-harmonics").stdout
    assert "Δ0 k3" in table and "Δ0 k5" in table
    plain = run("analyze", "--profile", "uav-blade-pass-tone").stdout
    assert "Δ0 k3" not in plain


def test_k3_and_k5_at_their_bounds_stay_within_budget(tmp_path: Path) -> None:
    # docs/model.md section 6: k3 and the linear k5 add linearly in Δ(1), so each gets β1/2;
    # with both at their bounds and of the same sign Δ(1)·Ω̄ = β1·Δ* and the RSS of all
    # shares is at most 1, so Δ_V(RMS) ≤ Δ* (the old β1/√2 each reached 1.098·Δ*).
    profile = """
    profiles:
      - id: t
        rate: [0, 0, 1]
        harmonic:
          - {frequency: 10, amplitude: [0, 0, 2]}
    """
    # Ω̄ = 1 < a·√(3/8) = 1.22: the linear k5 part is below the cubic one, so it binds
    budget = 0.01
    doc = json.loads(run("bounds", write(tmp_path, profile), "--budget", str(budget),
                         "--format", "json").stdout)
    b = doc["profiles"][0]["bounds"]
    assert b["k5"] == doc["profiles"][0]["parts"]["k5_linear"]  # the linear part binds here
    for sign in (1.0, -1.0):
        sensors = f"""
        sensors:
          - id: both
            coefficients: {{k3: {sign * b["k3"]!r}, k5: {sign * b["k5"]!r}}}
        """
        path = write(tmp_path, profile, sensors)
        result = run("select", path, "--budget", str(budget), "--criterion", "both",
                     "--format", "json")
        assert result.exit_code == 0, result.stdout
        cell = json.loads(result.stdout)["sensors"][0]["profiles"][0]
        assert cell["pass"] is True
        assert cell["rms"] <= budget * (1 + 1e-12)


def test_select_worst_maximises_the_error_over_unknown_phases(tmp_path: Path) -> None:
    """``select --criterion worst`` tests the worst |Δ_V| over ``phase: worst`` orders.

    README, "Methods": ``worst`` is the direct test |Δ_V| ≤ Δ*;
    docs/model.md section 10: under unknown phases the analysis maximises |Δ_V|.
    By hand (section 10): k3 = 1e-6, orders 1, 2 on x3 with a1 = 0.5, a2 = 0.3,
    Ω = −20 deg/s: M2 = (0.25 + 0.09)/2 = 0.17, |M3| ≤ ¾·0.25·0.3 = 0.05625, so
    Δ_V = k3·M3 + 3·k3·M2·Ω = k3·M3 − 1.02e-5, worst at M3 = −0.05625:
    |Δ_V| = 1.025625e-5 (the other sign gives 1.014375e-5, which would pass).
    """
    path = write(tmp_path, """
        profiles:
          - id: rotor
            rate: [0, 0, -20]
            harmonics:
              fundamental: 40
              orders:
                - {order: 1, amplitude: [0, 0, 0.5], phase: [0, 0, 0]}
                - {order: 2, amplitude: [0, 0, 0.3], phase: worst}
        """, """
        sensors:
          - id: s
            range: 100
            coefficients: {k3: 1.0e-6}
        """)
    result = run("select", path, "--budget", "1.02e-5", "--criterion", "worst",
                 "--format", "json")
    entry = json.loads(result.stdout)["sensors"][0]["profiles"][0]
    assert entry["total"] == pytest.approx(1.025625e-5, rel=1e-6)
    assert entry["pass"] is False
    assert result.exit_code == 1
    analysed = json.loads(run("analyze", path, "--format", "json").stdout)["results"][0]
    assert entry["total"] == pytest.approx(abs(analysed["total"]), rel=1e-9)


def test_bounds_table_prints_the_shares_of_section_10(tmp_path: Path) -> None:
    """The table's share column follows docs/model.md section 10 where M3, M5 ≠ 0.

    Orders 1, 2 with φ2 = 90° give M3 ≠ 0 and M5 ≠ 0, so k3 and k5 gain
    additive shares (w = 1 each): with w = (1, 1, 1, ½, ½, 1, 1), c_A = 0.832
    (docs/model.md section 6), α = c_A/‖w‖ = 0.8321/√5.5 = 0.3548 (0.4447 without);
    Δ(1) is split three ways, β1/3 = 0.4529/3 = 0.151, and Δ(2) two ways,
    β2/2 = 0.2265/2 = 0.1132.
    """
    path = write(tmp_path, profiles(5.0))
    doc = json.loads(run("bounds", path, "--budget", "0.01", "--format", "json").stdout)
    parts = doc["profiles"][0]["parts"]
    assert parts["k3_additive"] is not None and parts["k5_additive"] is not None
    text = run("bounds", path, "--budget", "0.01", env={"COLUMNS": "250"}).stdout
    c_a = 1.5 / math.sqrt(1 + 1.5**2)
    alpha = c_a / math.sqrt(5.5)
    assert f"α1 = {alpha:.4g}" in text
    assert f"α = {alpha:.4g} | β1/3 = 0.151" in text
    assert "β2/2 = 0.1132" in text
    assert "β1/2" not in text


def test_bounds_table_names_the_binding_section_10_part(tmp_path: Path) -> None:
    # docs/model.md section 10: each bound is the least of its parts; the table's
    # candidates line must list the section-10 parts and name the least, as the JSON
    # parts give it (orders 1 and 2 with φ2 − 2φ1 = 90°: M3 ≠ 0, so k3 has two parts)
    path = tmp_path / "rotor.yaml"
    path.write_text(
        "gyrovib: 1\nprofiles:\n  - id: rotor\n    rate: [0, 0, 20]\n    harmonics:\n"
        "      fundamental: 40\n      orders:\n"
        "        - {order: 1, amplitude: [0.1, 0.1, 2.0], phase: [0, 0, 0]}\n"
        "        - {order: 2, amplitude: [0.0, 0.0, 1.0], phase: [0, 0, 90]}\n")
    doc = json.loads(run("bounds", path, "--budget", "0.01", "--format", "json").stdout)
    parts = doc["profiles"][0]["parts"]
    table = run("bounds", path, "--budget", "0.01", env={"COLUMNS": "160"}).stdout
    for name, labels in (("k3", ("additive", "linear")),
                         ("k4", ("additive", "multiplicative", "linear")),
                         ("k5", ("additive", "linear", "quadratic", "cubic"))):
        keys = {"additive": f"{name}_additive", "linear": f"{name}_linear",
                "multiplicative": f"{name}_multiplicative", "quadratic": f"{name}_quadratic",
                "cubic": f"{name}_cubic"}
        least = min(labels, key=lambda label: parts[keys[label]])
        line = next(row for row in table.splitlines()
                    if row.startswith(f"│ {name} ") and "binds" in row)
        assert all(f"{label} " in line for label in labels), line
        assert f"{least} binds" in line, line
