"""The mission report's charts (render/report_mission.py, render/svg.py): labels of
nearby tone markers on separate lines, budget bars readable whatever the spread of the
totals, tooltips in deg, and the segments' carrier in the mission file's rate unit."""

from __future__ import annotations

import re

from gyrovib.render.svg import SIZES, WIDTH, LineChart, Marker, Series, text_width

LABEL = re.compile(r'<text x="([-0-9.]+)" y="([-0-9.]+)" class="ml"( text-anchor="end")?>'
                   r"(.*?)</text>")


def _spans(svg: str) -> list[tuple[float, float, float]]:
    """(line y, left, right) of each marker label, from its anchor and estimated width."""
    out = []
    for x, y, end, text in LABEL.findall(svg):
        w = text_width(text, SIZES["ml"])
        left = float(x) - w if end else float(x)
        out.append((float(y), left, left + w))
    return out


def test_labels_of_nearby_tones_do_not_overlap() -> None:
    # an engine's six orders and a blade-pass pair on a log axis: 30 and 36 Hz are 8 px
    # apart, far less than a label's width
    tones = [30.0, 36.0, 60.0, 72.0, 90.0, 120.0, 150.0, 180.0, 9.4]
    chart = LineChart("spectrum", "f (Hz)", "PSD", [Series("psd", [5.0, 400.0], [1e-4, 1e-5])],
                      xlog=True, ylog=True,
                      markers=[Marker(f"{f:g} Hz, a3 = 0.123", x=f, style="tone")
                               for f in tones])
    spans = _spans(chart.svg())
    assert len(spans) == len(tones)
    for i, (y1, a1, b1) in enumerate(spans):
        assert a1 >= 0 and b1 <= WIDTH
        for y2, a2, b2 in spans[i + 1:]:
            assert y1 != y2 or b1 <= a2 or b2 <= a1, (spans[i], (y2, a2, b2))


_CATALOGUE = """\
gyrovib: 1
units: {rate: deg/h}
sensors:
  - id: fine
    coefficients: {A1: 1.0e-6}
    vre: 0
    noise: {arw: 0.01 deg/sqrt(h), bias_instability: 0.01 deg/h, rrw: 0.001 deg/h/sqrt(h),
            bias_repeatability: 0}
  - id: coarse
    coefficients: {A1: 1.0e-3, k2: 1.0e-4}
    vre: 0
    noise: {arw: 3 deg/sqrt(h), bias_instability: 50 deg/h, rrw: 5 deg/h/sqrt(h),
            bias_repeatability: 0}
profiles:
  - id: tone
    rate: [0, 0, 1800]
    harmonic: [{frequency: 40, amplitude: [0, 0, 7200]}]
missions:
  - id: hour
    segments:
      - {profile: tone, duration: 3600, rate: [0, 0, 360]}
"""


def _result():  # type: ignore[no-untyped-def]
    from gyrovib import api
    from gyrovib.catalog.loader import merge, parse_catalog

    return api.mission(merge([parse_catalog(_CATALOGUE, "<c>")]), angle_budget=1.0,
                       coverage=2.0)


def test_budget_bars_keep_each_sensor_readable_and_tooltips_in_deg() -> None:
    from gyrovib.render.report_mission import budget_chart, budget_lengths

    result = _result()
    totals = {r.sensor: sum(budget_lengths(r)) for r in result.rows}
    assert totals["coarse"] > 20 * totals["fine"]  # one axis would flatten "fine"
    svg = budget_chart(result, "hour")
    assert "% of each bar" in svg
    # every part's tooltip is its length in deg (budget_lengths), not a share
    fine = next(r for r in result.rows if r.sensor == "fine")
    from gyrovib.render.common import fmt

    total = fmt(sum(budget_lengths(fine)))
    for value in budget_lengths(fine):
        if value > 0:
            assert f"{fmt(value)} deg of {total} deg</title>" in svg
    # each bar spans the same width: its parts are shares of its own total
    widths: dict[float, float] = {}
    for y, w in re.findall(r'<rect x="[-0-9.]+" y="([-0-9.]+)" width="([-0-9.]+)" '
                           r'height="12" fill=', svg):
        widths[float(y)] = widths.get(float(y), 0.0) + float(w)
    assert len(widths) == 2
    a, b = widths.values()
    assert abs(a - b) < 2.0


def test_segment_rates_in_the_mission_files_unit() -> None:
    from gyrovib.render.report_mission import mission_section

    result = _result()  # output in deg/s, the file's rates in deg/h
    page = mission_section(result, rate_units={"hour": "deg/h"})
    assert "Ω_K3 (deg/h)" in page
    assert ">360<" in page  # the segment's 360 deg/h, not 0.1 deg/s
