"""Chart text placed by width estimates stays inside its chart (no browser needed).

svg.py has no font metrics: it cuts titles, labels and legend entries to
:func:`gyrovib.render.svg.text_width`, a generous estimate. These tests check,
on every chart of the bundled report, that each text's estimated extent (its
anchor as the report's stylesheet sets it) lies within the chart's viewBox;
tests/test_browser.py checks the same with a real browser's font.
"""

from __future__ import annotations

import html
import re

import pytest

from gyrovib import api
from gyrovib.api.report.views import trade_study
from gyrovib.render.report import to_html
from gyrovib.render.svg import SIZES, WIDTH, fit, text_width

#: text-anchor per class, as report.py's stylesheet sets it (default: start).
ANCHOR = {"tx": "middle", "ty": "end", "xl": "middle", "mr": "end"}
TEXT = re.compile(r'<text x="([-0-9.]+)" y="[-0-9.]+" class="(\w+)"([^>]*)>(.*?)</text>')


def test_fit_cuts_to_the_estimate() -> None:
    assert fit("short", 200, 11) == "short"
    long = "a-sensor-id-much-longer-than-its-room " * 3
    cut = fit(long, 150, 11)
    assert cut.endswith("…") and long.startswith(cut[:-1])
    assert text_width(cut, 11) <= 150 < text_width(long, 11)
    # wide characters count more than narrow ones; bold more than regular
    assert text_width("MMMM", 11) > text_width("iiii", 11)
    assert text_width("Δ_V(RMS)", 13, bold=True) > text_width("Δ_V(RMS)", 13)


@pytest.fixture(scope="module")
def charts() -> list[str]:
    page = to_html(trade_study(api.load(), budget=10 / 3600))
    return re.findall(r"<svg .*?</svg>", page, flags=re.S)


def test_every_chart_text_is_estimated_inside_its_chart(charts: list[str]) -> None:
    assert len(charts) > 50  # 14 profiles × 4 or more, and the worst margins
    for svg in charts:
        for x, klass, rest, text in TEXT.findall(svg):
            if klass == "yl":  # rotated: along the y axis, cut to the plot's height
                continue
            anchor = "end" if 'text-anchor="end"' in rest else ANCHOR.get(klass, "start")
            width = text_width(html.unescape(text), SIZES[klass], bold=klass == "ct")
            start = float(x) - {"start": 0.0, "middle": width / 2, "end": width}[anchor]
            assert start >= 0 and start + width <= WIDTH, (klass, text, start, width)
