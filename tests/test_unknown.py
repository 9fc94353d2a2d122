"""Unknown is not zero: a datasheet figure that is not published leaves a verdict open.

README, "Reading the output": a spec-form part that passes on its
published figures, but whose verdict an unpublished one can change (the VRE
under linear vibration; m31, m32 under cross-axis vibration correlated with
x3, docs/model.md sections 8 and 11), is ``unverified``: not passing, not ranked,
with the figures to ask its vendor for. ``--assume-unknown zero`` restores
the reading of old and says so.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

import gyrovib
from tests.conftest import invoke

BUDGET = 0.01  # deg/s

# Two datasheet parts (one without a VRE, one with) and a coefficient part under
# 'shaker': linear random vibration only, σ = 1 g on each axis, Σ⟨a_j²⟩ = 3 g²
# (docs/model.md section 8), no angular vibration (C31 = C32 = 0, nothing for the NL
# envelope either: the worst case on the published figures is the VRE's alone);
# and 'tone': one angular tone a = (1, 0, 2) deg/s in phase, C31 = ½·1·2 = 1
# (deg/s)², C32 = 0 (eq. (9) with cos 0 = 1).
CATALOGUE = """\
gyrovib: 1
units: {rate: deg/s}
sensors:
  - id: no-vre
    specs:
      range: 100
      nonlinearity: {value: 0.001, unit: "%FS", fit: least-squares, measure: max}
  - id: with-vre
    specs:
      range: 100
      nonlinearity: {value: 0.001, unit: "%FS", fit: least-squares, measure: max}
      vre: 1.0e-3
  - id: coefficients
    coefficients: {k2: 1.0e-6}
    vre: 0.0      # stated: a known zero, unlike a g² sensitivity not given
profiles:
  - id: shaker
    rate: [0, 0, 0]
    acceleration:
      random: {rms: [1.0, 1.0, 1.0]}
  - id: tone
    rate: [0, 0, 0]
    harmonic:
      - {frequency: 100, amplitude: [1.0, 0.0, 2.0]}
"""


@pytest.fixture
def catalog(tmp_path: Path) -> str:
    path = tmp_path / "unknown.yaml"
    path.write_text(CATALOGUE, encoding="utf-8")
    return str(path)


def select_json(catalog: str, *args: str) -> tuple[int, dict]:
    done = invoke("select", catalog, "--budget", str(BUDGET), "--format", "json", *args)
    return done.exit_code, json.loads(done.stdout)


def test_a_part_without_a_vre_under_linear_vibration_is_unverified(catalog: str) -> None:
    code, doc = select_json(catalog, "--profile", "shaker", "--require", "all")
    assert code == 1  # unverified is not passing: --require all is not met
    assert doc["assume_unknown"] == "none"
    parts = {s["sensor"]: s for s in doc["sensors"]}
    cell = parts["no-vre"]["profiles"][0]
    assert (cell["pass"], cell["status"], cell["unknown"]) == (False, "unverified", ["vre"])
    assert cell["reason"].startswith("unverified: passes on its published figures, but VRE "
                                     "not published")
    # the VRE check neither passes nor fails: its value is not known (the cell is
    # unverified, and its own "pass" false)
    assert cell["checks"]["vre"] == {"value": None, "bound": cell["checks"]["vre"]["bound"],
                                     "pass": None}
    assert (parts["no-vre"]["pass"], parts["no-vre"]["status"]) == (False, "unverified")
    # the vendor question: the VRE that still passes. The worst case on the published
    # figures is 0 here (no angular vibration), so VRE_max = Δ*/Σ⟨a_j²⟩ = 0.01/3
    # deg/s/g² (docs/model.md section 11, all of Δ* to the one part the profile excites).
    assert parts["no-vre"]["questions"] == [
        f"VRE (vibration rectification, deg/s/g²): at most {BUDGET / 3:.4g} passes under "
        "shaker"]
    # a published VRE of 1e-3 deg/s/g² gives 3e-3 deg/s ≤ 0.01: a verified pass
    other = parts["with-vre"]["profiles"][0]
    assert (other["status"], other["unknown"], other["pass"]) == ("pass", [], True)
    # a coefficient-form part that states its g² sensitivity (here 0): nothing unknown
    assert parts["coefficients"]["status"] == "pass"


# Coefficient-form sensors: one without a g² figure (neither g2_sensitivity nor vre),
# one with vre: 1e-4 deg/s/g², and one that fails on its other figures; under 'shaker'
# (Σ⟨a_j²⟩ = 3 g², as above) and 'calm' (no linear vibration: the g² term cannot act).
COEFFICIENTS = """\
gyrovib: 1
units: {rate: deg/s}
sensors:
  - id: no-g2
    coefficients: {k2: 1.0e-6}
  - id: with-g2
    coefficients: {k2: 1.0e-6}
    vre: 1.0e-4
  - id: failing
    coefficients: {A1: 0.5}
profiles:
  - id: shaker
    rate: [0, 0, 0]
    harmonic:
      - {frequency: 100, amplitude: [0.0, 0.0, 1.0]}
    acceleration:
      random: {rms: [1.0, 1.0, 1.0]}
  - id: calm
    rate: [0, 0, 0]
    harmonic:
      - {frequency: 100, amplitude: [0.0, 0.0, 1.0]}
"""


@pytest.fixture
def coefficient_catalog(tmp_path: Path) -> str:
    path = tmp_path / "coefficients.yaml"
    path.write_text(COEFFICIENTS, encoding="utf-8")
    return str(path)


def test_a_coefficient_sensor_without_a_g2_figure_is_unverified_under_linear_vibration(
        coefficient_catalog: str) -> None:
    result = gyrovib.select(coefficient_catalog, budget=BUDGET, criterion="rms")
    no_g2, with_g2, failing = (result.sensors.index(s) for s in ("no-g2", "with-g2", "failing"))
    shaker, calm = result.profiles.index("shaker"), result.profiles.index("calm")
    # not given is unknown, not zero: under linear vibration the verdict is open
    assert result.unknown[(no_g2, shaker)] == ("vre",)
    assert result.status(no_g2, shaker) == "unverified" and not result.passed[no_g2, shaker]
    assert result.sensor_status(no_g2) == "unverified"
    # without linear vibration the g² term cannot act: a plain pass there
    assert (no_g2, calm) not in result.unknown and result.status(no_g2, calm) == "pass"
    # a stated g² sensitivity is known: vre·Σ⟨a_j²⟩ = 1e-4·3 = 3e-4 deg/s ≤ Δ*: a pass
    assert (with_g2, shaker) not in result.unknown and result.sensor_status(with_g2) == "pass"
    # one that fails on its other figures fails (|A1| = 0.5: Δ_V(RMS) far above Δ*)
    assert result.status(failing, shaker) == "fail" and failing not in result.questions
    # the question: Δ0(6) = vre·Σ⟨a_j²⟩ is one term of eq. (16), so under rms
    # vre_max = √(Δ*² − Δ_V(RMS)²)/Σ⟨a_j²⟩ with Δ_V(RMS) that of the other terms
    rms = float(result.rms[no_g2, shaker])
    left = (BUDGET**2 - rms**2) ** 0.5 / 3.0
    assert result.questions[no_g2] == (
        f"g² sensitivity (G11 = G22 = G33, `vre`, deg/s/g²): at most {left:.4g} passes "
        "under shaker",)
    # every format says so: JSON reason and checks, the table, junit
    done = invoke("select", coefficient_catalog, "--budget", str(BUDGET), "--criterion", "rms",
                  "--format", "json")
    cell = next(s for s in json.loads(done.stdout)["sensors"]
                if s["sensor"] == "no-g2")["profiles"][shaker]
    assert (cell["status"], cell["unknown"], cell["pass"]) == ("unverified", ["vre"], False)
    assert "g² sensitivity not given" in cell["reason"]
    assert cell["checks"]["vre"]["value"] is None and cell["checks"]["vre"]["pass"] is None
    table = invoke("select", coefficient_catalog, "--budget", str(BUDGET),
                   env={"COLUMNS": "200"}).stdout
    row = next(line for line in table.splitlines() if "│ no-g2" in line)
    assert "? g² unknown" in row and "UNVERIFIED" in row
    junit = invoke("select", coefficient_catalog, "--budget", str(BUDGET), "--format",
                   "junit").stdout
    case = junit.split('classname="no-g2" name="shaker"')[1].split("</testcase>")[0]
    assert 'type="Unverified"' in case and "g² sensitivity not given" in case
    # --assume-unknown zero: taken as 0, a pass, and the output says so
    zero = gyrovib.select(coefficient_catalog, budget=BUDGET, criterion="rms",
                          assume_unknown="zero")
    assert zero.status(no_g2, shaker) == "pass" and zero.unknown[(no_g2, shaker)] == ("vre",)
    flat = " ".join(invoke("select", coefficient_catalog, "--budget", str(BUDGET),
                           "--assume-unknown", "zero", env={"COLUMNS": "200"}).stdout.split())
    assert "unpublished figures taken as 0 -- failing: g²; no-g2: g²;" in flat


def test_assume_unknown_zero_passes_it_and_says_so(catalog: str) -> None:
    code, doc = select_json(catalog, "--profile", "shaker", "--require", "all",
                            "--assume-unknown", "zero")
    assert code == 0 and doc["assume_unknown"] == "zero"
    cell = {s["sensor"]: s for s in doc["sensors"]}["no-vre"]["profiles"][0]
    # still listed as unknown, but taken as 0: the reading of old (margin ∞: no error)
    assert (cell["pass"], cell["status"], cell["unknown"]) == (True, "pass", ["vre"])
    assert cell["reason"] is None and cell["margin"] is None
    table = invoke("select", catalog, "--budget", str(BUDGET), "--profile", "shaker",
                   "--assume-unknown", "zero", env={"COLUMNS": "200"}).stdout
    assert "Assumed (--assume-unknown zero): unpublished figures taken as 0 -- no-vre: VRE" in (
        " ".join(table.split()))
    assert "✓ ∞*" in table  # the cell that passes only under the assumption is marked
    junit = invoke("select", catalog, "--budget", str(BUDGET), "--profile", "shaker",
                   "--assume-unknown", "zero", "--format", "junit").stdout
    assert "<failure" not in junit and "(assumed VRE = 0: --assume-unknown zero)" in junit


def test_table_junit_csv_and_github_show_it(catalog: str) -> None:
    args = ("select", catalog, "--budget", str(BUDGET), "--profile", "shaker")
    table = invoke(*args, env={"COLUMNS": "200"}).stdout
    row = next(line for line in table.splitlines() if "│ no-vre" in line)
    assert "? VRE unknown" in row and "UNVERIFIED" in row and "✓" not in row
    assert "Unverified sensors: questions for the vendor" in table
    assert "1 of 3 sensor(s) pass" not in table and "2 of 3 sensor(s) pass, 1 unverified" in table
    junit = invoke(*args, "--format", "junit").stdout
    case = junit.split('classname="no-vre"')[1].split("</testcase>")[0]
    assert 'type="Unverified"' in case and "VRE not published" in case
    csv = invoke(*args, "--format", "csv").stdout.splitlines()
    head = csv[0].split(",")
    row = dict(zip(head, next(r for r in csv if r.startswith("no-vre")).split(","),
                   strict=False))
    assert (row["passed"], row["status"], row["unknown"]) == ("False", "unverified", "vre")
    github = invoke(*args, "--format", "github").stdout
    assert "no-vre is unverified" in github and "Ask the vendor: VRE" in github


def test_the_vre_check_of_an_unknown_figure_is_neither_passed_nor_failed(
        catalog: str, coefficient_catalog: str) -> None:
    # A VRE the datasheet does not publish (no-vre), or a g² sensitivity the catalogue
    # does not give (no-g2), under 'shaker', whose linear vibration sets a VRE bound:
    # the check has no value, so no verdict either (null, empty, None), while the cell
    # itself is unverified and its own "pass" false (docs/output.md, select's checks).
    for path, sensor in ((catalog, "no-vre"), (coefficient_catalog, "no-g2")):
        _, doc = select_json(path, "--profile", "shaker")
        cell = {s["sensor"]: s for s in doc["sensors"]}[sensor]["profiles"][0]
        assert cell["checks"]["vre"]["value"] is None
        assert cell["checks"]["vre"]["bound"] > 0  # the bound applies here
        assert cell["checks"]["vre"]["pass"] is None
        assert (cell["pass"], cell["status"]) == (False, "unverified")
        # the reason names the unknown figure, and no comparison of it ("nan exceeds")
        assert cell["reason"].startswith("unverified: passes on its published figures")
        assert "nan" not in cell["reason"] and "effective VRE" not in cell["reason"]
        csv = invoke("select", path, "--budget", str(BUDGET), "--profile", "shaker",
                     "--format", "csv").stdout.splitlines()
        row = dict(zip(csv[0].split(","), next(r for r in csv if r.startswith(sensor + ","))
                       .split(","), strict=False))
        assert (row["value_vre"], row["pass_vre"], row["passed"]) == ("", "", "False")
        result = gyrovib.select(path, budget=BUDGET, profiles="shaker")
        i = result.sensors.index(sensor)
        assert result.vre_check(i, 0) is None
        assert result.to_frame()["pass_vre"].iloc[i] is None
        # --assume-unknown zero takes the figure as 0 (and says so): 0 ≤ bound, a pass
        zero = gyrovib.select(path, budget=BUDGET, profiles="shaker", assume_unknown="zero")
        assert zero.vre_check(i, 0) is True and zero.to_frame()["pass_vre"].iloc[i]
    # a published VRE keeps its verdict: 1e-3 deg/s/g² passes under 'shaker' (as in
    # test_a_part_without_a_vre_under_linear_vibration_is_unverified)
    with_vre = gyrovib.select(catalog, budget=BUDGET, profiles="shaker")
    assert with_vre.vre_check(with_vre.sensors.index("with-vre"), 0) is True
    # without linear vibration there is no VRE bound: an unknown VRE cannot matter (pass)
    calm = gyrovib.select(coefficient_catalog, budget=BUDGET, profiles="calm")
    assert calm.vre_check(calm.sensors.index("no-g2"), 0) is True


def test_cross_axis_m31_is_unknown_where_c31_is_not_zero(catalog: str) -> None:
    result = gyrovib.select(catalog, budget=BUDGET, profiles="tone", criterion="worst")
    i = result.sensors.index("with-vre")
    # C31 = 1 (deg/s)² ≠ 0, C32 = 0: only m31 can matter (and no linear vibration: the
    # VRE cannot)
    assert result.unknown[(i, 0)] == ("m31",)
    assert result.status(i, 0) == "unverified" and not result.sensor_pass[i]
    # |m31|·C31 may take what the worst case leaves: (Δ* − worst |Δ_V|)/C31, (deg/s)^-1
    left = BUDGET - float(result.total[i, 0])
    assert 0 < left < BUDGET
    assert result.questions[i] == (
        f"m31 (multiplicative cross-axis coefficient, (deg/s)^-1): |m31| at most "
        f"{left / 1.0:.4g} passes under tone (with m32 = 0)",)
    # not ranked on its margin: the verified sensors come first
    assert result.ranking[-2:] == tuple(sorted(
        (result.sensors.index("no-vre"), i), key=lambda k: (-result.worst_margin[k], k)))
    zero = gyrovib.select(catalog, budget=BUDGET, profiles="tone", criterion="worst",
                          assume_unknown="zero")
    assert zero.status(i, 0) == "pass" and zero.unknown[(i, 0)] == ("m31",)


def test_a_part_that_fails_on_its_published_figures_fails(catalog: str) -> None:
    # Δ* below the NL worst case under 'tone': it fails whatever m31 is
    worst = gyrovib.select(catalog, budget=BUDGET, profiles="tone", criterion="worst")
    i = worst.sensors.index("no-vre")
    budget = 0.5 * float(worst.total[i, 0])
    result = gyrovib.select(catalog, budget=budget, profiles="tone", criterion="worst")
    assert result.status(i, 0) == "fail" and result.sensor_status(i) == "fail"
    assert result.limits[i].name == "worst" and i not in result.questions


def test_report_colours_it_apart_and_asks_the_vendor(catalog: str, tmp_path: Path) -> None:
    out = tmp_path / "r.html"
    invoke("report", catalog, "--budget", str(BUDGET), "--profile", "shaker", "-o", str(out))
    html = out.read_text(encoding="utf-8")
    row = html.split("<b>no-vre</b>")[1].split("</tr>")[0]
    assert 'class="unverified"' in row and "? unverified" in row and "VRE unknown" in row
    assert "✓" not in row and "∞" not in row
    assert "questions for the vendor</h2>" in html and "VRE (vibration rectification" in html


def test_analyze_says_the_vre_is_left_out(catalog: str) -> None:
    result = gyrovib.analyze(catalog, profiles="shaker")
    i = result.sensors.index("no-vre")
    assert any("publishes no VRE" in w for w in result.warnings[(i, 0)])
    assert not any("publishes no VRE" in w
                   for w in result.warnings.get((result.sensors.index("with-vre"), 0), ()))
    # the datasheet's worst case and its RMS bound hold the g² term: unknown without a VRE
    # (JSON null), where the published 1e-3 deg/s/g² gives |v|·Σ⟨a_j²⟩ = 3e-3 deg/s (the
    # NL envelope adds nothing without angular vibration)
    entries = {r["sensor"]: r for r in json.loads(invoke(
        "analyze", catalog, "--profile", "shaker", "--format", "json").stdout)["results"]}
    assert [entries["no-vre"][k] for k in ("additive_terms", "total", "rms", "envelope")] == [
        {**entries["no-vre"]["additive_terms"], "g2": None}, None, None,
        {**entries["no-vre"]["envelope"], "rms_bound": None}]
    assert entries["with-vre"]["total"] == pytest.approx(3e-3, rel=1e-9)



def test_analyze_says_a_g2_figure_not_given_is_left_out(coefficient_catalog: str) -> None:
    # the coefficient sensor with neither g2_sensitivity nor vre: its g² term under
    # 'shaker' is unknown, and analyze says so; one that states its figure, or a profile
    # without linear vibration, gets no note
    result = gyrovib.analyze(coefficient_catalog)
    shaker, calm = result.profiles.index("shaker"), result.profiles.index("calm")
    no_g2, with_g2 = result.sensors.index("no-g2"), result.sensors.index("with-g2")
    assert any("gives no g² sensitivity" in w for w in result.warnings[(no_g2, shaker)])
    for cell in ((with_g2, shaker), (no_g2, calm)):
        assert not any("g² sensitivity" in w for w in result.warnings.get(cell, ()))


#: The numbers of an analyze row that hold the g² term Δ0(6) (eq. 13, 15, 16).
G2_SUMS = ("additive", "total", "rms")


def test_analyze_writes_an_unknown_g2_term_and_its_sums_unknown_in_every_format(
        coefficient_catalog: str) -> None:
    # no-g2 under 'shaker' (linear vibration): Δ0(6), and Δ_VA, Δ_V, Δ_V(RMS) that sum it,
    # are unknown: null in JSON, empty in CSV, NaN in the frame and the result, '?' in the
    # tables; never the 0 (or the sum without it) of a figure not given. Its other terms
    # are known: k2·⟨x3²⟩-type terms equal with-g2's (the same k2 = 1e-6 and profile).
    # with-g2 (vre 1e-4 deg/s/g²: Δ0(6) = 1e-4·Σ⟨a_j²⟩ = 1e-4·3 = 3e-4 deg/s) and 'calm'
    # (no linear vibration: Δ0(6) = 0, a known zero) keep their numbers.
    result = gyrovib.analyze(coefficient_catalog)
    shaker, calm = result.profiles.index("shaker"), result.profiles.index("calm")
    no_g2, with_g2 = result.sensors.index("no-g2"), result.sensors.index("with-g2")
    e = result.error
    assert math.isnan(e.extra_terms[no_g2, shaker, 0])
    assert all(math.isnan(getattr(e, name)[no_g2, shaker]) for name in G2_SUMS)
    assert e.additive_terms[no_g2, shaker].tolist() == e.additive_terms[with_g2, shaker].tolist()
    assert e.extra_terms[with_g2, shaker, 0] == pytest.approx(3e-4, rel=1e-12)
    assert e.extra_terms[no_g2, calm, 0] == 0.0
    assert e.total[no_g2, calm] == e.total[with_g2, calm]  # g² cannot act there: known
    done = invoke("analyze", coefficient_catalog, "--format", "json")
    rows = {(r["sensor"], r["profile"]): r for r in json.loads(done.stdout)["results"]}
    unknown = rows[("no-g2", "shaker")]
    assert unknown["additive_terms"]["g2"] is None
    assert [unknown[k] for k in G2_SUMS] == [None, None, None]
    assert unknown["additive_terms"]["k2"] == rows[("with-g2", "shaker")]["additive_terms"]["k2"]
    assert rows[("with-g2", "shaker")]["additive_terms"]["g2"] == pytest.approx(3e-4, rel=1e-12)
    assert rows[("no-g2", "calm")]["additive_terms"]["g2"] == 0.0
    assert all(isinstance(rows[("no-g2", "calm")][k], float) for k in G2_SUMS)
    csv = invoke("analyze", coefficient_catalog, "--format", "csv").stdout.splitlines()
    head = csv[0].split(",")
    line = dict(zip(head, next(r for r in csv if r.startswith("no-g2,shaker,")).split(","),
                    strict=False))
    assert [line[k] for k in ("additive_g2", *G2_SUMS)] == ["", "", "", ""]
    assert line["additive_k2"] != ""
    frame = result.to_frame()
    at = frame[(frame["sensor"] == "no-g2") & (frame["profile"] == "shaker")].iloc[0]
    assert all(math.isnan(at[k]) for k in ("additive_g2", *G2_SUMS))
    # the tables: every such cell '?', and the matrix's cell '?' (no '≥' lower bound: the
    # g² term has a sign, so the sum without it bounds nothing)
    detail = invoke("analyze", coefficient_catalog, "--profile", "shaker",
                    "--format", "markdown").stdout
    lines = detail.splitlines()
    header = [c.strip() for c in lines[2].split("|")]
    cells = {line.split("|")[1].split()[0]: [c.strip() for c in line.split("|")]
             for line in lines if line.startswith(("| no-g2", "| with-g2"))}
    for label in ("Δ0 g²", "Δ_VA", "Δ_V", "Δ_V(RMS)"):
        assert cells["no-g2"][header.index(label)] == "?", label
        assert cells["with-g2"][header.index(label)] not in ("?", "0"), label
    table = invoke("analyze", coefficient_catalog, "--matrix", env={"COLUMNS": "200"}).stdout
    row = next(line for line in table.splitlines() if line.startswith("│ shaker"))
    assert [c.strip().split()[0] for c in row.split("│")[2:4]] == ["?", "0.0003"]
    assert "≥" not in table and "not given" in table
    text = invoke("analyze", coefficient_catalog, "--profile", "shaker",
                  env={"COLUMNS": "200"}).stdout
    row = next(line for line in text.splitlines() if line.startswith("│ no-g2"))
    # g², Δ_VA, Δ_VM (0 at Ω_K3 = 0, known), Δ_V, Δ_V(RMS)
    assert [c.strip() for c in row.split("│")[-6:-1]] == ["?", "?", "0", "?", "?"]
    # the report's share of each term in Δ_V(RMS)² (eq. 16): unknown for the rows of
    # no-g2 and 'failing' (no g² figure either) under shaker, and those only
    report = invoke("report", coefficient_catalog, "--budget", str(BUDGET), "-o", "-").stdout
    assert report.count('class="lg">? unknown</text>') == 2


def test_sweep_writes_an_unknown_g2_cell_as_analyze_does(coefficient_catalog: str) -> None:
    # a value of sweep at a rate equals analyze --rate at that rate (sweep --help): for
    # no-g2 under 'shaker' both are unknown at every rate (null, '?'), with a note on
    # standard error naming the pair; with-g2 and no-g2 under 'calm' keep their numbers,
    # equal to analyze's (the same closed form)
    done = invoke("sweep", coefficient_catalog, "--rate-range", "0:4:3", "--format", "json")
    assert done.exit_code == 0, done.stderr
    series = {(r["sensor"], r["profile"]): r for r in json.loads(done.stdout)["series"]}
    unknown = series[("no-g2", "shaker")]["exact"]
    assert unknown["total"] == [None] * 3 and unknown["rms"] == [None] * 3
    assert "unknown ('?', null) for no-g2 under shaker; failing under shaker" in done.stderr
    for rate, k in ((0.0, 0), (2.0, 1), (4.0, 2)):
        rows = {(r["sensor"], r["profile"]): r for r in json.loads(invoke(
            "analyze", coefficient_catalog, "--rate", str(rate), "--format", "json"
        ).stdout)["results"]}
        for cell in (("with-g2", "shaker"), ("no-g2", "calm")):
            assert series[cell]["exact"]["total"][k] == pytest.approx(rows[cell]["total"],
                                                                      rel=1e-12, abs=0)
        assert rows[("no-g2", "shaker")]["total"] is None
    table = invoke("sweep", coefficient_catalog, "--rate-range", "0:4:3", "--sensor", "no-g2",
                   "--profile", "shaker", env={"COLUMNS": "120"}).stdout
    assert table.count("?") >= 6


def test_the_uncertainty_of_an_unknown_total_is_unknown(tmp_path: Path) -> None:
    # no-g2 with a standard uncertainty on k2 (σ = 1e-7): under 'shaker' its Δ_V is
    # unknown (no g² figure, linear vibration), and so is Δ_V's uncertainty (left out of the JSON,
    # NaN in the result), never the spread of the known terms alone; under 'calm' both
    # are numbers, and with-g2 keeps its own under both profiles.
    path = tmp_path / "spread.yaml"
    path.write_text(COEFFICIENTS.replace(
        "  - id: no-g2\n    coefficients: {k2: 1.0e-6}\n",
        "  - id: no-g2\n    coefficients: {k2: 1.0e-6}\n"
        "    uncertainty:\n      sigma: {k2: 1.0e-7}\n").replace(
        "    vre: 1.0e-4\n",
        "    vre: 1.0e-4\n    uncertainty:\n      sigma: {k2: 1.0e-7}\n"), encoding="utf-8")
    result = gyrovib.analyze(str(path))
    assert result.uncertainty is not None
    shaker, calm = result.profiles.index("shaker"), result.profiles.index("calm")
    no_g2, with_g2 = result.sensors.index("no-g2"), result.sensors.index("with-g2")
    assert math.isnan(result.error.total[no_g2, shaker])
    assert math.isnan(result.uncertainty[no_g2, shaker])
    assert result.uncertainty[no_g2, calm] > 0
    assert result.uncertainty[with_g2, shaker] > 0 and result.uncertainty[with_g2, calm] > 0
    rows = {(r["sensor"], r["profile"]): r for r in json.loads(
        invoke("analyze", str(path), "--format", "json").stdout)["results"]}
    assert rows[("no-g2", "shaker")]["total"] is None
    assert "uncertainty" not in rows[("no-g2", "shaker")]  # left out, as docs/output.md says
    assert rows[("no-g2", "calm")]["uncertainty"]["total"] > 0


# ---------------------------------------------------------------- missions
# The same parts over missions (docs/model.md section 12): 'trip' flies a quiet tone
# along x3 only (a = (0, 0, 2) deg/s: C31 = C32 = 0, no linear vibration) for 100 s,
# then 'shaker' for 10 s; 'wobble' flies 'tone' (C31 = 1 (deg/s)²) for 60 s. ('quiet'
# continues CATALOGUE's list of profiles.)
MISSIONS = """\
  - id: quiet
    rate: [0, 0, 0]
    harmonic:
      - {frequency: 100, amplitude: [0.0, 0.0, 2.0]}
missions:
  - id: trip
    segments:
      - {profile: quiet, duration: 100}
      - {profile: shaker, duration: 10}
  - id: wobble
    segments:
      - {profile: tone, duration: 60}
"""


@pytest.fixture
def flights(tmp_path: Path) -> str:
    path = tmp_path / "flights.yaml"
    path.write_text(CATALOGUE + MISSIONS, encoding="utf-8")
    return str(path)


def mission_json(catalog: str, *args: str) -> tuple[int, dict]:
    done = invoke("mission", catalog, "--budget", str(BUDGET), "--format", "json", *args)
    return done.exit_code, json.loads(done.stdout)


def test_a_mission_with_linear_vibration_leaves_a_part_without_vre_unverified(
        flights: str) -> None:
    code, doc = mission_json(flights, "--mission", "trip", "--require", "all")
    assert code == 1  # unverified is not passing
    assert doc["assume_unknown"] == "none"
    rows = {r["sensor"]: r for r in doc["mission"]}
    cell = rows["no-vre"]
    assert (cell["pass"], cell["status"], cell["unknown"]) == (False, "unverified", ["vre"])
    assert cell["reason"].startswith("unverified: passes on its published figures, but VRE "
                                     "not published")
    for part in ("with-vre", "coefficients"):
        assert (rows[part]["pass"], rows[part]["status"], rows[part]["unknown"]) == \
            (True, "pass", [])
    sensors = {s["sensor"]: s for s in doc["sensors"]}
    assert (sensors["no-vre"]["pass"], sensors["no-vre"]["status"]) == (False, "unverified")
    # by hand: the two parts differ only by the published VRE's term, 1e-3 deg/s/g² ×
    # Σ⟨a_j²⟩ = 3 g² during the 10 s of 110 (the quiet segment has no acceleration)
    assert rows["with-vre"]["mean"] - rows["no-vre"]["mean"] == pytest.approx(
        1.0e-3 * 3.0 * 10.0 / 110.0, rel=1e-9)


def test_a_mission_leaves_a_coefficient_sensor_without_g2_unverified(tmp_path: Path) -> None:
    # COEFFICIENTS' parts over a mission: 100 s 'calm' (no linear vibration), then 10 s
    # 'shaker' (σ = 1 g on each axis). 'no-g2' gives no g² figure: unknown there, as
    # select reads it (test above); 'with-g2' states one; a mission that never shakes
    # leaves nothing unknown
    path = tmp_path / "coefficient-flights.yaml"
    path.write_text(COEFFICIENTS + """missions:
  - id: shaken
    segments:
      - {profile: calm, duration: 100}
      - {profile: shaker, duration: 10}
  - id: still
    segments:
      - {profile: calm, duration: 60}
""", encoding="utf-8")
    _, doc = mission_json(str(path), "--budget", "1")
    rows = {(r["sensor"], r["mission"]): r for r in doc["mission"]}
    cell = rows[("no-g2", "shaken")]
    assert (cell["pass"], cell["status"], cell["unknown"]) == (False, "unverified", ["vre"])
    assert "g² sensitivity not given" in cell["reason"]
    assert rows[("with-g2", "shaken")]["status"] == "pass"
    assert rows[("no-g2", "still")]["status"] == "pass"
    zero = invoke("mission", str(path), "--budget", "1", "--format", "json",
                  "--assume-unknown", "zero")
    assert {(r["sensor"], r["mission"]): r["status"] for r in json.loads(zero.stdout)[
        "mission"]}[("no-g2", "shaken")] == "pass"


def test_cross_axis_vibration_in_a_segment_leaves_m31_unknown(flights: str) -> None:
    _, doc = mission_json(flights, "--mission", "wobble")
    rows = {r["sensor"]: r for r in doc["mission"]}
    for part in ("no-vre", "with-vre"):  # no datasheet gives m31
        assert (rows[part]["status"], rows[part]["unknown"]) == ("unverified", ["m31"])
        assert "m31 not published" in rows[part]["reason"]
    assert rows["coefficients"]["status"] == "pass"


def test_mission_assume_unknown_zero_restores_and_says_so(flights: str) -> None:
    code, doc = mission_json(flights, "--mission", "trip", "--require", "all",
                             "--assume-unknown", "zero")
    assert code == 0 and doc["assume_unknown"] == "zero"
    rows = {r["sensor"]: r for r in doc["mission"]}
    # still listed as unknown, but taken as 0: it passes on its published figures
    assert (rows["no-vre"]["pass"], rows["no-vre"]["status"], rows["no-vre"]["unknown"]) \
        == (True, "pass", ["vre"])
    table = invoke("mission", flights, "--mission", "trip", "--budget", str(BUDGET),
                   "--assume-unknown", "zero")
    assert "Assumed (--assume-unknown zero): unpublished figures taken as 0 -- no-vre: VRE" \
        in " ".join(table.stdout.split())


def test_unverified_mission_rows_in_every_format(flights: str) -> None:
    table = invoke("mission", flights, "--mission", "trip", "--budget", str(BUDGET))
    assert "UNVERIFIED" in table.stdout and "1 unverified" in table.stdout
    flat = " ".join(table.stdout.split())
    assert "no-vre: unverified: passes on its published figures, but VRE not published" in flat
    markdown = invoke("mission", flights, "--mission", "trip", "--budget", str(BUDGET),
                      "--format", "markdown").stdout
    assert "| UNVERIFIED |" in markdown
    csv = invoke("mission", flights, "--mission", "trip", "--budget", str(BUDGET),
                 "--format", "csv").stdout.splitlines()
    # the verdict columns, then the angle budget's (docs/model.md section 15)
    assert ",passed,status,unknown,theta_arw," in csv[0]
    (line,) = [ln for ln in csv if ln.startswith("no-vre,")]
    assert ",false,unverified,vre," in line
    junit = invoke("select", "--mission", "trip", flights, "--budget", str(BUDGET),
                   "--format", "junit", "--require", "all")
    assert junit.exit_code == 1
    assert 'type="Unverified"' in junit.stdout and junit.stdout.count("<failure") == 1
    assert 'message="unverified: passes on its published figures, but VRE' in junit.stdout
    frame = gyrovib.mission(flights, missions="trip", budget=BUDGET).to_frame()
    assert list(frame.loc[frame.sensor == "no-vre", "status"]) == ["unverified"]


def test_mission_and_select_share_one_rule(flights: str) -> None:
    """A one-segment mission is select's verdict under the RMS criterion (the mission's
    budget is on Δ̄_RMS): the same status for every part, with or without the assumption."""
    one = flights.replace("flights.yaml", "one.yaml")
    Path(one).write_text(CATALOGUE + "missions:\n  - id: only\n    segments:\n"
                         "      - {profile: shaker, duration: 5}\n", encoding="utf-8")
    for extra in ((), ("--assume-unknown", "zero")):
        _, m = mission_json(one, *extra)
        _, s = select_json(one, "--profile", "shaker", "--criterion", "rms", *extra)
        by_select = {p["sensor"]: (p["profiles"][0]["status"], p["profiles"][0]["unknown"])
                     for p in s["sensors"]}
        by_mission = {r["sensor"]: (r["status"], r["unknown"]) for r in m["mission"]}
        assert by_mission == by_select
    assert by_select["no-vre"] == ("pass", ["vre"])


def test_report_mission_section_paints_unverified_apart(flights: str, tmp_path: Path) -> None:
    """report --mission: an unverified part's bar has its own colour (never the pass
    green), and --assume-unknown zero reaches the section."""
    from gyrovib.render.report_mission import OPEN_FILL, PASS_FILL

    out = tmp_path / "r.html"
    done = invoke("report", flights, "--budget", str(BUDGET), "--mission", "trip",
                  "--angle-budget", "1deg", "-o", out)
    assert done.exit_code in (0, 1), done.stderr
    html = out.read_text(encoding="utf-8")
    assert OPEN_FILL in html and "purple: unverified" in html
    out_zero = tmp_path / "z.html"
    invoke("report", flights, "--budget", str(BUDGET), "--mission", "trip",
           "--angle-budget", "1deg", "--assume-unknown", "zero", "-o", out_zero)
    zero = out_zero.read_text(encoding="utf-8")
    assert OPEN_FILL not in zero and PASS_FILL in zero
