"""The vessel path of docs/vessel.md on a SYNTHETIC vessel (tools/make_vessel.py: a made-up
recording, static log, candidates and voyage; nothing here is a measurement), and the
pieces it needs: plausible harmonic groups, more than two locked groups on a random part,
the allowance (the inverse of the mission budget) and the budget over time.

Where each expected number comes from is said at its assertion: a hand closed form,
a brute force over the phases, or the budget formula evaluated back at the answer.
The timed full-size path is benchmarks/bench_vessel.py.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from gyrovib.api.noise import allowance, budget, timeline
from gyrovib.core.harmonic_mixtures import locked_mixture_excess
from gyrovib.core.harmonics import group_signal, locked_group
from gyrovib.core.recording import affordable_groups, harmonic_groups
from tests.conftest import invoke

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tools"))
import make_vessel

#: A coefficient sensor with every nonlinear term (made up for the test).
CATALOGUE_TEXT = ("gyrovib: 1\nunits: {rate: deg/s}\nsensors:\n  - id: s\n    range: 500\n"
                  "    coefficients: {k2: 2.0e-4, k3: 1.0e-5, k4: -3.0e-7, k5: 1.0e-8}\n")


def test_groups_are_trimmed_weakest_order_first_to_an_affordable_search() -> None:
    # two groups of orders 1-4 (six unknown phases); a budget of four lets the weakest
    # non-fundamental orders go first (strength: the line's amplitude), and a group left
    # with its fundamental alone is no group (its fundamental goes too)
    groups = [(10.0, [0, 1, 2, 3], [1, 2, 3, 4]), (17.0, [4, 5, 6, 7], [1, 2, 3, 4])]
    strength = [9.0, 8.0, 0.5, 7.0, 9.0, 0.1, 0.2, 0.3]
    kept, released = affordable_groups(groups, strength, lambda dims, n_max: dims <= 4)
    assert kept == [(10.0, [0, 1, 2, 3], [1, 2, 3, 4]), (17.0, [4, 7], [1, 4])]
    assert released == [5, 6]
    kept, released = affordable_groups(groups, strength, lambda dims, n_max: dims <= 2)
    assert kept == [(10.0, [0, 1, 3], [1, 2, 4])] and released == [2, 4, 5, 6, 7]
    # already affordable: unchanged
    assert affordable_groups(groups, strength, lambda d, n: True) == (
        [(f0, list(m), list(o)) for f0, m, o in groups], [])


def _engines(path: Path, seed: int) -> Path:
    """SYNTHETIC: two engines (30 Hz and 47.3 Hz) of nine orders each on white noise, 20 s
    at 1 kHz, written as a CSV recording."""
    rng = np.random.default_rng(seed)
    t = np.arange(20000) / 1000.0
    gz = rng.normal(0.0, 0.5, t.size) + 2.0
    for f0 in (30.0, 47.3):
        for n in range(1, 10):
            gz += (3.0 / n) * np.sin(2 * np.pi * n * f0 * t + rng.uniform(0, 2 * np.pi))
    np.savetxt(path, np.column_stack([t, 0.2 * rng.normal(size=t.size),
                                      0.2 * rng.normal(size=t.size), gz]),
               delimiter=",", header="t,gx,gy,gz", comments="", fmt="%.6f")
    return path


def test_a_profile_fitted_from_many_harmonics_is_one_the_commands_compute(
        tmp_path: Path) -> None:
    # all eighteen lines of two engines as two phase: worst groups would be a search of
    # sixteen unknown phases, refused by analyze as over its budget. profile writes the
    # weakest orders as independent tones instead, says so, and what it wrote is computed.
    path = _engines(tmp_path / "engines.csv", 7)
    fitted = tmp_path / "engines.gyrovib.yaml"
    r = invoke("profile", path, "--rate-columns", "gx,gy,gz", "-o", fitted)
    assert r.exit_code == 0, r.stderr
    assert "are written as independent tones" in r.stderr
    text = fitted.read_text(encoding="utf-8")
    assert text.count("fundamental:") >= 1
    cat = tmp_path / "s.gyrovib.yaml"
    cat.write_text(CATALOGUE_TEXT, encoding="utf-8")
    # analyze searches one objective; bounds and select five, which the trim is sized for
    # (the same cost bound, at a few seconds each: benchmarks/bench_vessel.py times them)
    run = invoke("analyze", cat, fitted, "--format", "json")
    assert run.exit_code == 0, run.stderr


def test_an_envelope_says_which_orders_it_writes_as_independent_tones(
        tmp_path: Path) -> None:
    # the envelope of two such recordings is trimmed by the same rule as one recording's
    # fit: its table and its JSON say which orders left their group, as one fit does
    logs = [_engines(tmp_path / f"engines{k}.csv", seed) for k, seed in enumerate((7, 8))]
    r = invoke("profile", *logs, "--rate-columns", "gx,gy,gz", "--format", "json")
    assert r.exit_code == 0, r.stderr
    said = json.loads(r.stdout)["envelope"]["warnings"]
    head = "envelope of 2 recordings: lines at "  # the warning names what it is about
    assert len(said) == 1 and said[0].startswith(head)
    assert "are written as independent tones" in said[0]
    envelope_part = r.stderr[r.stderr.index("envelope of 2 recordings"):]
    assert "are written as independent tones" in envelope_part
    profile = json.loads(r.stdout)["profile"]
    released = said[0][len(head):said[0].index(" Hz")].split(", ")
    # every line said is written as a tone (the warning rounds to 4 figures), and no
    # other line is: the rest stay in the groups of the two fundamentals
    tones = [float(x.split("frequency: ")[1].split(",")[0])
             for x in profile.splitlines() if "- {frequency:" in x]
    assert sorted(f"{f:.4g}" for f in tones) == sorted(released) and len(released) >= 2
    assert profile.count("fundamental:") == 2


def test_a_slam_mode_and_an_engine_order_are_no_harmonic_series() -> None:
    # the case: a 9.39 Hz hull mode and the 6th order (180 Hz) of a 30 Hz engine
    # were grouped as "orders 1 and 19"
    lines = [9.39, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0]
    groups = harmonic_groups(lines)
    assert [(f0, sorted(orders)) for f0, _, orders in groups] == [(30.0, [1, 2, 3, 4, 5, 6])]
    # 178.4 Hz is within 1 % of 19 × 9.39 = 178.41 Hz, but order 19 alone is no series
    assert harmonic_groups([9.39, 178.4]) == []
    # a gap of more than three orders is no series either; a gap of two is one
    assert harmonic_groups([30.0, 180.0]) == []
    assert [sorted(o) for _, _, o in harmonic_groups([30.0, 60.0, 150.0])] == [[1, 2, 5]]


def _shifts(groups: list, nodes: int = 64) -> np.ndarray:
    """Σ_g x3_g(θ_g) on the full product grid of the groups' phases (midpoint rule)."""
    shift = np.zeros(1)
    theta = 2.0 * math.pi * (np.arange(nodes) + 0.5) / nodes
    for g in groups:
        x3 = group_signal(g.orders, g.phasors[:, 2:3], theta)[0]
        shift = (shift[:, None] + x3[None, :]).ravel()
    return shift


def _brute_excess(omega: float, shift: np.ndarray, sigma: float) -> float:
    """<|Ω + Σ_g x3_g + σZ|> − |Ω| over the product grid, the Gaussian average in closed
    form (folded normal: <|c + σZ|> = c·erf(c/(σ√2)) + σ√(2/π)·exp(−c²/2σ²)): the
    reference, slow but with no table and no fold (the midpoint rule converges
    geometrically on the smooth Gaussian-averaged integrand)."""
    c = omega + shift
    folded = (c * np.vectorize(math.erf)(c / (sigma * math.sqrt(2.0)))
              + sigma * math.sqrt(2.0 / math.pi) * np.exp(-c * c / (2.0 * sigma * sigma)))
    return float(folded.mean() - abs(omega))


@pytest.mark.parametrize("omega", [0.0, 0.4, 1.5, 4.0])
def test_three_locked_groups_on_a_random_part_match_the_brute_force(omega: float) -> None:
    # three groups were refused ("3 phase-locked groups, more than 2"); with a random part
    # the groups beyond the first are folded into its table
    groups = [locked_group([1, 2], [[0, 0, 0.5], [0, 0, 0.3]], [[0, 0, 0], [0, 0, 40]],
                           fundamental=13.0),
              locked_group([1, 3], [[0, 0, 0.4], [0, 0, 0.2]], [[0, 0, 10], [0, 0, 70]],
                           fundamental=23.0),
              locked_group([1, 2], [[0, 0, 0.3], [0, 0, 0.1]], [[0, 0, 0], [0, 0, 200]],
                           fundamental=37.0)]
    shift = _shifts(groups)
    scale = float(np.std(shift))
    sigma = 0.4 * scale  # narrower than the groups' swing: the fold's kernel matters
    w = omega * scale
    got = float(locked_mixture_excess(np.array([w]), groups, [], sigma)[0])
    assert got == pytest.approx(_brute_excess(w, shift, sigma), rel=1e-9)


def test_the_allowance_inverts_the_budget() -> None:
    # N = 0.05 deg/√h, B = 0.3 deg/h, K = 0.4 deg/h/√h, R = 0 over T = 4 h, θ_V = 0.1 deg,
    # k = 2: θ_ARW = 0.1, θ_B = 1.2, θ_RRW = 0.4·8/√3 = 1.8475, θ_R = 0 (by hand)
    figures = {"arw": 0.05, "bias_instability": 0.3, "rrw": 0.4, "bias_repeatability": 0.0}
    b = budget(0.1, figures, 4 * 3600.0, coverage=2.0)
    a = allowance(b, 5.0, 4 * 3600.0)
    # closed form: A = (5 − 0.1)/2 = 2.45; θ_B ≤ √(A² − 0.1² − 1.8475²) = 1.60598; B = θ_B/4
    assert a.bias_instability == pytest.approx(math.sqrt(2.45**2 - 0.01 - (3.2 / math.sqrt(3))
                                                         ** 2) / 4.0, rel=1e-12)
    # and each allowed figure, put back into the budget, meets it exactly
    for name, key in (("arw", "arw"), ("bias_instability", "bias_instability"),
                      ("rrw", "rrw"), ("repeatability", "bias_repeatability")):
        at = budget(0.1, {**figures, key: getattr(a, name)}, 4 * 3600.0, coverage=2.0)
        assert at.total == pytest.approx(5.0, rel=1e-12), name
    assert budget(a.vibration, figures, 4 * 3600.0, coverage=2.0).total == pytest.approx(5.0)
    # a budget the RRW alone exceeds: no B passes, and the RRW is named
    tight = allowance(b, 3.0, 4 * 3600.0)
    assert tight.bias_instability is None and tight.limit("bias_instability") == "rrw"
    assert tight.rrw is not None  # the RRW itself may shrink to fit


def test_the_timeline_is_the_budget_at_each_segment_end() -> None:
    figures = {"arw": 0.1, "bias_instability": 1.5, "rrw": 0.5, "bias_repeatability": None}
    steps = timeline([0.2, -0.05, 0.1], [3600.0, 1800.0, 5400.0], figures, 2.0)
    # at t = 1.5 h (hand): θ_V = 0.15, θ_ARW = 0.1·√1.5, θ_B = 2.25, θ_RRW = 0.5·1.5^1.5/√3
    mid = steps[1]
    assert mid.vibration == pytest.approx(0.15, rel=1e-12)
    sigma = math.sqrt(0.01 * 1.5 + 2.25**2 + 0.25 * 1.5**3 / 3.0)
    assert mid.total == pytest.approx(0.15 + 2.0 * sigma, rel=1e-12)
    assert mid.repeatability is None and mid.lower_bound  # unknown R stays unknown
    assert steps[-1].vibration == pytest.approx(0.25, rel=1e-12)


@pytest.fixture(scope="module")
def vessel(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A small synthetic vessel: 1 min of rough sea at 400 Hz, a 15 min static log, a
    4-segment 4 h voyage (the benchmark runs the full-size scenario)."""
    d = tmp_path_factory.mktemp("vessel")
    make_vessel.write(d, minutes=1.0, fs=400.0, static_hours=0.25, segments=4)
    return d


def test_the_vessel_path_runs_from_the_commands(vessel: Path) -> None:
    fitted = vessel / "rough-sea.gyrovib.yaml"
    out = invoke("profile", vessel / "rough-sea.npz", "--fs", "400", "--rate-columns",
                 "gx,gy,gz", "-o", fitted)
    assert out.exit_code == 0, out.stderr
    text = fitted.read_text(encoding="utf-8")
    # the engine (30 Hz, orders 1-6) and the blade-pass (36 Hz, orders 1-2) are groups;
    # the slam mode (about 9.4 Hz) stays an independent tone
    assert text.count("fundamental:") == 2 and "order: 6" in text and "order: 19" not in text
    assert invoke("validate", fitted).exit_code == 0
    allan = invoke("allan", vessel / "static.npz", "--fs", "10", "--rate-columns", "-,-,gz",
                   "--format", "json")
    assert allan.exit_code == 0, allan.stderr
    # ARW read back within 10 % of the 0.02 deg/√h the generator put in
    arw = json.loads(allan.stdout)
    arw = (arw[0] if isinstance(arw, list) else arw["axes"][0])["arw"]["value"]
    assert arw == pytest.approx(make_vessel.N_ARW, rel=0.1)
    run = invoke("mission", vessel / "candidates.gyrovib.yaml", fitted,
                 vessel / "voyage.gyrovib.yaml", "--mission", "voyage", "--sensor", "usv-fog",
                 "--sensor", "usv-mems-b", "--placement", "x1=+X,x2=+Y,x3=+Z",
                 "--angle-budget", "1deg", "--coverage", "2", "--format", "json",
                 "--plot", vessel / "theta.png")
    assert run.exit_code == 0, run.stderr
    # the answer first, on standard error; the JSON on standard output stays clean
    assert "answer: buy usv-fog" in run.stderr
    rows = {r["sensor"]: r for r in json.loads(run.stdout)["mission"]}
    fog = rows["usv-fog"]
    # the last segment's budget is the row's (a coefficient sensor: the staircase ends
    # at θ_V)
    assert fog["segments"][-1]["budget"]["total"] == pytest.approx(fog["budget"]["total"],
                                                                   rel=1e-12)
    assert fog["segments"][-1]["end"] == pytest.approx(4 * 3600.0)
    # the MEMS fails on its noise alone: no B passes at k = 2, the RRW names the reason
    mems = rows["usv-mems-b"]["budget"]["allowed"]
    assert mems["bias_instability"] is None and mems["limited_by"]["bias_instability"] in (
        "rrw", "arw")
    assert (vessel / "theta.png").read_bytes()[:4] == b"\x89PNG"


def test_the_number_of_sensors_never_refuses_a_phase_search() -> None:
    # the refusal: "3,000 allowed … for 4 sensors"; each sensor's search is the
    # same size, so a profile one sensor may search, a thousand may too (one by one)
    from gyrovib.api.study.prepare import cost_problems
    from gyrovib.catalog.loader import merge, parse_catalog

    orders = "".join(f"      - {{order: {n}, amplitude: [0, 0, 0.1], phase: worst}}\n"
                     for n in range(1, 7))
    text = ("gyrovib: 1\nunits: {rate: deg/s}\nprofiles:\n  - id: p\n    rate: [0, 0, 0.5]\n"
            "    harmonics:\n      fundamental: 30\n      orders:\n" + orders)
    entries = merge([parse_catalog(text, "<p>")]).profiles
    assert cost_problems(entries, 1, 1, False) == {}
    assert cost_problems(entries, 1, 1000, False) == {}


def test_the_report_states_each_total_verdict_and_theta_of_t(tmp_path: Path) -> None:
    # a small coefficient catalogue (no phase search): the report's mission section opens
    # with the answer, states each total and verdict in words, draws θ(t) with its cone,
    # lists the noise figures with their qualifiers ('?' where not given), and takes
    # --placement like mission
    from tests.test_noise_budget import CATALOGUE

    path = tmp_path / "c.yaml"
    path.write_text(CATALOGUE, encoding="utf-8")
    out = tmp_path / "r.html"
    run = invoke("report", path, "--budget", "1", "--mission", "two-hours", "--angle-budget",
                 "3deg", "--coverage", "2", "--placement", "triad", "-o", out)
    assert run.exit_code == 0, run.stderr
    html = out.read_text(encoding="utf-8")
    assert "answer:" in html
    assert "passes" in html or "FAILS" in html or "UNVERIFIED" in html
    assert "θ(t)" in html and "<polygon" in html  # the cone
    assert "0.5 °/h typ" in html  # the unit and qualifier as the catalogue writes them
    assert "<td>silent</td><td>?</td>" in html  # not given: unknown, never 0
    # the triad placement was applied: the tone is on vehicle Z, the worst axis
    assert "x3 on Z" in html
    # every segment end is a point with its θ values as a tooltip
    assert html.count("segment 2 ends at 2 h") >= 1


def test_the_answer_names_the_one_figure_that_would_change_a_failure(tmp_path: Path) -> None:
    from tests.test_noise_budget import CATALOGUE

    path = tmp_path / "c.yaml"
    path.write_text(CATALOGUE, encoding="utf-8")
    run = invoke("mission", path, "--sensor", "full", "--angle-budget", "4deg", "--coverage",
                 "2", "--format", "csv")
    # by hand, over T = 2 h at k = 2: θ_ARW = 0.15·√2, θ_B = 0.5·2, θ_RRW = 0.02·2^1.5/√3,
    # θ_R = 1·2; A = (4 − |θ_V|)/2; R may reach √(A² − θ_ARW² − θ_B² − θ_RRW²)/2 h, and no
    # B passes (θ_R alone is 2 deg of the 1.97 deg allowance)
    import csv

    theta_v = float(next(csv.DictReader(run.stdout.splitlines()))["angle"])
    room = (4.0 - abs(theta_v)) / 2.0
    r_max = math.sqrt(room**2 - 0.045 - 1.0 - (0.04 * math.sqrt(2) / math.sqrt(3)) ** 2) / 2.0
    assert run.exit_code == 1
    assert f"it would pass with R ≤ {r_max:.4g} deg/h (it has 1)" in run.stderr
    assert run.stdout.startswith("sensor,")  # the data stay clean
