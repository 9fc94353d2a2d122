"""Missions and placements (docs/model.md section 12): the aggregates against per-segment
analyze results worked by hand, the spec-form mission worst case against an independent
LP, placements against profiles permuted by hand, and invariants."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib import api
from gyrovib.api.placement.placement import place_catalog
from gyrovib.catalog.loader import merge, parse_catalog
from gyrovib.core.placement import Placement, parse
from tests.conftest import invoke

# A coefficient sensor with odd, even and cross-axis terms, so that sign flips,
# permutations and coherences all move its error.
SENSOR = """\
gyrovib: 1
units: {rate: deg/s}
sensors:
  - id: s
    coefficients: {A1: 2.0e-3, k2: 3.0e-4, k3: 2.0e-6, k4: 1.0e-7, m31: 5.0e-4, m32: -3.0e-4}
"""

# A profile in vehicle axes with a different value on every axis.
PROFILE = """\
  - id: veh
    rate: [1.0, 2.0, 3.0]
    harmonic:
      - {frequency: 50, amplitude: [1.0, 2.0, 3.0], phase: [10, 40, 70]}
      - {frequency: 120, amplitude: [0.5, 0.25, 1.5], phase: [0, 90, 200]}
    random: {rms: [0.7, 1.1, 1.9], coherence: [0.4, -0.3, 0.25]}
"""


def _catalog(*texts: str):  # type: ignore[no-untyped-def]
    return merge([parse_catalog(t, f"<{k}>") for k, t in enumerate(texts)])


def _profiles(*items: str) -> str:
    return "gyrovib: 1\nprofiles:\n" + "".join(items)


def _analyze(catalog) -> np.ndarray:  # type: ignore[no-untyped-def]
    return np.asarray(api.analyze(catalog).error.total)


# ---------------------------------------------------------------- placements by hand

# x1=-X, x2=-Y, x3=+Z (two flips, det +1): rates of X and Y negate, their tones' phases
# gain 180°, ρ31 and ρ32 change sign (one flipped axis each), ρ12 does not (two).
FLIPPED = """\
  - id: veh
    rate: [-1.0, -2.0, 3.0]
    harmonic:
      - {frequency: 50, amplitude: [1.0, 2.0, 3.0], phase: [190, 220, 70]}
      - {frequency: 120, amplitude: [0.5, 0.25, 1.5], phase: [180, 270, 200]}
    random: {rms: [0.7, 1.1, 1.9], coherence: [-0.4, 0.3, 0.25]}
"""
# x1=+Y, x2=+Z, x3=+X (cyclic): sensor axes read (Y, Z, X); ρ31' = corr(X, Y) = ρ12,
# ρ32' = corr(X, Z) = ρ31, ρ12' = corr(Y, Z) = ρ32.
CYCLIC = """\
  - id: veh
    rate: [2.0, 3.0, 1.0]
    harmonic:
      - {frequency: 50, amplitude: [2.0, 3.0, 1.0], phase: [40, 70, 10]}
      - {frequency: 120, amplitude: [0.25, 1.5, 0.5], phase: [90, 200, 0]}
    random: {rms: [1.1, 1.9, 0.7], coherence: [0.25, 0.4, -0.3]}
"""
# x1=+Z, x2=+X, x3=+Y: sensor axes read (Z, X, Y); ρ31' = corr(Y, Z) = ρ32,
# ρ32' = corr(Y, X) = ρ12, ρ12' = corr(Z, X) = ρ31.
CYCLIC2 = """\
  - id: veh
    rate: [3.0, 1.0, 2.0]
    harmonic:
      - {frequency: 50, amplitude: [3.0, 1.0, 2.0], phase: [70, 10, 40]}
      - {frequency: 120, amplitude: [1.5, 0.5, 0.25], phase: [200, 0, 90]}
    random: {rms: [1.9, 0.7, 1.1], coherence: [-0.3, 0.25, 0.4]}
"""


@pytest.mark.parametrize(("placement", "by_hand"), [
    ("x1=-X,x2=-Y,x3=+Z", FLIPPED),
    ("x1=+Y,x2=+Z,x3=+X", CYCLIC),
    ("x1=+Z,x2=+X,x3=+Y", CYCLIC2),
])
def test_a_placed_profile_is_the_profile_permuted_by_hand(placement: str, by_hand: str) -> None:
    placed = _analyze(place_catalog(_catalog(SENSOR, _profiles(PROFILE)), parse(placement)))
    hand = _analyze(_catalog(SENSOR, _profiles(by_hand)))
    plain = _analyze(_catalog(SENSOR, _profiles(PROFILE)))
    np.testing.assert_allclose(placed, hand, rtol=1e-12, atol=0)
    assert not np.allclose(placed, plain)  # the placement does move the error


def test_a_triad_is_the_three_hand_permuted_profiles() -> None:
    mission = """\
gyrovib: 1
missions:
  - id: m
    placement: triad
    segments: [{profile: veh, duration: 60}]
"""
    result = api.mission(_catalog(SENSOR, _profiles(PROFILE), mission), unit="deg/s")
    by_axis = {r.axis: r.mean for r in result.rows}
    # x3 on X: (x1, x2) = (+Y, +Z) is CYCLIC; on Y: (+Z, +X) is CYCLIC2; on Z: the profile
    expected = {"X": _analyze(_catalog(SENSOR, _profiles(CYCLIC)))[0, 0],
                "Y": _analyze(_catalog(SENSOR, _profiles(CYCLIC2)))[0, 0],
                "Z": _analyze(_catalog(SENSOR, _profiles(PROFILE)))[0, 0]}
    assert by_axis == pytest.approx(expected, rel=1e-12)
    worst = max(expected, key=lambda a: abs(expected[a]))
    assert {r.worst_axis for r in result.rows} == {worst}


_axis = st.floats(0.0, 3.0)
_phase = st.floats(-180.0, 180.0)
_rho = st.floats(-0.5, 0.5)


@given(rate=st.tuples(st.floats(-5, 5), st.floats(-5, 5), st.floats(-5, 5)),
       amp=st.tuples(_axis, _axis, _axis), phase=st.tuples(_phase, _phase, _phase),
       rms=st.tuples(_axis, _axis, _axis), rho=st.tuples(_rho, _rho, _rho))
def test_the_default_placement_and_full_turns_change_nothing(rate, amp, phase, rms, rho):  # type: ignore[no-untyped-def]
    """The default placement is the identity; so are three cyclic turns and a double
    flip through the general mapping (each step maps every part of the profile)."""
    text = _profiles(
        f"  - id: veh\n    rate: {list(rate)}\n"
        f"    harmonic: [{{frequency: 80, amplitude: {list(amp)}, phase: {list(phase)}}}]\n"
        f"    random: {{rms: {list(rms)}, coherence: {list(rho)}}}\n")
    catalog = _catalog(SENSOR, text)
    plain = _analyze(catalog)
    assert np.array_equal(_analyze(place_catalog(catalog, parse("default"))), plain)
    turn = parse("x1=+Y,x2=+Z,x3=+X")
    flip = parse("x1=-X,x2=-Y,x3=+Z")
    assert isinstance(turn, Placement) and isinstance(flip, Placement)
    turned = place_catalog(place_catalog(place_catalog(catalog, turn), turn), turn)
    flipped = place_catalog(place_catalog(catalog, flip), flip)
    np.testing.assert_allclose(_analyze(turned), plain, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(_analyze(flipped), plain, rtol=1e-9, atol=1e-15)


# ---------------------------------------------------------------- aggregates by hand

TWO_PROFILES = """\
  - id: hover
    rate: [0, 0, 2]
    random: {rms: [0.5, 0.5, 1.5]}
  - id: turn
    harmonic: [{frequency: 100, amplitude: [1, 0.5, 2]}]
"""
# 'turn' at the segment's rate 10 deg/s about Z, written out by hand
TURN_AT_10 = """\
  - id: turn10
    rate: [0, 0, 10]
    harmonic: [{frequency: 100, amplitude: [1, 0.5, 2]}]
"""
MISSION = """\
gyrovib: 1
units: {rate: deg/h}
missions:
  - id: flight
    segments:
      - {profile: hover, duration: 10 min}
      - {profile: turn, duration: 60, rate: [0, 0, 36000]}
      - {profile: hover, duration: 2 min}
"""


def test_mean_angle_rms_and_worst_segment_by_hand() -> None:
    # the segments' Δ_V and Δ_V(RMS) from analyze, each profile as written by hand
    per = api.analyze(_catalog(SENSOR, _profiles(TWO_PROFILES, TURN_AT_10)),
                      profiles=["hover", "turn10"], unit="deg/h")
    d_hover, d_turn = (float(v) for v in per.error.total[0])
    r_hover, r_turn = (float(v) for v in per.error.rms[0])
    t = [600.0, 60.0, 120.0]  # 10 min, 60 s, 2 min; 36000 deg/h = 10 deg/s
    d = [d_hover, d_turn, d_hover]
    r = [r_hover, r_turn, r_hover]
    theta_deg = sum(a * b for a, b in zip(t, d, strict=True)) / 3600.0  # deg/h × s → deg
    mean = theta_deg * 3600.0 / sum(t)
    rms = math.sqrt(sum(a * b * b for a, b in zip(t, r, strict=True)) / sum(t))
    result = api.mission(_catalog(SENSOR, _profiles(TWO_PROFILES), MISSION), unit="deg/h")
    (row,) = result.rows
    assert result.angle_unit == "deg"
    assert row.mean == pytest.approx(mean, rel=1e-12)
    assert row.angle == pytest.approx(theta_deg, rel=1e-12)
    assert row.rms == pytest.approx(rms, rel=1e-12)
    worst = int(np.argmax(np.abs(d)))
    assert (row.worst_index, row.worst_profile) == (worst, ["hover", "turn", "hover"][worst])
    assert [s.total for s in row.segments] == pytest.approx(d, rel=1e-12)
    assert row.segments[1].rate == pytest.approx((0.0, 0.0, 36000.0))
    # in rad/s the angle is in rad
    rad = api.mission(_catalog(SENSOR, _profiles(TWO_PROFILES), MISSION), unit="rad/s")
    assert rad.angle_unit == "rad"
    assert rad.rows[0].angle == pytest.approx(math.radians(theta_deg), rel=1e-12)


@settings(max_examples=15)
@given(fraction=st.floats(0.01, 0.99), seconds=st.floats(1.0, 1e5))
def test_splitting_a_segment_changes_nothing(fraction: float, seconds: float) -> None:
    """A segment split in two of the same profile: the same mean, angle and RMS, for a
    coefficient sensor and for a datasheet sensor's whole-mission worst case."""
    first = seconds * fraction
    whole = MISSION.replace("duration: 10 min", f"duration: {seconds!r}")
    split = MISSION.replace("- {profile: hover, duration: 10 min}",
                            f"- {{profile: hover, duration: {first!r}}}\n"
                            f"      - {{profile: hover, duration: {seconds - first!r}}}")
    profiles = _profiles(TWO_PROFILES)
    a = api.mission(_catalog(SENSOR, SPEC, profiles, whole)).rows
    b = api.mission(_catalog(SENSOR, SPEC, profiles, split)).rows
    for x, y in zip(a, b, strict=True):
        assert len(y.segments) == len(x.segments) + 1
        assert (y.mean, y.angle, y.rms) == pytest.approx((x.mean, x.angle, x.rms), rel=1e-9)


def test_saturation_in_one_segment_fails_the_mission() -> None:
    ranged = SENSOR.replace("  - id: s\n", "  - id: s\n    range: 20\n")
    text = MISSION.replace("rate: [0, 0, 36000]", "rate: [0, 0, 72000]")  # 20 deg/s + tones
    result = api.mission(_catalog(ranged, _profiles(TWO_PROFILES), text),
                         angle_budget=1.0)  # 1 rad: the angle alone would pass
    (row,) = result.rows
    assert row.saturated and [s.saturated for s in row.segments] == [False, True, False]
    assert row.passed is False and not result.requirement_met


# ---------------------------------------------------------------- datasheet sensors

SPEC = """\
gyrovib: 1
sensors:
  - id: ds
    specs:
      range: 300
      nonlinearity: {value: 0.1, unit: "%FS"}
"""
R, B = 300.0, 0.3  # 0.1 %FS of a 300 deg/s range, least-squares line, max measure
UNIT_SENSORS = "".join(
    f"  - id: unit-{name}\n    coefficients: {{{name}: {scale}}}\n"
    for name, scale in (("A1", 1e-3), ("k2", 1e-5), ("k3", 1e-7), ("k4", 1e-9), ("k5", 1e-11)))
SCALES = np.array([1e-3, 1e-5, 1e-7, 1e-9, 1e-11])


def _functionals(profiles: str) -> np.ndarray:
    """c_s per profile: Δ_V is linear in x = (A1, k2…k5), so a sensor with one unit
    coefficient gives one column (analyze of coefficient sensors, no envelope code)."""
    cat = _catalog("gyrovib: 1\nsensors:\n" + UNIT_SENSORS, _profiles(profiles))
    return np.asarray(api.analyze(cat).error.total).T / SCALES  # (P, 5)


def _lp_worst(c: np.ndarray) -> float:
    """max |c·x| over |p(ω) − LS line of p| ≤ b on a fine grid of [−R, R] (scipy)."""
    from scipy.optimize import linprog

    w = np.linspace(-R, R, 4001)
    basis = np.stack([0.5 * np.abs(w), w**2, w**3, w**4, w**5], axis=1)
    line = np.stack([np.ones_like(w), w], axis=1)
    proj = line @ np.linalg.lstsq(line, basis, rcond=None)[0]
    resid = basis - proj                                              # r(ω) = resid · x
    # scale the variables to order 1: x_k = u_k / R^(k+1) ... R^k
    s = np.array([1.0, R**-1, R**-2, R**-3, R**-4])
    a = resid * s
    res = linprog(-(c * s), A_ub=np.vstack([a, -a]), b_ub=np.full(2 * w.size, B),
                  bounds=[(None, None)] * 5, method="highs")
    assert res.status == 0
    return float(-res.fun)


MIXED = """\
  - id: slow
    rate: [0, 0, 1]
    random: {rms: [0, 0, 20]}
  - id: fast
    rate: [0, 0, 150]
    harmonic: [{frequency: 100, amplitude: [0, 0, 5]}]
"""


def test_spec_mission_worst_case_is_one_programme_against_an_lp() -> None:
    mission = """\
gyrovib: 1
missions:
  - id: m
    segments: [{profile: slow, duration: 300}, {profile: fast, duration: 100}]
"""
    c = _functionals(MIXED)                                           # (2, 5)
    weights = np.array([300.0, 100.0]) / 400.0
    lp = _lp_worst(weights @ c)
    result = api.mission(_catalog(SPEC, _profiles(MIXED), mission))
    (row,) = result.rows
    assert row.source == "specs"
    assert row.mean == pytest.approx(lp, rel=2e-3)  # grid LP vs refined continuous LP
    assert row.angle == pytest.approx(row.mean * 400.0, rel=1e-12)
    # each segment's own worst case, and their duration-weighted sum: strictly larger
    per = [_lp_worst(ci) for ci in c]
    assert [s.total for s in row.segments] == pytest.approx(per, rel=2e-3)
    summed = float(weights @ np.array([s.total for s in row.segments]))
    assert row.mean < summed * (1 - 1e-3)


def test_spec_mission_equals_the_sum_when_one_function_is_worst_everywhere() -> None:
    # the same profile at two durations: one polynomial is worst for both segments
    mission = """\
gyrovib: 1
missions:
  - id: m
    segments: [{profile: slow, duration: 300}, {profile: slow, duration: 100, rate: [0, 0, 1]}]
"""
    (row,) = api.mission(_catalog(SPEC, _profiles(MIXED), mission)).rows
    summed = (300.0 * row.segments[0].total + 100.0 * row.segments[1].total) / 400.0
    assert row.mean == pytest.approx(summed, rel=1e-9)


# ---------------------------------------------------------------- the command

def test_bundled_mission_prints_angle_and_worst_segment() -> None:
    result = invoke("mission", "--format", "json")
    assert result.exit_code == 0, result.stderr
    doc = json.loads(result.stdout)
    # the default output unit is every command's (README, "Units": deg/s unless --budget
    # carries a unit)
    assert doc["angle_unit"] == "deg" and doc["unit"] == "deg/s"
    rows = doc["mission"]
    assert {r["mission"] for r in rows} == {"survey-flight"}
    assert {r["axis"] for r in rows} == {"X", "Y", "Z"}
    for r in rows:
        assert set(r) >= {"sensor", "mission", "placement", "mean", "angle", "rms",
                          "worst_segment", "segments", "saturated", "pass", "axis",
                          "worst_axis"}
        assert r["angle"] == pytest.approx(  # deg/s × s = deg
            sum(s["duration"] * s["total"] for s in r["segments"]), rel=1e-9) \
            or r["source"] == "specs"
    table = invoke("mission")
    assert "survey-flight" in table.stdout and "flat-random-hover" in table.stdout


def test_angle_budget_exits_1_when_no_sensor_passes() -> None:
    mems = ["--sensor", "adxrs645", "--sensor", "sch16t", "--sensor", "generic-rate-mems"]
    result = invoke("mission", *mems, "--angle-budget", "0.5deg")
    assert result.exit_code == 1
    assert "FAIL" in result.stdout
    # the navigation FOG gives no g² figure (catalogs/sensors.gyrovib.yaml): under the
    # flight's shaken segments it is unverified, a failure for junit; taking the
    # unknown figure as 0 it passes
    open_ = invoke("mission", "--sensor", "generic-navigation-fog", "--angle-budget", "0.5deg",
                   "--format", "junit")
    assert open_.exit_code == 1 and "Unverified" in open_.stdout
    # the row's reason names the option that takes the unknown as 0 (the command line's)
    rows = json.loads(invoke("mission", "--sensor", "generic-navigation-fog", "--angle-budget",
                             "0.5deg", "--format", "json").stdout)["mission"]
    assert any(r["reason"] and r["reason"].endswith(
        "-- ask the vendor, or --assume-unknown zero to take it as 0") for r in rows)
    ok = invoke("mission", "--sensor", "generic-navigation-fog", "--angle-budget", "0.5deg",
                "--format", "junit", "--assume-unknown", "zero")
    assert ok.exit_code == 0 and 'failures="0"' in ok.stdout


def test_angle_budget_units_and_refusals() -> None:
    r = invoke("mission", "--sensor", "generic-navigation-fog", "--angle-budget", "2 mrad",
               "--format", "json", "--assume-unknown", "zero")
    assert r.exit_code == 0
    assert json.loads(r.stdout)["angle_budget"] == pytest.approx(math.degrees(2e-3))
    bad = invoke("mission", "--angle-budget", "0.5")
    assert bad.exit_code == 2 and "angle unit" in bad.stderr
    both = invoke("mission", "--angle-budget", "1deg", "--budget", "1")
    assert both.exit_code == 2


def test_csv_and_frame_have_one_row_per_sensor_mission_axis() -> None:
    result = api.mission(api.load(), sensors=["generic-navigation-fog"])
    frame = result.to_frame()
    assert len(frame) == 3 and list(frame["axis"]) == ["X", "Y", "Z"]
    csv = invoke("mission", "--sensor", "generic-navigation-fog", "--format", "csv").stdout
    assert csv.splitlines()[0].split(",") == list(frame.columns)
    assert len(csv.splitlines()) == 4


# ---------------------------------------------------------------- --placement on the commands


def test_analyze_placement_option_against_a_hand_permuted_file(tmp_path) -> None:  # type: ignore[no-untyped-def]
    veh = tmp_path / "veh.yaml"
    veh.write_text(SENSOR + "profiles:\n" + PROFILE, encoding="utf-8")
    hand = tmp_path / "hand.yaml"
    hand.write_text(SENSOR + "profiles:\n" + CYCLIC, encoding="utf-8")
    placed = invoke("analyze", veh, "--placement", "x1=+Y,x2=+Z,x3=+X", "--format", "json")
    by_hand = invoke("analyze", hand, "--format", "json")
    assert placed.exit_code == 0 and by_hand.exit_code == 0
    assert json.loads(placed.stdout)["results"] == json.loads(by_hand.stdout)["results"]


def test_analyze_triad_tags_each_result_with_its_axis(tmp_path) -> None:  # type: ignore[no-untyped-def]
    veh = tmp_path / "veh.yaml"
    veh.write_text(SENSOR + "profiles:\n" + PROFILE, encoding="utf-8")
    doc = json.loads(invoke("analyze", veh, "--placement", "triad", "--format", "json").stdout)
    totals = {r["axis"]: r["total"] for r in doc["results"]}
    for axis, text in (("X", CYCLIC), ("Y", CYCLIC2), ("Z", PROFILE)):
        expected = _analyze(_catalog(SENSOR, _profiles(text)))[0, 0]
        assert totals[axis] == pytest.approx(expected, rel=1e-12)
    assert doc["worst_axis"] == {"s": max(totals, key=lambda a: abs(totals[a]))}
    assert doc["placement"] == "triad"


def test_select_triad_fails_a_sensor_failing_on_one_axis(tmp_path) -> None:  # type: ignore[no-untyped-def]
    # all vibration on X: the sensor is quiet with x3 on Z, loud with x3 on X
    text = SENSOR + "profiles:\n  - id: xonly\n    random: {rms: [3.0, 0, 0]}\n"
    path = tmp_path / "x.yaml"
    path.write_text(text, encoding="utf-8")
    plain = invoke("select", path, "--budget", "1e-3", "--criterion", "rms")
    assert plain.exit_code == 0, plain.stdout  # x3 on Z: no x3 vibration, no error
    triad = invoke("select", path, "--budget", "1e-3", "--criterion", "rms",
                   "--placement", "triad", "--format", "json")
    assert triad.exit_code == 1
    doc = json.loads(triad.stdout)
    assert doc["worst_axis"] == {"s": "X"} and doc["requirement_met"] is False


def test_a_mirror_placement_option_is_refused() -> None:
    result = invoke("analyze", "--placement", "x1=+Y,x2=+X,x3=+Z")
    assert result.exit_code == 2 and "determinant -1" in result.stderr


def test_select_on_a_mission_is_the_mission_verdict() -> None:
    args = ["--sensor", "sch16t", "--sensor", "generic-navigation-fog", "--format", "json",
            "--assume-unknown", "zero"]
    direct = invoke("mission", "--mission", "survey-flight", "--angle-budget", "0.5deg", *args)
    chosen = invoke("select", "--mission", "survey-flight", "--angle-budget", "0.5deg", *args)
    assert direct.exit_code == chosen.exit_code == 0
    mission_doc, select_doc = json.loads(direct.stdout), json.loads(chosen.stdout)
    # the same verdicts, select's sensors ranked on their largest budget total (section 15)
    def key(r: dict) -> tuple[str, str]:  # type: ignore[type-arg]
        return r["sensor"], r.get("axis", "")

    assert sorted(select_doc["mission"], key=key) == sorted(mission_doc["mission"], key=key)
    worst = {s["sensor"]: max(r["budget"]["total"] for r in select_doc["mission"]
                              if r["sensor"] == s["sensor"]) for s in select_doc["sensors"]}
    order = [s["sensor"] for s in select_doc["sensors"]]
    # only a sensor whose every total is a figure is ranked, the others follow unranked
    lower = {r["sensor"] for r in select_doc["mission"] if r["budget"]["lower_bound"]}
    ranked = [s for s in order if s not in lower]
    assert ranked == sorted(ranked, key=worst.__getitem__)
    assert order == ranked + [s for s in order if s in lower]
    assert [s["rank"] for s in select_doc["sensors"]] == [
        *range(1, len(ranked) + 1), *[None] * (len(order) - len(ranked))]
    assert set(order) == {"generic-navigation-fog", "sch16t"}
    # only the MEMS part: nothing passes, exit 1; --budget (on the mean RMS) alike
    assert invoke("select", "--mission", "survey-flight", "--angle-budget", "0.5deg",
                  "--sensor", "sch16t").exit_code == 1
    assert invoke("select", "--mission", "survey-flight", "--budget", "1deg/h",
                  "--sensor", "sch16t").exit_code == 1
    assert invoke("select").exit_code == 2  # without a mission --budget is still required


def test_report_gains_a_mission_section(tmp_path) -> None:  # type: ignore[no-untyped-def]
    out = tmp_path / "r.html"
    result = invoke("report", "--budget", "10deg/h", "--profile", "flat-random-hover",
                    "--sensor", "sch16t", "--sensor", "generic-tactical-fog",
                    "--mission", "survey-flight", "--angle-budget", "0.5deg", "-o", out)
    assert result.exit_code == 0, result.stderr
    html = out.read_text(encoding="utf-8")
    section = html[html.index("<h2>Missions</h2>"):]
    assert "Accumulated angle |θ_V| over survey-flight" in section
    assert "θ* = 0.5 deg" in section
    doc = json.loads(invoke("mission", "--sensor", "sch16t", "--sensor", "generic-tactical-fog",
                            "--format", "json").stdout)
    for r in doc["mission"]:
        if r["axis"] == r["worst_axis"]:  # the report shows each sensor's worst axis
            from gyrovib.render.common import fmt

            assert f"{r['sensor']} with x3 on {r['axis']}: θ_V = {fmt(r['angle'])} deg" in section
    # one table row per segment (8) per sensor shown (2), and a header row each; then
    # the verdict table and the noise figures' table, a header and a row per sensor each
    assert section.count("<tr") == 2 * (8 + 1) + 2 * (1 + 2)


def test_notebook_mission_is_the_command() -> None:
    import gyrovib

    result = gyrovib.mission(sensors="generic-navigation-fog", angle_budget="0.5deg")
    doc = json.loads(invoke("mission", "--sensor", "generic-navigation-fog",
                            "--angle-budget", "0.5deg", "--format", "json").stdout)
    assert [r.angle for r in result.rows] == [r["angle"] for r in doc["mission"]]
    assert result.angle_budget == pytest.approx(0.5)
    with pytest.raises(gyrovib.errors.ArgumentError, match="angle unit"):
        gyrovib.mission(angle_budget="0.5")
    with pytest.raises(gyrovib.errors.ArgumentError, match="determinant -1"):
        gyrovib.mission(placement="x1=+Y,x2=+X,x3=+Z")


# Locked orders, a PSD on two axes and a linear vibration, for a sensor with every
# g² sensitivity: the parts test_a_placed_profile_... does not reach.
SENSOR_G2 = """\
gyrovib: 1
sensors:
  - id: g
    coefficients: {A1: 2.0e-3, k2: 3.0e-4, k3: 2.0e-5, k4: 1.0e-7, m31: 5.0e-4, m32: -3.0e-4}
    g2_sensitivity: {G11: 4.0e-3, G22: 1.0e-3, G33: 2.0e-3, G12: 1.5e-3, G13: -2.0e-3, G23: 3.0e-3}
"""
RICH = """\
  - id: veh
    rate: [1.0, 2.0, 3.0]
    harmonics:
      fundamental: 20
      orders:
        - {order: 1, amplitude: [1.0, 0.5, 2.0], phase: [0, 30, 60]}
        - {order: 2, amplitude: [0.3, 0.6, 0.9], phase: [10, 20, 45]}
    random:
      psd:
        x1: [[20, 1.0e-3], [500, 1.0e-3]]
        x3: [[20, 4.0e-3], [800, 2.0e-3]]
      coherence: [0.3, 0.0]
    acceleration:
      harmonic:
        - {frequency: 100, amplitude: [1.0, 2.0, 3.0], phase: [0, 90, 30]}
      random:
        rms: [1.0, 2.0, 0.5]
        coherence: [0.5, -0.2, 0.1]
"""
# x1=-Y, x2=+X, x3=+Z (a quarter turn about Z): sensor axes read (−Y, X, Z). Y's phases
# gain 180°; the PSD of X moves to x2 (Y has none); rate coherences: ρ31' = corr(Z, −Y)
# = −ρ32 = 0, ρ32' = corr(Z, X) = ρ31 = 0.3, ρ12' = corr(−Y, X) = −ρ31·ρ32 = 0;
# acceleration: ρ12' = corr(−Y, X) = −0.5, ρ13' = corr(−Y, Z) = −0.1, ρ23' = corr(X, Z) = −0.2.
RICH_TURNED = """\
  - id: veh
    rate: [-2.0, 1.0, 3.0]
    harmonics:
      fundamental: 20
      orders:
        - {order: 1, amplitude: [0.5, 1.0, 2.0], phase: [210, 0, 60]}
        - {order: 2, amplitude: [0.6, 0.3, 0.9], phase: [200, 10, 45]}
    random:
      psd:
        x2: [[20, 1.0e-3], [500, 1.0e-3]]
        x3: [[20, 4.0e-3], [800, 2.0e-3]]
      coherence: [0.0, 0.3, 0.0]
    acceleration:
      harmonic:
        - {frequency: 100, amplitude: [2.0, 1.0, 3.0], phase: [270, 0, 30]}
      random:
        rms: [2.0, 1.0, 0.5]
        coherence: [-0.5, -0.1, -0.2]
"""


def test_locked_orders_psd_and_linear_vibration_are_placed_as_by_hand() -> None:
    turn = parse("x1=-Y,x2=+X,x3=+Z")
    assert isinstance(turn, Placement)
    placed = api.analyze(place_catalog(_catalog(SENSOR_G2, _profiles(RICH)), turn))
    hand = api.analyze(_catalog(SENSOR_G2, _profiles(RICH_TURNED)))
    plain = api.analyze(_catalog(SENSOR_G2, _profiles(RICH)))
    for name in ("total", "rms", "additive_terms", "extra_terms"):
        np.testing.assert_allclose(getattr(placed.error, name), getattr(hand.error, name),
                                   rtol=1e-12, atol=1e-18)
    assert not np.allclose(placed.error.total, plain.error.total)
    assert not np.allclose(placed.error.extra_terms[..., 0], plain.error.extra_terms[..., 0])


def test_mission_unit_defaults_as_every_command() -> None:
    """--unit: the unit --budget is written in, else deg/s (README, "Units"), as
    analyze and select; the angle stays in deg either way, and the same number."""
    plain = json.loads(invoke("mission", "--sensor", "adxrs453", "--format", "json").stdout)
    hours = json.loads(invoke("mission", "--sensor", "adxrs453", "--budget", "36deg/h",
                              "--format", "json").stdout)
    analyzed = json.loads(invoke("analyze", "--sensor", "adxrs453", "--profile",
                                 "flat-random-hover", "--format", "json").stdout)
    assert plain["unit"] == analyzed["unit"] == "deg/s"
    assert hours["unit"] == "deg/h"
    for a, b in zip(plain["mission"], hours["mission"], strict=True):
        assert b["angle"] == pytest.approx(a["angle"], rel=1e-12)
        assert b["mean"] == pytest.approx(3600.0 * a["mean"], rel=1e-12)  # 1 deg/s = 3600 deg/h


def test_a_gaussian_part_whose_variance_underflows_counts_as_none() -> None:
    """A random part of rms 2.2e-313 (σ² underflows to 0) beside a tone: E moves by at
    most σ·√(2/π) from the tone alone (|·| is 1-Lipschitz), so the analysis equals the
    tone-only profile's to the last bit instead of overflowing (a case hypothesis found
    for the placement invariant above)."""
    def profile(rms: str) -> str:
        return _profiles("  - id: veh\n    rate: [0.0, 0.0, 0.0]\n"
                         "    harmonic: [{frequency: 80, amplitude: [0.0, 0.0, 1.0], "
                         "phase: [0.0, 0.0, 0.0]}]\n"
                         f"    random: {{rms: [0.0, 0.0, {rms}], coherence: [0.0, 0.0, 0.0]}}\n")
    tiny = _analyze(_catalog(SENSOR, profile("2.2250738585e-313")))
    none = _analyze(_catalog(SENSOR, profile("0.0")))
    assert np.array_equal(tiny, none)
