"""``mission --segments``: the angle budget segment by segment (docs/model.md sections 12
and 15), in CSV records declared once and in a table. Every expected number is the hand
formula at the segment's end t: θ_V = Σ T_s·Δ_V,s so far, N·√t, B·t, K·t^1.5/√3, R·t
(t in hours), an unknown figure empty (never 0)."""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import pytest

from gyrovib.api.missions.results import SEGMENT_COLUMNS
from gyrovib.records import names, written
from tests.conftest import invoke
from tests.test_noise_budget import CATALOGUE


def _write(tmp_path: Path) -> Path:
    path = tmp_path / "c.gyrovib.yaml"
    path.write_text(CATALOGUE, encoding="utf-8")
    return path


def test_segment_records_are_the_budget_at_each_segments_end(tmp_path: Path) -> None:
    r = invoke("mission", _write(tmp_path), "--coverage", "2", "--segments",
               "--format", "csv")
    assert r.exit_code == 0, r.stderr
    rows = list(csv.DictReader(io.StringIO(r.stdout)))
    assert tuple(rows[0]) == names(written(SEGMENT_COLUMNS, "csv"))
    assert [(x["sensor"], x["segment"]) for x in rows] == [
        ("full", "1"), ("full", "2"), ("silent", "1"), ("silent", "2")]
    full = [x for x in rows if x["sensor"] == "full"]
    delta = float(full[0]["total"])           # one profile at one rate: Δ_V,s alike
    assert float(full[1]["total"]) == delta
    for k, x in enumerate(full, start=1):
        t = float(k)                           # hours flown at the segment's end
        assert (float(x["start"]), float(x["end"])) == (3600.0 * (k - 1), 3600.0 * k)
        assert float(x["theta_vibration"]) == pytest.approx(delta * 3600.0 * k, rel=1e-12)
        arw, bias = 0.15 * math.sqrt(t), 0.5 * t
        rrw, rep = 0.02 * t**1.5 / math.sqrt(3.0), 1.0 * t
        got = [float(x[f"theta_{n}"]) for n in
               ("arw", "bias_instability", "rrw", "repeatability")]
        assert got == pytest.approx([arw, bias, rrw, rep], rel=1e-9)
        total = abs(delta * 3600.0 * k) + 2.0 * math.sqrt(arw**2 + bias**2 + rrw**2 + rep**2)
        assert float(x["budget_total"]) == pytest.approx(total, rel=1e-9)
    # a sensor with no noise figures: each term unknown, written empty, never 0
    silent = [x for x in rows if x["sensor"] == "silent"]
    assert all(x["theta_arw"] == "" and x["theta_rrw"] == "" for x in silent)


def test_segments_table_and_formats(tmp_path: Path) -> None:
    path = _write(tmp_path)
    r = invoke("mission", path, "--segments")
    assert r.exit_code == 0, r.stderr
    assert "Segment by segment" in r.stdout
    plain = invoke("mission", path)
    assert "Segment by segment" not in plain.stdout
    # the default CSV keeps one row per sensor × mission × axis
    assert len(invoke("mission", path, "--format", "csv").stdout.splitlines()) == 3
    refused = invoke("mission", path, "--segments", "--format", "junit")
    assert refused.exit_code == 2 and "--segments" in refused.stderr
    # Markdown: the same segment table under the rows, the same cells as the CSV's
    md = invoke("mission", path, "--segments", "--format", "markdown", "--coverage", "2")
    assert md.exit_code == 0, md.stderr
    assert md.stdout.startswith(invoke("mission", path, "--format", "markdown",
                                       "--coverage", "2").stdout)
    lines = md.stdout.split("Segment by segment")[1].splitlines()
    rows = [line for line in lines if line.startswith("| full ")]
    assert len(rows) == 2 and rows[1].split(" | ")[2] == "2"  # its segment number
    silent = [line for line in lines if line.startswith("| silent ")]
    assert all("| ? |" in line for line in silent)  # unknown noise: '?', never 0


def test_segment_csv_and_frame_come_from_one_declaration() -> None:
    pytest.importorskip("pandas")
    from gyrovib import api
    from gyrovib.catalog.loader import merge, parse_catalog
    from gyrovib.render.mission_segments import segments_csv

    result = api.mission(merge([parse_catalog(CATALOGUE, "<c>")]), coverage=2.0)
    table = list(csv.reader(io.StringIO(segments_csv(result))))
    frame = result.segments_frame()
    assert tuple(table[0]) == tuple(frame.columns) == names(written(SEGMENT_COLUMNS, "csv"))
    assert len(table) - 1 == len(frame) == sum(len(r.segments) for r in result.rows) == 4
