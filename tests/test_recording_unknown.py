"""Nothing read as zero from a recording (docs/model.md section 13, first paragraph;
docs/recordings.md): an axis not recorded is unknown, a lone
rate column is placed by the user, duplicated recordings are refused, short segments
and damaged files are located errors or labelled answers, never a crash."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import invoke

pytest.importorskip("scipy.signal")

FS = 1000.0

#: k2 only (depends on x3 alone); m31 (depends on x1 too); a g² term (needs the
#: accelerations); none of these reads an axis it does not depend on.
SENSORS = """\
gyrovib: 1
units: {rate: deg/s, acceleration: g}
sensors:
  - id: k2-only
    coefficients: {k2: 1.0e-3}
    vre: 0
  - id: cross
    coefficients: {k2: 1.0e-3, m31: 2.0e-3}
    vre: 0
  - id: g2
    coefficients: {k2: 1.0e-3}
    vre: 1.0e-3
"""


def _catalogue(tmp_path: Path) -> Path:
    path = tmp_path / "sensors.gyrovib.yaml"
    path.write_text(SENSORS, encoding="utf-8")
    return path


def _csv(tmp_path: Path, columns: str, seconds: float = 20.0, name: str = "rec.csv",
         seed: int = 1) -> Path:
    """Gaussian noise σ = 1 deg/s and a 60 Hz tone of 3 deg/s on each named column."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * FS)) / FS
    names = columns.split(",")
    data = [t] + [rng.normal(0, 1, t.size) + 3 * np.sin(2 * np.pi * 60 * t) for _ in names]
    path = tmp_path / name
    np.savetxt(path, np.column_stack(data), delimiter=",", header="t," + columns,
               comments="", fmt="%.6f")
    return path


# ----------------------------------------------------------------- a lone column


@pytest.mark.parametrize("columns", ["gz", "gx,gy"])
def test_a_lone_rate_column_is_placed_by_the_user_not_by_a_rule(tmp_path: Path,
                                                                 columns: str) -> None:
    path = _csv(tmp_path, columns, seconds=2.0)
    for command in (("profile", path), ("analyze", "--recording", path, "--bundled",
                                        "sensors")):
        r = invoke(*command)
        assert r.exit_code == 2 and r.stdout == ""
        assert r.stderr.startswith(f"{path}: ") and "--rate-columns" in r.stderr
    r = invoke("profile", path)
    example = "-,-,gz" if columns == "gz" else "-,gx,gy"
    assert f"--rate-columns {example}" in r.stderr


# ----------------------------------------------------------------- analyze --recording


def _analyze(tmp_path: Path, fmt: str, columns: str = "-,-,gz") -> str:
    path = _csv(tmp_path, "gz")
    r = invoke("analyze", "--recording", path, "--rate-columns", columns,
               _catalogue(tmp_path), "--format", fmt)
    assert r.exit_code == 0, r.stderr
    return r.stdout


def test_analyze_json_is_null_where_an_axis_is_not_recorded(tmp_path: Path) -> None:
    # only x3 recorded: k2-only depends on x3 alone (a number); cross's m31·x3·x1 needs x1,
    # g2's G_jj·⟨a_j² − A_j²⟩ needs the accelerations: unknown, null (never 0)
    rows = {r["sensor"]: r for r in json.loads(_analyze(tmp_path, "json"))["results"]}
    assert rows["k2-only"]["recorded"]["total"] > 0
    for sensor, axis in (("cross", "axis x1"), ("g2", "the accelerations")):
        assert rows[sensor]["recorded"]["total"] is None
        assert rows[sensor]["fitted"]["total"] is None and rows[sensor]["ratio"] is None
        assert set(rows[sensor]["recorded"]["additive_terms"].values()) == {None}
        assert axis in rows[sensor]["warnings"][0]


def test_analyze_with_the_sensitive_axis_unknown_knows_nothing(tmp_path: Path) -> None:
    # the same column placed on X: x3 is not recorded, every Δ_V,rec is unknown
    rows = json.loads(_analyze(tmp_path, "json", "gz,-,-"))["results"]
    assert [r["recorded"]["total"] for r in rows] == [None, None, None]
    assert all("axis x3 (the sensitive axis)" in r["warnings"][0] for r in rows)


def test_analyze_csv_table_markdown_and_frame_say_unknown(tmp_path: Path) -> None:
    csv_rows = _analyze(tmp_path, "csv").splitlines()
    cross = next(r for r in csv_rows if r.startswith("cross,")).split(",")
    assert cross[1] == "" and cross[10] == ""  # recorded, fitted: empty, not 0
    for fmt in ("table", "markdown"):
        out = _analyze(tmp_path, fmt)
        line = next(x for x in out.splitlines() if "cross" in x and "?" in x)
        assert line.count("?") == 3  # Δ_V,rec, the fitted closed form and their ratio
    from gyrovib.api import load
    from gyrovib.api.recordings.analysis import analyze_recording
    from gyrovib.api.recordings.reading import read_recording

    pytest.importorskip("pandas")
    rec = read_recording(str(tmp_path / "rec.csv"), rate_columns=(None, None, "gz"))
    frame = analyze_recording(rec, load([_catalogue(tmp_path)])).to_frame()
    assert np.isnan(frame["recorded"][1]) and np.isnan(frame["fitted"][2])
    assert frame["recorded"][0] > 0


def test_report_shows_unknown_as_a_question_mark(tmp_path: Path) -> None:
    path = _csv(tmp_path, "gz")
    out = tmp_path / "r.html"
    r = invoke("report", _catalogue(tmp_path), "--recording", path, "--rate-columns",
               "-,-,gz", "--budget", "1deg/s", "-o", out)
    assert r.exit_code in (0, 1), r.stderr
    html = out.read_text(encoding="utf-8")
    assert "<td>cross</td><td>?</td><td>?</td>" in html
    # the honesty of the fit: the axes not recorded are '?' throughout, never '—'
    assert "<td>X</td>" + "<td>?</td>" * 6 in html and "<td>Y</td>" + "<td>?</td>" * 6 in html


def test_several_recordings_one_without_an_axis_leave_the_worst_unknown(
        tmp_path: Path) -> None:
    full = _csv(tmp_path, "gx,gy,gz", name="full.csv")
    lone = _csv(tmp_path, "gx,gy", name="lone.csv", seed=2)
    doc_args = ("analyze", "--recording", full, "--recording", lone,
                _catalogue(tmp_path), "--format", "json")
    # one placement for both files: x3 is recorded in neither, so every sensor's Δ_V,rec
    # is unknown on each and its worst recording is unknown too (null), never the other's
    r = invoke(*doc_args, "--rate-columns", "gx,gy,-")
    assert r.exit_code == 0, r.stderr
    worst = json.loads(r.stdout)["worst"]
    assert [w["recording"] for w in worst] == [None, None, None]


# ----------------------------------------------------------------- profile, select, mission


def test_profile_writes_no_part_for_an_axis_not_recorded(tmp_path: Path) -> None:
    import yaml

    path = _csv(tmp_path, "gz")
    out = tmp_path / "p.gyrovib.yaml"
    r = invoke("profile", path, "--rate-columns", "-,-,gz", "-o", out)
    assert r.exit_code == 0, r.stderr
    text = out.read_text(encoding="utf-8")
    assert "# Not recorded: x1, x2, acceleration. Unknown, not 0" in text
    profile = yaml.safe_load(text)["profiles"][0]
    assert profile["not_recorded"] == ["x1", "x2", "acceleration"]
    assert set(profile["random"]["psd"]) == {"x3"}
    assert "acceleration" not in profile
    assert invoke("validate", out).exit_code == 0


def test_select_and_mission_do_not_pass_sensors_on_an_unknown_axis(tmp_path: Path) -> None:
    path = _csv(tmp_path, "gz")
    out = tmp_path / "p.gyrovib.yaml"
    assert invoke("profile", path, "--rate-columns", "-,-,gz", "-o", out).exit_code == 0
    cat = _catalogue(tmp_path)
    # a budget every sensor meets on the recorded axis alone (k2·σ² ≈ 1e-3·10 deg/s)
    r = invoke("select", cat, out, "--budget", "10deg/s", "--format", "json")
    cells = {s["sensor"]: s["profiles"][0] for s in json.loads(r.stdout)["sensors"]}
    assert cells["k2-only"]["status"] == "pass"
    for sensor, part in (("cross", "x1"), ("g2", "acceleration")):
        assert (cells[sensor]["pass"], cells[sensor]["status"]) == (False, "unverified")
        assert part in cells[sensor]["unknown"]
        assert "fitted from a recording without" in cells[sensor]["reason"]
    # the fitted mission alike, with a budget and under select --mission
    mission = "rec-fitted-mission"
    for args in (("mission", cat, out, "--mission", mission),
                 ("select", cat, out, "--mission", mission)):
        r = invoke(*args, "--angle-budget", "1000deg", "--format", "json")
        rows = {row["sensor"]: row for row in json.loads(r.stdout)["mission"]}
        assert rows["cross"]["status"] == rows["g2"]["status"] == "unverified"
        assert "x1" in rows["cross"]["unknown"] and "acceleration" in rows["g2"]["unknown"]
    # --assume-unknown zero is for unpublished figures, not for axes not recorded
    r = invoke("select", cat, out, "--budget", "10deg/s", "--assume-unknown", "zero",
               "--format", "json")
    cells = {s["sensor"]: s["profiles"][0] for s in json.loads(r.stdout)["sensors"]}
    assert cells["cross"]["status"] == "unverified"


# ----------------------------------------------------------------- duplicates


def test_a_recording_given_twice_is_refused_naming_both(tmp_path: Path) -> None:
    path = _csv(tmp_path, "gx,gy,gz", seconds=10.0)
    r = invoke("profile", path, path)
    assert r.exit_code == 2 and r.stdout == ""
    assert r.stderr.startswith(f"{path}: this recording is given twice")
    copy = tmp_path / "copy.csv"
    shutil.copy(path, copy)
    for args in (("profile", path, copy), ("analyze", "--recording", path, "--recording",
                                           copy, "--bundled", "sensors")):
        r = invoke(*args, "--jobs", 1)
        assert r.exit_code == 2 and r.stdout == ""
        assert r.stderr.startswith(f"{copy}: this recording has the same contents")
        assert str(path) in r.stderr


# ----------------------------------------------------------------- short segments


def _gappy(tmp_path: Path, length: float, gaps: int = 8) -> Path:
    """Segments of ``length`` s at 1 kHz, 50 ms apart (a gap is > 1.5 median intervals)."""
    rng = np.random.default_rng(3)
    t = np.concatenate([k * (length + 0.05) + np.arange(int(length * FS)) / FS
                        for k in range(gaps)])
    path = tmp_path / "gaps.csv"
    np.savetxt(path, np.column_stack([t, rng.normal(0, 1, (t.size, 3))]), delimiter=",",
               header="t,gx,gy,gz", comments="", fmt="%.6f")
    return path


def test_segments_shorter_than_a_welch_window_are_a_located_error(tmp_path: Path) -> None:
    # 1.5 s segments: longer than 4/f_c = 0.8 s, shorter than 1/Δf = 2 s (2000 samples)
    path = _gappy(tmp_path, 1.5)
    for args in (("profile", path), ("analyze", "--recording", path, "--bundled", "sensors"),
                 ("profile", path, _csv(tmp_path, "gx,gy,gz"), "--jobs", 2)):
        r = invoke(*args)
        assert r.exit_code == 2, r.stderr
        assert f"{path}: no contiguous segment holds one Welch window" in r.stderr
        # fs / longest = 1000 / 1500 = 0.6667 Hz, rounded up
        assert "--resolution 0.667 or more" in r.stderr
    assert invoke("profile", path, "--resolution", "0.667").exit_code == 0


def test_short_segments_are_left_out_of_the_spectra_with_a_warning(tmp_path: Path) -> None:
    # a variant: one 3 s segment holds a window, the 1.5 s ones do not
    path = _gappy(tmp_path, 1.5)
    with path.open("a", encoding="utf-8") as fh:
        t = 20.0 + np.arange(3000) / FS
        for v in t:
            fh.write(f"{v:.6f},0.1,0.2,0.3\n")
    r = invoke("profile", path)
    assert r.exit_code == 0, r.stderr
    assert "8 of 9 segment(s) shorter than one Welch window" in r.stderr
    assert "Δ_V,rec and the statistics use every sample" in r.stderr
    assert "15 s analysed" in r.stderr  # every sample: 8 × 1.5 s + 3 s


# ----------------------------------------------------------------- only recorded axes


def test_only_recorded_axes_are_built(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from gyrovib.api.noise import allan
    from gyrovib.api.recordings.readers import NpyStore
    from gyrovib.api.recordings.reading import read_recording

    path = tmp_path / "one.npy"
    np.save(path, np.random.default_rng(4).normal(0, 1, (5000, 1)))
    rec = read_recording(str(path), fs=100.0, rate_columns=(None, None, 0))

    def whole(*args: object) -> None:
        raise AssertionError("the three axes were built")

    monkeypatch.setattr(NpyStore, "block", whole)
    result = allan(rec)
    assert [a.axis for a in result.axes] == ["Z"]
    csv = _csv(tmp_path, "gz", seconds=1.0)
    store = read_recording(str(csv), rate_columns=(None, None, "gz")).store
    assert [c is None for c in store.arrays["rate"]] == [True, True, False]


# ----------------------------------------------------------------- messages


@pytest.mark.parametrize("suffix", [".npz", ".npy"])
def test_random_bytes_are_not_a_valid_numpy_file(tmp_path: Path, suffix: str) -> None:
    path = tmp_path / f"noise{suffix}"
    path.write_bytes(np.random.default_rng(5).bytes(4096))
    r = invoke("profile", path, "--fs", 100)
    assert r.exit_code == 2
    assert r.stderr.startswith(f"{path}: not a valid {suffix[1:]}")
    assert "allow_pickle" not in r.stderr and "pickle" not in r.stderr


@pytest.mark.parametrize(("stamps", "line", "what"), [
    ("0\n0.001\n0.001\n0.003\n", 4, "repeats"),
    ("0\n0.001\n\n0.002\n0.0015\n", 6, "goes back"),  # the blank line 4 is counted
])
def test_bad_time_stamps_name_file_and_line(tmp_path: Path, stamps: str, line: int,
                                            what: str) -> None:
    path = tmp_path / "t.csv"
    path.write_text("gx,gy,t,gz\n" + "".join(f"1,2,{s},3\n" if s else "\n"
                                               for s in stamps.split("\n")[:-1]),
                    encoding="utf-8")
    r = invoke("profile", path)
    assert r.exit_code == 2
    # the time cell is the third: column 1 + len("1,2,") = 5
    assert r.stderr.startswith(f"{path}:{line}:5: ") and f"the time stamp {what}" in r.stderr


def test_the_worst_of_several_recordings_is_unknown_where_one_is() -> None:
    from gyrovib.api.fleet.run import worst_recordings

    # sensor 0: unknown on recording 1, so its worst is unknown (-1) though recording 0
    # gives 1.0; sensor 1: |−3| on recording 1 is the largest (a hand count)
    recorded = np.array([[1.0, 2.0], [np.nan, -3.0]])
    assert worst_recordings(recorded) == (-1, 1)


def test_an_envelope_knows_an_axis_only_where_every_recording_recorded_it(
        tmp_path: Path) -> None:
    import yaml

    from gyrovib.api.fleet.envelope import envelope
    from gyrovib.api.fleet.run import RecordingOptions, profile_one

    full = _csv(tmp_path, "gx,gy,gz,ax,ay,az", name="full.csv")
    lone = _csv(tmp_path, "gy,gz", name="lone.csv", seed=2)
    fits = [profile_one(str(full), RecordingOptions(rate_columns=("gx", "gy", "gz"),
                                                    accel_columns=("ax", "ay", "az"))),
            profile_one(str(lone), RecordingOptions(rate_columns=(None, "gy", "gz")))]
    env = envelope(fits)
    # lone.csv has neither x1 nor accelerations: the envelope's largest PSD on x1 would
    # be full.csv's alone, a lower bound; unknown instead, and said so
    assert env.fit.rate_axes == (False, True, True)
    text = env.fit.yaml
    assert "# Not recorded: x1, acceleration. Unknown, not 0" in text
    profile = yaml.safe_load(text)["profiles"][0]
    assert profile["not_recorded"] == ["x1", "acceleration"]
    assert set(profile["random"]["psd"]) == {"x2", "x3"} and "acceleration" not in profile
    assert np.isnan(env.fit.honesty[0].variance)
    # both recordings complete: nothing is said
    other = _csv(tmp_path, "gx,gy,gz,ax,ay,az", name="other.csv", seed=3)
    both = envelope([fits[0], profile_one(str(other), RecordingOptions(
        rate_columns=("gx", "gy", "gz"), accel_columns=("ax", "ay", "az")))])
    assert "not_recorded" not in both.fit.yaml and "Not recorded" not in both.fit.yaml
    # the library's envelope refuses one recording twice, as the command does
    from gyrovib.errors import GyrovibError

    with pytest.raises(GyrovibError, match="same contents"):
        envelope([fits[0], fits[0]])


def test_a_placement_moves_the_unknown_axis_with_the_sensor(tmp_path: Path) -> None:
    # recorded: vehicle Y and Z; with x3 on vehicle X (x1=+Y, x2=+Z, x3=+X) the sensitive
    # axis lies on the unrecorded X, so even k2-only, which needs x3 alone, is unverified;
    # with the default placement it is not
    path = _csv(tmp_path, "gy,gz")
    out = tmp_path / "p.gyrovib.yaml"
    assert invoke("profile", path, "--rate-columns", "-,gy,gz", "-o", out).exit_code == 0
    cat = _catalogue(tmp_path)
    for placement, status in (("x1=+X,x2=+Y,x3=+Z", "pass"), ("x1=+Y,x2=+Z,x3=+X",
                                                              "unverified")):
        r = invoke("select", cat, out, "--budget", "10deg/s", "--placement", placement,
                   "--format", "json")
        cells = {s["sensor"]: s["profiles"][0] for s in json.loads(r.stdout)["sensors"]}
        assert cells["k2-only"]["status"] == status, placement
    from gyrovib.api import load
    from gyrovib.api.placement.placement import place_profile
    from gyrovib.core.placement import Placement

    profile = load([out]).profiles[0].profile
    assert profile.not_recorded == ["x1", "acceleration"]
    placed = place_profile(profile, Placement(source=(1, 2, 0)))
    assert placed.not_recorded == ["x3", "acceleration"]


def test_the_fitted_mission_reads_unknown_where_a_sensor_needs_a_missing_axis(
        tmp_path: Path) -> None:
    path = _csv(tmp_path, "gz")
    out = tmp_path / "p.gyrovib.yaml"
    assert invoke("profile", path, "--rate-columns", "-,-,gz", "-o", out).exit_code == 0
    args = ("mission", _catalogue(tmp_path), out, "--angle-budget", "1000deg")
    rows = {r["sensor"]: r for r in json.loads(invoke(*args, "--format", "json").stdout)[
        "mission"]}
    # k2-only needs x3 alone: numbers; cross needs x1 (m31): unknown, never those numbers
    # (no noise figures here: both are unverified on them too, k2-only on them alone)
    assert rows["k2-only"]["mean"] > 0
    assert not set(rows["k2-only"]["unknown"]) & {"x1", "x2", "x3", "acceleration"}
    cross = rows["cross"]
    assert (cross["mean"], cross["angle"], cross["rms"]) == (None, None, None)
    assert cross["budget"]["vibration"] is None and cross["budget"]["total"] is None
    assert cross["status"] == "unverified"
    table = invoke(*args, "--format", "markdown").stdout
    line = next(x for x in table.splitlines() if x.startswith("| cross"))
    assert "nan" not in line and line.count("| ? |") >= 3
    got = next(r for r in invoke(*args, "--format", "csv").stdout.splitlines()
               if r.startswith("cross,"))
    assert ",,,," in got and "nan" not in got
    # a triad: with x3 on every vehicle axis in turn, the worst axis is unknown too
    triad = json.loads(invoke(*args, "--placement", "triad", "--format", "json").stdout)
    assert {t["worst_axis"] for t in triad["triads"] if t["sensor"] == "cross"} == {None}


def test_analyze_on_a_fitted_profile_reads_unknown_where_an_axis_is_missing(
        tmp_path: Path) -> None:
    path = _csv(tmp_path, "gz")
    out = tmp_path / "p.gyrovib.yaml"
    assert invoke("profile", path, "--rate-columns", "-,-,gz", "-o", out).exit_code == 0
    args = ("analyze", _catalogue(tmp_path), out)
    rows = {r["sensor"]: r for r in json.loads(invoke(*args, "--format", "json").stdout)[
        "results"]}
    # k2-only: Δ0(2) = k2·σ3² > 0 on the recorded x3; cross needs x1 (m31·C31): null
    assert rows["k2-only"]["total"] > 0
    assert rows["cross"]["total"] is None and rows["cross"]["rms"] is None
    assert set(rows["cross"]["additive_terms"].values()) == {None}
    assert "without x1" in rows["cross"]["warnings"][0]
    for fmt in ("table", "markdown"):
        line = next(x for x in invoke(*args, "--format", fmt).stdout.splitlines()
                    if "cross" in x)
        assert "?" in line and "nan" not in line and " 0 " not in line
    got = next(r for r in invoke(*args, "--format", "csv").stdout.splitlines()
               if r.startswith("cross,"))
    assert "nan" not in got and ",,,," in got


def test_bounds_of_a_profile_without_an_axis_are_unknown_not_unbounded(
        tmp_path: Path) -> None:
    # x1 not recorded: m31's bound (α4·Δ*/|C31|) is unknown, not the 'unbounded' that a
    # C31 read as 0 would give; x3 not recorded: every bound is unknown
    path = tmp_path / "p.yaml"
    path.write_text("""\
gyrovib: 1
units: {rate: deg/s, acceleration: g}
profiles:
  - id: no-x1
    rate: [0, 0, 1]
    not_recorded: [x1]
    harmonic: [{frequency: 50, amplitude: [1, 1, 2]}]
  - id: no-x3
    rate: [0, 0, 1]
    not_recorded: [x3]
    harmonic: [{frequency: 50, amplitude: [1, 1, 0]}]
""", encoding="utf-8")
    doc = json.loads(invoke("bounds", path, "--budget", "1deg/s", "--format", "json").stdout)
    no_x1, no_x3 = (p["bounds"] for p in doc["profiles"])
    assert no_x1["m31"] is None and no_x1["m32"] > 0 and no_x1["k2"] > 0
    assert set(no_x3.values()) == {None}
    table = invoke("bounds", path, "--budget", "1deg/s").stdout
    m31 = next(x for x in table.splitlines() if "m31" in x)
    assert "?" in m31 and "unbounded" not in m31 and "nan" not in table
    rows = invoke("bounds", path, "--budget", "1deg/s", "--format", "csv").stdout.splitlines()
    assert rows[2].startswith("no-x3,0.0,0.0,1.0,,,") and "nan" not in rows[2]


def test_sweep_on_a_fitted_profile_reads_unknown_where_an_axis_is_missing(
        tmp_path: Path) -> None:
    path = _csv(tmp_path, "gz")
    out = tmp_path / "p.gyrovib.yaml"
    assert invoke("profile", path, "--rate-columns", "-,-,gz", "-o", out).exit_code == 0
    args = ("sweep", _catalogue(tmp_path), out, "--rate-range", "0:10:3")
    series = {s["sensor"]: s for s in json.loads(invoke(*args, "--format", "json").stdout)[
        "series"]}
    assert all(v > 0 for v in series["k2-only"]["exact"]["total"])
    assert series["cross"]["exact"]["total"] == [None, None, None]
    rows = [r for r in invoke(*args, "--format", "csv").stdout.splitlines()
            if r.startswith("cross,")]
    assert len(rows) == 3 and all(",,,," in r and "nan" not in r for r in rows)
    table = invoke(*args).stdout
    cross = table[table.index("cross / "):]
    assert "nan" not in table and cross.count("?") >= 6  # Δ_V and Δ_V(RMS) at 3 rates


def test_select_checks_that_rest_on_an_unrecorded_axis_are_unknown(tmp_path: Path) -> None:
    """A cell made unverified by a missing axis shows no check computed without it: each
    bound that depends on the axis is unknown (docs/model.md section 13: m31's bound rests
    on x1, every bound on x3), and a check of a coefficient that is not 0 against an
    unknown bound is neither passed nor failed; the cell's margin is unknown too. A
    coefficient that is 0 is within any bound (0 ≤ b for every b ≥ 0), so k2-only's m31
    check still passes."""
    path = _csv(tmp_path, "gy,gz")
    out = tmp_path / "p.gyrovib.yaml"
    assert invoke("profile", path, "--rate-columns", "-,gy,gz", "-o", out).exit_code == 0
    cat = _catalogue(tmp_path)
    r = invoke("select", cat, out, "--budget", "10deg/s", "--format", "json")
    assert r.exit_code == 0, r.stderr
    cells = {s["sensor"]: s["profiles"][0] for s in json.loads(r.stdout)["sensors"]}
    cross, alone = cells["cross"], cells["k2-only"]
    assert cross["status"] == "unverified" and cross["criterion_margin"] is None
    assert cross["checks"]["m31"] == {"value": 2.0e-3, "bound": None, "pass": None}
    assert alone["checks"]["m31"]["bound"] is None and alone["checks"]["m31"]["pass"] is True
    # the bounds resting on x2 and x3 alone, which were recorded, are still figures
    assert cross["checks"]["k2"]["bound"] == alone["checks"]["k2"]["bound"] > 0
    r = invoke("select", cat, out, "--budget", "10deg/s", "--format", "csv")
    rows = {row.split(",")[0]: row.split(",") for row in r.stdout.splitlines()}
    head = rows["sensor"]
    cell = dict(zip(head, rows["cross"], strict=False))
    assert (cell["bound_m31"], cell["pass_m31"], cell["criterion_margin"]) == ("", "", "")
    r = invoke("select", cat, out, "--budget", "10deg/s", "--format", "junit")
    assert "nan" not in r.stdout.lower()


def test_select_without_the_sensitive_axis_knows_no_bound(tmp_path: Path) -> None:
    """Without x3 every bound is unknown (each rests on x3): no check passes on a
    coefficient that is not 0, and no sensor is ranked."""
    path = _csv(tmp_path, "gx,gy")
    out = tmp_path / "p.gyrovib.yaml"
    assert invoke("profile", path, "--rate-columns", "gx,gy,-", "-o", out).exit_code == 0
    r = invoke("select", _catalogue(tmp_path), out, "--budget", "10deg/s", "--format", "json")
    assert r.exit_code == 1, r.stderr  # the requirement is not met: nothing is verified
    for sensor in json.loads(r.stdout)["sensors"]:
        cell = sensor["profiles"][0]
        assert cell["status"] == "unverified"
        assert cell["checks"]["k2"] == {"value": 1.0e-3, "bound": None, "pass": None}
        assert all(c["bound"] is None for c in cell["checks"].values())


def test_a_mission_allowance_on_an_unknown_error_is_unknown(tmp_path: Path) -> None:
    """The largest noise figure that meets the angle budget is θ* − |θ_V| shared out
    (docs/model.md section 15): with θ_V unknown (the sensor needs x1, not recorded) it
    is unknown — null in JSON with no 'limited_by' reason, '?' in the table — never 'nan'."""
    path = _csv(tmp_path, "gy,gz")
    out = tmp_path / "p.gyrovib.yaml"
    assert invoke("profile", path, "--rate-columns", "-,gy,gz", "-o", out).exit_code == 0
    args = ("mission", _catalogue(tmp_path), out, "--mission", "rec-fitted-mission",
            "--angle-budget", "1000deg")
    r = invoke(*args, "--format", "json")
    rows = {row["sensor"]: row for row in json.loads(r.stdout)["mission"]}
    allowed = rows["cross"]["budget"]["allowed"]
    assert allowed["arw"] is None and "arw" not in allowed["limited_by"]
    table = invoke(*args, env={"COLUMNS": "240"})
    assert "nan" not in table.stdout.lower()
    cross = next(line for line in table.stdout.splitlines()
                 if "cross" in line and "≤" in line)
    assert cross.count("?") == 4  # N, B, K, R


def test_the_report_of_a_mission_draws_no_unknown_angle(tmp_path: Path) -> None:
    """A mission whose θ_V is unknown for a sensor (it needs x1, not recorded): the report's
    verdict table and segment table read '?', and no θ(t) chart is drawn from NaN (an
    SVG of 'nan' coordinates draws nothing a reader can tell from an empty chart)."""
    path = _csv(tmp_path, "gy,gz")
    fitted = tmp_path / "p.gyrovib.yaml"
    assert invoke("profile", path, "--rate-columns", "-,gy,gz", "-o", fitted).exit_code == 0
    out = tmp_path / "r.html"
    r = invoke("report", _catalogue(tmp_path), fitted, "--budget", "10deg/s", "--mission",
               "rec-fitted-mission", "--angle-budget", "1000deg", "-o", out)
    assert r.exit_code in (0, 1), r.stderr
    html = out.read_text(encoding="utf-8")
    assert re.search(r"\bnan\b", html, re.IGNORECASE) is None
    assert "cross: θ(t) unknown" in html
    assert "<tr><td>cross</td><td>-</td><td>?</td><td>?</td>" in html


def test_a_datasheet_part_without_the_sensitive_axis_has_no_allowable_figures(
        tmp_path: Path) -> None:
    """A datasheet part's allowable NL and VRE rest on x3 and the accelerations (docs/model.md
    section 11): without them both are unknown, and so are the checks against them."""
    path = _csv(tmp_path, "gx,gy")
    out = tmp_path / "p.gyrovib.yaml"
    assert invoke("profile", path, "--rate-columns", "gx,gy,-", "-o", out).exit_code == 0
    cat = tmp_path / "ds.gyrovib.yaml"
    cat.write_text("gyrovib: 1\nunits: {rate: deg/s, acceleration: g}\nsensors:\n"
                   "  - id: ds\n    specs:\n      range: 300\n"
                   "      nonlinearity: {value: 0.1, unit: '%FS', fit: least-squares, "
                   "measure: max, of: range}\n      vre: 0.01\n", encoding="utf-8")
    r = invoke("select", cat, out, "--budget", "10deg/s", "--format", "json")
    cell = json.loads(r.stdout)["sensors"][0]["profiles"][0]
    assert cell["status"] == "unverified"
    for name in ("nonlinearity", "vre"):
        assert (cell["checks"][name]["bound"], cell["checks"][name]["pass"]) == (None, None)
    r = invoke("select", cat, out, "--budget", "10deg/s", "--format", "csv")
    head, row = (line.split(",") for line in r.stdout.splitlines()[:2])
    cells = dict(zip(head, row, strict=False))
    assert [cells[k] for k in ("bound_nonlinearity", "pass_nonlinearity", "bound_vre",
                               "pass_vre")] == ["", "", "", ""]


def test_the_stderr_tables_write_an_axis_not_recorded_as_unknown(tmp_path: Path) -> None:
    # profile's honesty table (standard error) for a lone x3 column: the X and Y rows and
    # their mean rates are '?', never '—' (a figure that does not apply) or 0; a note
    # says why. Z, recorded, keeps its numbers, and a complete recording has no '?'.
    lone = _csv(tmp_path, "gz", name="lone.csv")
    r = invoke("profile", lone, "--rate-columns", "-,-,gz", "-o", tmp_path / "p.yaml")
    assert r.exit_code == 0, r.stderr
    rows = {line.split()[0]: line.split() for line in r.stderr.splitlines()
            if line[:2] in ("X ", "Y ", "Z ")}
    assert rows["X"][1:] == rows["Y"][1:] == ["?"] * 6
    assert "?" not in rows["Z"] and float(rows["Z"][1]) > 0
    rate = r.stderr.split("mean rate Ω_K = [")[1].split("]")[0].split(", ")
    assert rate[:2] == ["?", "?"] and rate[2] != "?"
    assert "?: an axis the recording did not record: unknown, never 0" in r.stderr
    full = _csv(tmp_path, "gx,gy,gz", name="full.csv", seed=2)
    r = invoke("profile", full, "--rate-columns", "gx,gy,gz", "-o", tmp_path / "f.yaml")
    assert r.exit_code == 0 and "?" not in r.stderr
    # the envelope of both: x1 and x2 known only where every recording recorded them
    r = invoke("profile", full, lone, "--rate-columns", "-,-,gz", "-o", tmp_path / "e.yaml")
    assert r.exit_code == 0, r.stderr
    envelope = r.stderr.split("envelope of 2 recordings")[1]
    rows = {line.split()[0]: line.split() for line in envelope.splitlines()
            if line[:2] in ("X ", "Y ", "Z ")}
    assert rows["X"][1:] == rows["Y"][1:] == ["?", "?"] and "?" not in rows["Z"]
    assert envelope.split("mean rate Ω_K = [")[1].startswith("?, ?, ")


def test_analyze_recording_writes_a_ratio_to_an_unknown_closed_form_as_unknown() -> None:
    # A datasheet part on a log with x3 alone: Δ_V,rec is known (its worst case needs x3
    # only), the fitted mission's closed form is not (its envelope reads m31, m32 with
    # x1, x2 unrecorded): their ratio is '?', never '—' (which says one of them is 0)
    root = Path(__file__).resolve().parents[1]
    r = invoke("analyze", "--bundled", "sensors", "--sensor", "adxrs645", "--recording",
               root / "tests" / "data" / "px4-sample.ulg", "--rate-columns", "-,-,gyro_rad[2]")
    assert r.exit_code == 0, r.stderr
    row = next(line for line in r.stdout.splitlines() if line.startswith("adxrs645")).split()
    assert row[2:4] == ["?", "?"] and float(row[1]) > 0
