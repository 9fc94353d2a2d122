"""The mission's angle budget (docs/model.md section 15): the formulas worked by hand,
the verdict on the total, and unknown noise never read as 0."""

from __future__ import annotations

import json
import math

import pytest

from gyrovib import api
from gyrovib.catalog.loader import merge, parse_catalog
from tests.conftest import invoke

# A tactical sensor with every noise figure, one without any, over a two-hour mission
# (two segments of 3600 s) of one tone profile.
CATALOGUE = """\
gyrovib: 1
units: {rate: deg/s}
sensors:
  - id: full
    coefficients: {A1: 1.0e-5, k2: 2.0e-6}
    vre: 0
    noise:
      arw: 0.15 deg/sqrt(h)
      bias_instability: "0.5 °/h typ"
      rrw: {value: 0.02, unit: deg/h/sqrt(h)}
      bias_repeatability: 1
  - id: silent
    coefficients: {A1: 1.0e-5, k2: 2.0e-6}
    vre: 0
profiles:
  - id: tone
    rate: [0, 0, 0.5]
    harmonic: [{frequency: 40, amplitude: [0, 0, 2.0]}]
missions:
  - id: two-hours
    segments:
      - {profile: tone, duration: 3600}
      - {profile: tone, duration: "1 h"}
"""


def _result(**options: object):  # type: ignore[no-untyped-def]
    return api.mission(merge([parse_catalog(CATALOGUE, "<c>")]), **options)


def test_the_budget_is_the_formulas_worked_by_hand() -> None:
    row = _result(coverage=2.0).rows[0]
    b = row.budget
    assert b is not None
    t = 2.0                                    # hours: 3600 s + 1 h
    arw = 0.15 * math.sqrt(t)                  # N·√T
    bias = 0.5 * t                             # B·T
    rrw = 0.02 * t ** 1.5 / math.sqrt(3.0)     # K·T^{3/2}/√3
    rep = 1.0 * t                              # R·T
    # θ_V in deg: the row's angle (deg/s output: Σ T_s·Δ_V,s)
    assert b.vibration == pytest.approx(row.angle, rel=1e-12)
    assert (b.arw, b.bias_instability, b.rrw, b.repeatability) == pytest.approx(
        (arw, bias, rrw, rep), rel=1e-9, abs=0)
    total = abs(row.angle) + 2.0 * math.sqrt(arw**2 + bias**2 + rrw**2 + rep**2)
    assert b.total == pytest.approx(total, rel=1e-9, abs=0)
    assert b.unknown == () and not b.lower_bound and b.coverage == 2.0


def test_the_vibration_term_is_in_deg_whatever_the_output_unit() -> None:
    deg = _result(unit="deg/s").rows[0]
    rad = _result(unit="rad/s").rows[0]
    assert rad.budget.vibration == pytest.approx(math.degrees(rad.angle), rel=1e-12)
    assert rad.budget.total == pytest.approx(deg.budget.total, rel=1e-12)


def test_angle_budget_judges_the_total() -> None:
    # the noise alone, k = 1: √((0.15√2)² + 1² + (0.02·2^1.5/√3)² + 2²) ≈ 2.24 deg
    assert _result(angle_budget=math.radians(3.0)).rows[0].status == "pass"
    assert _result(angle_budget=math.radians(2.0)).rows[0].status == "fail"
    assert _result(angle_budget=math.radians(3.0), coverage=2.0).rows[0].status == "fail"


def test_an_unknown_figure_is_unknown_never_zero() -> None:
    row = _result(angle_budget=math.radians(3.0)).rows[1]
    assert row.sensor == "silent"
    b = row.budget
    assert b.arw is None and b.bias_instability is None and b.rrw is None
    assert b.lower_bound and b.total == pytest.approx(abs(row.angle), rel=1e-12)
    assert row.status == "unverified" and "arw" in row.unknown
    taken = _result(angle_budget=math.radians(3.0), assume_unknown="zero").rows[1]
    assert taken.status == "pass"


def test_json_and_table_say_unknown(tmp_path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "c.yaml"
    path.write_text(CATALOGUE, encoding="utf-8")
    out = invoke("mission", path, "--angle-budget", "3deg", "--format", "json")
    rows = json.loads(out.stdout)["mission"]
    silent = rows[1]["budget"]
    assert silent["arw"] is None and silent["lower_bound"] is True
    assert set(rows[0]["budget"]) == {"vibration", "arw", "bias_instability", "rrw",
                                      "repeatability", "total", "coverage", "unit",
                                      "lower_bound", "rests_on_bound", "bounds", "typical",
                                      "allowed"}
    # with unknown noise figures, every figure's allowance is only an upper limit (the
    # unknown ones can only take more of the budget); with all known, none is
    assert rows[1]["budget"]["allowed"]["upper"] == ["vibration", "arw", "bias_instability",
                                                     "rrw", "repeatability"]
    assert rows[0]["budget"]["allowed"]["upper"] == []
    table = invoke("mission", path, "--angle-budget", "3deg").stdout
    line = next(x for x in table.splitlines() if x.startswith("│ silent"))
    assert "?" in line and " 0 " not in line
    # the allowance table marks the upper limits with '*'
    allowed = [x for x in table.splitlines() if x.startswith("│ silent")][-1]
    assert "*" in allowed


def test_select_ranks_on_the_total(tmp_path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "c.yaml"
    path.write_text(CATALOGUE, encoding="utf-8")
    out = invoke("select", path, "--mission", "two-hours", "--angle-budget", "3deg",
                 "--format", "json")
    sensors = json.loads(out.stdout)["sensors"]
    # 'silent' gives no noise figure: its total is only a lower bound (|θ_V| alone, smaller
    # than full's ≈ 2.24 deg, test_angle_budget_judges_the_total), so it is not ranked above
    # the sensor whose every figure is known: it follows it, without a rank
    assert [(s["sensor"], s["rank"], s["status"]) for s in sensors] == [
        ("full", 1, "pass"), ("silent", None, "unverified")]


def test_select_does_not_rank_lower_bounds_in_any_format(tmp_path) -> None:  # type: ignore[no-untyped-def]
    # a variant: three sensors without noise figures (smaller lower bounds) and one with all
    text = CATALOGUE.replace("profiles:", "".join(
        f"  - id: quiet-{k}\n    coefficients: {{A1: 1.0e-6}}\n    vre: 0\n"
        for k in range(3)) + "profiles:")
    path = tmp_path / "c.yaml"
    path.write_text(text, encoding="utf-8")
    args = ("select", path, "--mission", "two-hours", "--angle-budget", "3deg")
    doc = json.loads(invoke(*args, "--format", "json").stdout)
    assert doc["sensors"][0]["sensor"] == "full"
    assert [s["rank"] for s in doc["sensors"]] == [1, None, None, None, None]
    rows = invoke(*args, "--format", "csv").stdout.splitlines()[1:]
    assert rows[0].startswith("full,")
    for fmt in ("table", "markdown"):
        out = invoke(*args, "--format", fmt).stdout
        assert out.index("full") < out.index("quiet-0")
        assert "Not ranked" in out and "silent" in out.split("Not ranked")[1]


def test_coverage_must_be_positive() -> None:
    assert invoke("mission", "--coverage", "0").exit_code == 2


def test_report_shows_the_budget_as_a_stacked_bar(tmp_path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "c.yaml"
    path.write_text(CATALOGUE, encoding="utf-8")
    out = tmp_path / "r.html"
    result = invoke("report", path, "--budget", "10deg/h", "--mission", "two-hours",
                    "--angle-budget", "3deg", "--coverage", "2", "-o", out)
    assert result.exit_code == 0, result.stderr
    html = out.read_text(encoding="utf-8")
    chart = html[html.index("Angle budget over two-hours: |θ_V| + 2·RSS(noise)"):]
    chart = chart[:chart.index("</svg>")]
    # full: the vibration and the four noise parts; silent: its vibration and '≥ ?'
    for part in ("full: vibration |θ_V|", "full: angle random walk", "full: bias instability",
                 "full: rate random walk", "full: bias repeatability", "silent: vibration"):
        assert part in chart
    assert "silent: angle random walk" not in chart and chart.count("≥ ?") == 1


BOUNDED = CATALOGUE.replace('rrw: {value: 0.02, unit: deg/h/sqrt(h)}',
                            'rrw: "≤ 0.02 deg/h/sqrt(h)"')


def test_a_bound_is_the_budget_maximum_and_the_row_says_so(tmp_path) -> None:  # type: ignore[no-untyped-def]
    measured = _result(coverage=2.0).rows[0].budget
    bounded = api.mission(merge([parse_catalog(BOUNDED, "<c>")]), coverage=2.0).rows[0]
    b = bounded.budget
    assert b is not None and measured is not None
    # the bound's upper value enters exactly as the value did (K·T^{3/2}/√3 at K = 0.02)
    assert b.rrw == measured.rrw and b.total == measured.total
    assert b.bounds == ("rrw",) and measured.bounds == ()
    path = tmp_path / "c.yaml"
    path.write_text(BOUNDED, encoding="utf-8")
    doc = json.loads(invoke("mission", path, "--angle-budget", "3deg", "--format",
                            "json").stdout)["mission"][0]["budget"]
    assert doc["rests_on_bound"] is True and doc["bounds"] == ["rrw"]
    table = invoke("mission", path, "--angle-budget", "3deg").stdout
    assert f"≤ {b.rrw:.4g}" in table and "rests on" in table


def test_a_triad_row_takes_its_axis_figures() -> None:
    per_axis = CATALOGUE.replace("      bias_repeatability: 1\n",
                                 "      bias_repeatability: 1\n"
                                 "      z: {arw: 0.6 deg/sqrt(h), rrw: \"≤ 0.1 deg/h/sqrt(h)\"}\n")
    per_axis = per_axis.replace("  - id: two-hours\n", "  - id: two-hours\n    placement: triad\n")
    rows = [r for r in api.mission(merge([parse_catalog(per_axis, "<c>")])).rows
            if r.sensor == "full"]
    by_axis = {r.axis: r.budget for r in rows}
    assert set(by_axis) == {"X", "Y", "Z"}
    t = 2.0
    # X and Y: the block's own figures; Z: its sub-block's N and bound on K, the block's B
    assert by_axis["X"].arw == pytest.approx(0.15 * math.sqrt(t), rel=1e-12)
    assert by_axis["Z"].arw == pytest.approx(0.6 * math.sqrt(t), rel=1e-12)
    assert by_axis["Z"].rrw == pytest.approx(0.1 * t ** 1.5 / math.sqrt(3.0), rel=1e-12)
    assert by_axis["Z"].bias_instability == by_axis["X"].bias_instability
    assert by_axis["Z"].bounds == ("rrw",) and by_axis["X"].bounds == ()
