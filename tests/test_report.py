"""`gyrovib report`: a self-contained HTML page, escaped, with the numbers of `select`."""

from __future__ import annotations

import hashlib
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib import api
from gyrovib.api.report.views import envelope, trade_study
from gyrovib.cli.main import cli
from gyrovib.core.analysis import ADDITIVE_TERMS, MULTIPLICATIVE_TERMS
from gyrovib.render import svg
from gyrovib.render.report import term_names, term_squares, to_html

HOSTILE = '<script>alert("x")</script> & <b>bold</b>'

# One sensor passes, one fails: A1 = 0.5 against the tone's A1 bound
# α1·Δ*/g_A = 0.4447·0.01/0.4066 = 0.01094 (exact, Δ* = 0.01 deg/s; test_select_cli.py).
CATALOG = f"""\
gyrovib: 1
units: {{rate: deg/s}}
sensors:
  - id: good
    name: '{HOSTILE}'
    coefficients: {{k2: 1.0e-4}}
  - id: awful
    range: 1.0
    coefficients: {{A1: 0.5}}
profiles:
  - id: tone
    notes: '{HOSTILE}'
    rate: [0, 0, 0.5]
    harmonic:
      - {{frequency: 100, amplitude: [1.0, 0.5, 2.0]}}
  - id: noise
    rate: [0, 0, 2.0]
    random:
      psd: {{x3: [[20, 1.0e-3], [2000, 1.0e-3]]}}
    mount: [[20, 1.0], [200, 0.3]]
"""


@pytest.fixture(scope="module")
def bundled_study() -> object:
    """The trade study of the bundled catalogues at 10 deg/h, computed once for the module
    (an immutable result; two tests read it)."""
    return trade_study(api.load(), budget=10 / 3600)


@pytest.fixture
def catalog_file(tmp_path: Path) -> Path:
    path = tmp_path / "a<b>&c.yaml"
    path.write_text(CATALOG, encoding="utf-8")
    return path


def run(*args: str):
    return CliRunner().invoke(cli, [str(a) for a in args], catch_exceptions=False)


def test_report_is_self_contained_and_escaped(catalog_file, tmp_path):
    out = tmp_path / "study.html"
    result = run("report", catalog_file, "--budget", "0.01", "--require", "all", "-o", out)
    assert result.exit_code == 0, result.output  # not met, yet a report is no gate
    html = out.read_text(encoding="utf-8")
    assert html.startswith("<!DOCTYPE html>")
    # Nothing to fetch: no script, no stylesheet link, no src=, no URL but the SVG namespace.
    assert "<script" not in html and "<link" not in html and "src=" not in html
    assert set(re.findall(r"https?://[^\s\"'<>]+", html)) == {"http://www.w3.org/2000/svg"}
    # Catalogue text arrives escaped: the name, the notes and the file name.
    assert HOSTILE not in html and "<b>bold" not in html
    assert "&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; &lt;b&gt;" in html
    assert "a&lt;b&gt;&amp;c.yaml" in html
    # The file's SHA-256, computed here from its bytes.
    assert hashlib.sha256(catalog_file.read_bytes()).hexdigest() in html
    assert "Requirement NOT met" in html and "@media print" in html
    # "awful" saturates (range 1 < 0.5 + 2.0 under the tone, and under the noise): that
    # limits it first (docs/model.md section 9: a saturating sensor fails whatever the criterion).
    assert re.search(r"its range under (tone|noise): saturated:", html)
    assert "exceeds the sensor&#x27;s range" in html
    assert 'class="num fail warn" title="' in html  # the saturated cell is marked ⚠
    for chart in re.findall(r"<svg.*?</svg>", html, flags=re.S):
        ET.fromstring(chart)  # every chart is well-formed XML


def test_report_to_stdout_and_bad_output(catalog_file, tmp_path):
    result = run("report", catalog_file, "--budget", "36deg/h", "-o", "-")
    assert result.exit_code == 0 and result.stdout.startswith("<!DOCTYPE html>")
    bad = run("report", catalog_file, "--budget", "0.01", "-o", tmp_path / "no" / "r.html")
    assert bad.exit_code == 2 and "does not exist" in bad.stderr


def test_report_of_the_bundled_catalogues(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = run("report", "--budget", "10deg/h")
    assert result.exit_code == 0, result.output
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    catalog = api.load()
    for entry in catalog.sensors:
        assert f"<b>{entry.sensor.id}</b>" in html
    for j, entry in enumerate(catalog.profiles):
        assert f'<section class="profile" id="p{j}"><div class="profile-head"><h3>' \
               f"{entry.profile.id}" in html
    # per profile: margins, breakdown, sweep, and a chart of its tones or PSD if it has
    # one (a random part given as RMS, or linear vibration alone, has none to draw);
    # a profile with linear vibration states its linear RMS
    sections = html.split('<section class="profile"')[1:]
    assert len(sections) == len(catalog.profiles)
    for entry, section in zip(catalog.profiles, sections, strict=True):
        p = entry.profile
        drawn = bool(p.harmonic) or (p.random is not None and p.random.psd is not None)
        assert section.count("<svg") >= (4 if drawn else 3), p.id
        if p.acceleration is not None:
            assert "linear vibration, RMS at the sensor" in section, p.id


def test_terms_of_eq16_add_up_to_the_rms(catalog_file):
    """Δ_V(RMS)² = ΣΔ0² + Σ(Δ(q)·Ω_K3^q)² (eq. 16): the breakdown's squares sum to it."""
    study = trade_study(api.load([catalog_file]), budget=0.01)
    squares = term_squares(study)
    assert squares.shape[-1] == len(ADDITIVE_TERMS) + len(MULTIPLICATIVE_TERMS)
    np.testing.assert_allclose(squares.sum(axis=-1), study.analysis.error.rms ** 2,
                               rtol=1e-12, atol=0)
    assert term_names() == [*ADDITIVE_TERMS, "q1·Ω", "q2·Ω²", "q3·Ω³"]


def test_breakdown_of_locked_harmonics_and_linear_vibration_adds_up_to_the_rms(bundled_study):
    """The bundled catalogues have a linear vibration and phase-locked harmonics
    (rotor-harmonics): the breakdown gains g2 = Δ0(6) (docs/model.md section 8) and k3·M3,
    k5·M5 (section 10), and eq. (16)'s squares again sum to Δ_V(RMS)² for every sensor
    given by coefficients (a datasheet sensor's RMS is its envelope's worst case)."""
    study = bundled_study
    a = study.analysis
    assert a.has_linear and any(a.locked)
    names = term_names(a.has_linear, any(a.locked))
    assert names == [*ADDITIVE_TERMS, "g2", "k3", "k5", "q1·Ω", "q2·Ω²", "q3·Ω³"]
    squares = term_squares(study)
    coefficients = [i for i in range(len(a.sensors)) if a.source(i) == "coefficients"]
    np.testing.assert_allclose(squares[coefficients].sum(axis=-1),
                               a.error.rms[coefficients] ** 2, rtol=1e-12, atol=0)
    # without the odd terms the locked profile's RMS would not be reached
    j = a.locked.index(True)
    odd = squares[coefficients, j, 6:8].sum(axis=-1)
    assert np.all(odd > 1e-14 * a.error.rms[coefficients, j] ** 2)


def test_study_matches_select_and_sweeps_the_envelope(catalog_file):
    catalog = api.load([catalog_file])
    study = trade_study(catalog, budget=0.01, method="exact")
    direct = api.select(catalog, budget=0.01)
    np.testing.assert_array_equal(study.selection.margin, direct.margin)
    np.testing.assert_array_equal(study.analysis.error.rms, direct.rms)
    # Envelope: 1.5 × max(|Ω_K3| + peak); tone: 0.5 + 2.0; noise: 2 + 3σ with the
    # mount, so σ ≤ √(1e-3·1980) = 1.41 deg/s and the noise reach is under 6.2.
    half = envelope(catalog, (), None)
    assert half >= 1.5 * 2.5 and half <= 1.5 * (2 + 3 * math.sqrt(1e-3 * 1980))
    assert study.sweep.rates[0] == -half and study.sweep.rates[-1] == half
    assert 0.0 in study.sweep.rates  # odd count: the still carrier is swept
    assert [f.name for f in study.files] == [str(catalog_file)]


def test_log_axes_drop_non_positive_values():
    chart = svg.LineChart("t", "x", "y", [svg.Series("s", [1, 2, 3, 4], [1, 0, -1, 10])],
                          ylog=True).svg()
    ET.fromstring(chart)
    # 1 and 10 survive as isolated points (circles), 0 and -1 break the line
    assert chart.count("<circle") == 2 and "<polyline" not in chart


def test_scale_ticks():
    # decades 1e-3..1e3 on a log axis: 7 ticks, one per decade
    assert svg.Scale(1e-3, 1e3, 0, 100, log=True).ticks() == [10.0 ** e for e in range(-3, 4)]
    # 0..10 linear: step 2 (raw 10/6 = 1.67 → 2), 0, 2, ..., 10
    assert svg.Scale(0, 10, 0, 100).ticks() == [0, 2, 4, 6, 8, 10]


def test_report_html_of_a_study_is_deterministic(catalog_file):
    import datetime as dt

    when = dt.datetime(2026, 1, 2, 3, 4, 5, tzinfo=dt.UTC)
    a = to_html(trade_study(api.load([catalog_file]), budget=0.01, created=when))
    b = to_html(trade_study(api.load([catalog_file]), budget=0.01, created=when))
    assert a == b and "2026-01-02 03:04:05 UTC" in a


def test_sensor_forms_are_shown(valid_file, tmp_path):
    """conftest's mems-a is given by output coefficients (eq. 1), fog-a by coefficients."""
    study = trade_study(api.load([valid_file]), budget=0.01)
    assert study.sensor_forms == ("coefficients", "output coefficients")
    html = to_html(study)
    assert "<b>mems-a</b><br><span class=\"small\">from output coefficients (eq. 1)" in html
    assert "<b>fog-a</b></td>" in html


def test_rate_range_option(catalog_file, tmp_path, monkeypatch):
    bad = run("report", catalog_file, "--budget", "0.01", "--rate-range", "1:2",
              "-o", tmp_path / "r.html")
    assert bad.exit_code == 2 and "START:STOP:COUNT" in bad.stderr
    import gyrovib.api.report.views

    seen = {}
    real = gyrovib.api.report.views.trade_study

    def spy(*args, **kwargs):
        seen.update(kwargs)
        return real(*args, **kwargs)

    monkeypatch.setattr(gyrovib.api.report.views, "trade_study", spy)
    good = run("report", catalog_file, "--budget", "0.01", "--unit", "deg/h",
               "--rate-range", "-3deg/s:3deg/s:7", "-o", tmp_path / "r.html")
    assert good.exit_code == 0
    # 7 rates from -3 to 3 deg/s, passed on in deg/s (the library's unit)
    assert list(seen["sweep_rates"]) == [-3.0, -2.0, -1.0, 0.0, 1.0, 2.0, 3.0]
    # "0.01" is read in --unit: 0.01 deg/h = 0.01/3600 deg/s
    assert seen["budget"] == pytest.approx(0.01 / 3600, rel=1e-12)


positive = st.floats(min_value=1e-300, max_value=1e300, allow_nan=False, allow_infinity=False)


@settings(deadline=None, max_examples=200)
@given(st.lists(positive, min_size=1, max_size=20), st.booleans())
def test_every_plotted_value_lies_inside_the_axes(values, log):
    """extent() pads, never clips; the Scale puts lo at start, hi at stop, ticks inside."""
    lo, hi = svg.extent(values, log)
    scale = svg.Scale(lo, hi, 100.0, 500.0, log)
    for v in values:
        assert 100.0 - 1e-6 <= scale(v) <= 500.0 + 1e-6
    assert scale(lo) == pytest.approx(100.0) and scale(hi) == pytest.approx(500.0)
    assert all(lo * (1 - 1e-9) <= t <= hi * (1 + 1e-9) for t in scale.ticks() if log)


def test_bundled_catalogues_are_named_by_package_path_with_their_hash(bundled_study) -> None:
    # the inputs table names a bundled file gyrovib/catalogs/NAME, not where it is
    # installed; its hash is still that of the file's bytes (hashlib, independently)
    from gyrovib.catalog.loader import bundled_paths

    shown = {f.name: f.sha256 for f in bundled_study.files}
    for path in bundled_paths():
        key = f"gyrovib/catalogs/{path.name} (bundled)"
        assert shown[key] == hashlib.sha256(path.read_bytes()).hexdigest()
    assert not any(str(p.parent) in name for p in bundled_paths() for name in shown)
