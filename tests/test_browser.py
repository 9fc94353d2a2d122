"""The bundled report in a real browser: headless Chromium, started once.

One run of Chromium (``--dump-dom`` and ``--screenshot`` together) loads the
bundled report with the layout probe of ``tests/data/layout.js`` added at its
end. The probe measures the page as shown (1280 px window) and as printed (the
report's print stylesheet, on an A4 landscape page's content width, 277 mm):
what reaches past the page's width, chart text clipped by its chart's edge or
shown smaller than 11 px, and the charts of each profile. The checks are the
issue's (22): nothing overflows the printed page, no clipped label or legend,
chart text ≥ 11 px as displayed, every profile plotted.

Chromium started with ``--enable-logging=stderr --v=0`` writes every console
message of the page (errors, ``Uncaught`` exceptions, refused loads) to
stderr as an ``INFO:CONSOLE`` line; the report has no script and loads
nothing, so the only lines are the probe's own. The probes are checked in the
same run: deliberate faults added after the report (an element wider than the
printed page, a shrunk chart whose text runs past its edge, an undefined
function called) must each be found, and charts at the edges of what
svg.py lays out (long legends, names and labels; markers at the edge) must
show whole. Skipped where no Chromium is installed
(Debian: ``apt-get install chromium``; ``.ci/run`` installs it where it can).
"""

from __future__ import annotations

import html
import json
import re
import shutil
import struct
import subprocess
from pathlib import Path
from typing import Any

import pytest

from gyrovib import api
from gyrovib.api.report.views import trade_study
from gyrovib.render.report import to_html
from gyrovib.render.svg import LineChart, Marker, Series, bar_chart, color, dash, share_chart

CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
CHROMIUM = next(filter(None, map(shutil.which, CANDIDATES)), None)

pytestmark = pytest.mark.skipif(
    CHROMIUM is None,
    reason="no Chromium on PATH (chromium, chromium-browser, google-chrome): "
           "apt-get install chromium to run the browser test",
)

CONSOLE = re.compile(r":CONSOLE[:(]|Uncaught")
WINDOW = (1280, 2000)
PROBE_JS = Path(__file__).parent / "data" / "layout.js"

#: The deliberate faults, after the report: each must be found by the probe.
FAULTS = """
<div data-probe style="width: 1100px">overflow probe: wider than the printed page</div>
<svg data-probe class="chart" viewBox="0 0 100 40" width="50" height="20"
  aria-label="probe chart"><text x="80" y="20" style="font-size: 11px">clipped</text></svg>
"""


def hard_charts() -> str:
    """Charts at the edges of what svg.py lays out, added to the page: they must show
    whole like the report's own. A legend longer than the chart (2 rows, 13 terms;
    20 series), names and labels longer than their room, markers at the right edge."""
    long = "a-sensor-id-much-longer-than-any-room-for-it-{}"
    terms = [f"term {k} with a long name" for k in range(13)]
    charts = [
        share_chart("Error by term: two sensors, thirteen terms", ["s1", long.format(2)], terms,
                    [[1.0] * 13, [0.0] * 12 + [1.0]]),
        LineChart("Twenty series " + "and a very long title " * 5, "x " * 80, "y " * 80,
                  [Series(long.format(k), [1.0, 2.0, 3.0], [k + 1.0, k + 2.0, k + 3.0],
                          color(k), dash(k)) for k in range(20)],
                  markers=(Marker("Δ* = 12.3456 at the right edge, labelled at length", y=20.0),
                           Marker("a tone at the right edge, labelled at length", x=3.0),
                           Marker("a tone at the left edge", x=1.0, row=1))).svg(),
        bar_chart("Bars " * 30, "value " * 40, [long.format(k) for k in range(3)],
                  [1e-3, 2e-3, 4e-3], ["#2ca02c"] * 3,
                  Marker("Δ* = 0.0039999 at the right end", x=4e-3)),
    ]
    return '<section id="hard"><div class="charts">' + "".join(
        f"<figure>{c}</figure>" for c in charts) + "</div></section>"


@pytest.fixture(scope="module")
def page(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    """The bundled report loaded once: screenshot, console lines and the probe's result."""
    assert CHROMIUM is not None
    tmp = tmp_path_factory.mktemp("browser")
    report = to_html(trade_study(api.load(), budget=10 / 3600))
    probe = PROBE_JS.read_text(encoding="utf-8")
    path = tmp / "report.html"
    path.write_text(report.replace(
        "</body>", f"{hard_charts()}{FAULTS}<script>{probe}</script>"
                   "<script>gyrovibUndefinedProbe()</script></body>"), encoding="utf-8")
    png = tmp / "report.png"
    done = subprocess.run(
        [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
         "--no-first-run", "--disable-background-networking", "--disable-component-update",
         "--disable-sync", f"--user-data-dir={tmp / 'profile'}", "--enable-logging=stderr",
         "--v=0", "--dump-dom", f"--screenshot={png}",
         f"--window-size={WINDOW[0]},{WINDOW[1]}", path.resolve().as_uri()],
        capture_output=True, text=True, timeout=180, check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    found = re.search(r'<pre id="gyrovib-layout"[^>]*>(.*?)</pre>', done.stdout, flags=re.S)
    assert found, "the layout probe left no result: " + done.stderr[-2000:]
    return {"png": png.read_bytes(),
            "console": [line for line in done.stderr.splitlines() if CONSOLE.search(line)],
            "layout": json.loads(html.unescape(found.group(1))),
            "profiles": len(api.load().profiles)}


def png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    width, height = struct.unpack(">II", data[16:24])  # IHDR: the first chunk
    return width, height


def report_only(items: list[str]) -> list[str]:
    """The findings in the report itself, the deliberate faults left out."""
    return [item for item in items if not item.startswith("PROBE")]


def test_no_console_message_but_the_probes(page: dict[str, Any]) -> None:
    console = page["console"]
    # the probe's own two lines, and nothing from the report
    assert any('"gyrovib-layout-probe"' in line for line in console), console
    assert any("Uncaught ReferenceError: gyrovibUndefinedProbe" in line
               for line in console), console
    assert len(console) == 2, console


def test_the_screenshot_is_not_blank(page: dict[str, Any]) -> None:
    assert png_size(page["png"]) == WINDOW
    assert len(page["png"]) > 20_000  # a blank page compresses to a few kB


def test_nothing_overflows_the_printed_page(page: dict[str, Any]) -> None:
    printed = page["layout"]["print"]
    assert printed["rules"] > 0  # the print stylesheet was applied
    assert abs(printed["width"] - 277 / 25.4 * 96) < 0.01  # A4 landscape less 2 × 10 mm
    # the probe sees an element wider than the page, and nothing else is
    assert any(item.startswith("PROBE div") for item in printed["overflow"])
    assert report_only(printed["overflow"]) == []
    assert report_only(page["layout"]["screen"]["overflow"]) == []


@pytest.mark.parametrize("mode", ["screen", "print"])
def test_chart_text_is_whole_and_at_least_11_px(page: dict[str, Any], mode: str) -> None:
    found = page["layout"][mode]
    # the probe chart: its text runs past its edge, and at half size is 5.5 px
    assert "PROBE probe chart: 'clipped'" in found["clipped"]
    assert any(item.startswith("PROBE probe chart: 'clipped' 5.5 px") for item in found["small"])
    assert report_only(found["clipped"]) == []
    assert report_only(found["small"]) == []


def test_every_profile_has_a_chart_of_its_vibration(page: dict[str, Any]) -> None:
    for mode in ("screen", "print"):
        charts = page["layout"][mode]["charts"]
        assert len(charts) == page["profiles"]
        for section, titles in charts.items():
            # shown (non-zero size): the margins, breakdown and sweep, and the vibration
            assert len(titles) >= 4, (mode, section, titles)
            assert any(t.startswith(("Spectrum:", "Linear vibration:")) for t in titles), (
                mode, section, titles)
