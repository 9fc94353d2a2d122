"""`gyrovib analyze`: formats, options, exit codes (docs/output.md)."""

from __future__ import annotations

import csv
import io
import json
import math
import os
import stat
import subprocess
import sys
import threading

import pytest

CATALOG = """
gyrovib: 1
sensors:
  - id: small
    range: 10
    coefficients: {A1: 1e-3, k2: 1e-4, k3: 1e-6}
  - id: big
    range: 1000
    coefficients: {k2: -2e-4}
profiles:
  - id: tone
    rate: [0, 0, 5]
    harmonic: [{frequency: 100, amplitude: [0, 0, 2]}]
  - id: random
    random: {rms: [0, 0, 2]}
  - id: mixed
    harmonic: [{frequency: 100, amplitude: [0, 0, 1]}]
    random: {rms: [0, 0, 1]}
"""


@pytest.fixture
def catalog(write):
    return write(CATALOG)


def test_json_keys_and_values(run, catalog):
    result = run("analyze", catalog, "--format", "json", "--profile", "tone")
    assert result.exit_code == 0, result.output
    doc = json.loads(result.output)
    assert set(doc) == {"tool", "version", "method", "unit", "results"}
    assert (doc["tool"], doc["method"], doc["unit"]) == ("gyrovib", "exact", "deg/s")
    row = doc["results"][0]
    # the keys in the order of docs/output.md's analyze entry (a list: the order is fixed)
    assert list(row) == ["sensor", "profile", "rate", "additive_terms",
                         "multiplicative_coefficients", "additive", "multiplicative", "total",
                         "rms", "source", "saturated", "warnings"]
    assert row["source"] == "coefficients"
    # g2 = Δ0(6) of a linear vibration (docs/model.md section 8), then k3·M3 and k5·M5 of
    # locked harmonics (section 10): always present, 0 here (neither in this catalogue)
    assert list(row["additive_terms"]) == ["A1", "k2", "k4", "m31", "m32", "g2", "k3", "k5"]
    assert row["additive_terms"]["g2"] == 0.0
    assert row["additive_terms"]["k3"] == row["additive_terms"]["k5"] == 0.0
    assert row["saturated"] is False
    assert list(row["multiplicative_coefficients"]) == ["q1", "q2", "q3"]
    # small under tone: a = 2 < Ω = 5, so no asymmetry; k2·a²/2 = 2e-4;
    # Δ(1) = 3·k3·a²/2 = 6e-6, Δ_VM = 6e-6·5 = 3e-5
    assert row["additive_terms"]["A1"] == 0.0
    assert row["additive"] == pytest.approx(2e-4)
    assert row["multiplicative"] == pytest.approx(3e-5)
    assert row["total"] == pytest.approx(2.3e-4)
    assert row["rms"] == pytest.approx(math.hypot(2e-4, 3e-5))
    assert row["rate"] == [0.0, 0.0, 5.0]


def test_saturation_warning(run, catalog):
    # small: |Ω| + a = 5 + 2 = 7 < 10, fine; random: 3σ = 6 < 10; with --rate 9: 9 + 2 > 10
    doc = json.loads(run("analyze", catalog, "--format", "json", "--profile", "tone",
                         "--rate", "9").output)
    warned = {r["sensor"]: r["warnings"] for r in doc["results"]}
    assert warned["big"] == []
    assert len(warned["small"]) == 1 and "range" in warned["small"][0]
    table = run("analyze", catalog, "--profile", "tone", "--rate", "9").output
    assert "⚠1" in table and "saturation" in table


def test_rate_override_one_and_three_numbers(run, catalog):
    one = json.loads(run("analyze", catalog, "--format", "json", "--rate", "1").output)
    three = json.loads(run("analyze", catalog, "--format", "json", "--rate", "0,0,1").output)
    assert [r["total"] for r in one["results"]] == [r["total"] for r in three["results"]]
    assert all(r["rate"][2] == 1.0 for r in one["results"])


def test_rate_is_in_the_output_unit(run, catalog):
    # --rate 3600 with --unit deg/h is Ω = 1 deg/s
    a = json.loads(run("analyze", catalog, "--format", "json", "--rate", "1").output)
    b = json.loads(run("analyze", catalog, "--format", "json", "--rate", "3600",
                       "--unit", "deg/h").output)
    for x, y in zip(a["results"], b["results"], strict=True):
        assert y["total"] == pytest.approx(x["total"] * 3600, rel=1e-12)


def test_csv_has_one_row_per_pair(run, catalog):
    result = run("analyze", catalog, "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(result.output)))
    assert len(rows) == 2 * 3
    assert {r["sensor"] for r in rows} == {"small", "big"}
    json_rows = json.loads(run("analyze", catalog, "--format", "json").output)["results"]
    assert [float(r["total"]) for r in rows] == [r["total"] for r in json_rows]


def test_markdown_and_table(run, catalog):
    md = run("analyze", catalog, "--format", "markdown").output
    assert md.count("\n| small |") == 3 and "|---|" in md
    table = run("analyze", catalog).output
    assert "small" in table and "Δ_V(RMS)" in table


def test_paper_refuses_mixed_profile_with_its_location(run, catalog):
    result = run("analyze", catalog, "--method", "paper")
    assert result.exit_code == 2
    assert f"{catalog}:16:9: profile 'mixed'" in result.output
    assert "--method exact" in result.output
    ok = run("analyze", catalog, "--method", "paper", "--profile", "tone", "--profile", "random")
    assert ok.exit_code == 0, ok.output


def test_output_file_written_atomically_and_kept_on_failure(run, catalog, tmp_path):
    out = tmp_path / "result.json"
    assert run("analyze", catalog, "--format", "json", "-o", out).exit_code == 0
    good = out.read_text()
    assert json.loads(good)["results"]
    failed = run("analyze", catalog, "--format", "json", "-o", out, "--sensor", "nope")
    assert failed.exit_code == 2
    assert out.read_text() == good
    assert sorted(p.name for p in tmp_path.iterdir()) == ["catalog.yaml", "result.json"]


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs")
def test_output_to_a_fifo_writes_through_it(run, catalog, tmp_path):
    # -o /dev/null, a FIFO or a terminal must be written to, never replaced by a file
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    received: list[bytes] = []
    reader = threading.Thread(target=lambda: received.append(fifo.read_bytes()), daemon=True)
    reader.start()
    result = run("analyze", catalog, "--format", "json", "-o", fifo)
    reader.join(timeout=30)
    assert result.exit_code == 0, result.output
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert json.loads(received[0])["results"]


def test_bundled_catalogues_run_in_every_format(run):
    for fmt in ("table", "json", "csv", "markdown"):
        result = run("analyze", "--format", fmt)
        assert result.exit_code == 0, result.output
    doc = json.loads(run("analyze", "--format", "json").output)
    assert len({r["sensor"] for r in doc["results"]}) >= 8
    assert len({r["profile"] for r in doc["results"]}) >= 5


def test_module_entry_point_and_version():
    out = subprocess.run([sys.executable, "-m", "gyrovib", "--version"],
                         capture_output=True, text=True, check=True)
    assert out.stdout.startswith("gyrovib, version ")


def test_paper_names_every_refused_profile(run, write):
    path = write("""
        gyrovib: 1
        sensors:
          - id: s
            coefficients: {k2: 1e-4}
        profiles:
          - id: two-tones
            harmonic: [{frequency: 10, amplitude: [0, 0, 1]}, {frequency: 20, amplitude: [0, 0, 1]}]
          - id: ok
            random: {rms: [0, 0, 1]}
          - id: mixed
            harmonic: [{frequency: 10, amplitude: [0, 0, 1]}]
            random: {rms: [0, 0, 1]}
    """)
    result = run("analyze", path, "--method", "paper")
    assert result.exit_code == 2
    lines = result.output.splitlines()
    # one line per refused profile, at its id: lines 7 and 11 (the text opens with a blank line)
    assert [line.split(": profile ")[0] for line in lines] == [f"{path}:7:9", f"{path}:11:9"]
