"""Small inline-SVG charts for the HTML report, written by hand.

Hand-written rather than matplotlib: the report needs three kinds of chart
(lines on linear or log axes, horizontal bars on a log axis, 100 % stacked
bars), which take a few hundred lines of plain string building; in exchange
``gyrovib report`` works without the optional ``plot`` extra, starts without
importing matplotlib (about a second), writes text that is the same on every
machine (no font metrics, no backend), and the charts stay vector graphics that
scale and print sharply. Every piece of text is escaped.

Coordinates are computed in Python; a chart is a ``<svg>`` element with a
``viewBox`` and its own width and height in px: the report shows it at that
size (scaled down only where the page is narrower), so its text is shown at
the sizes of :data:`SIZES`. There are no font metrics here: text that could
run past the chart's edge is cut to a generous width estimate
(:func:`text_width`). Non-finite values and, on log axes, values ≤ 0
are left out (a line breaks there).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from html import escape

#: Ten distinguishable colours (the "tab10" cycle); more series reuse them dashed.
#: Distinct colours: at least as many as the terms of eq. (16) a report can show
#: (5 additive, g², k3·M3, k5·M5, 3 multiplicative), so no two terms share one.
PALETTE = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
           "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf",
           "#393b79", "#637939", "#843c39")
DASHES = ("", "6 3", "2 2", "8 3 2 3")

WIDTH, HEIGHT = 720, 280
LEFT, RIGHT, TOP, BOTTOM = 72, 190, 30, 44


def color(k: int) -> str:
    return PALETTE[k % len(PALETTE)]


def dash(k: int) -> str:
    return DASHES[(k // len(PALETTE)) % len(DASHES)]


def label(value: float) -> str:
    """A tick label: 3 significant figures, powers of ten as 1e-05."""
    if value == 0:
        return "0"
    if abs(value) >= 1e4 or abs(value) < 1e-3:
        mantissa, exponent = f"{value:.2e}".split("e")
        mantissa = mantissa.rstrip("0").rstrip(".")
        return f"{mantissa}e{int(exponent)}"
    return f"{value:.3g}"


#: Font sizes (px, the chart's own units) of the report's chart text classes; the
#: report's stylesheet sets the same (render/report.py). A chart is shown at its
#: own width (never shrunk), so these are the sizes as displayed.
SIZES = {"ct": 13.0, "xl": 12.0, "yl": 12.0, "tx": 11.0, "ty": 11.0, "lg": 11.0, "ml": 11.0,
         "mr": 11.0}
_NARROW = set("iljtfr.,:;!|'()[] -/1")
_WIDE = set("mwMWΔΩ%@—…")


def text_width(text: str, size: float, bold: bool = False) -> float:
    """A generous estimate of the width of ``text`` at font size ``size`` (px).

    No font metrics here (the text is laid out by the viewer's font): an
    upper bound for common sans-serif fonts, character classes at 0.36, 0.64
    and 0.95 em (bold: 8 % more), so text placed by it is not clipped.
    """
    em = sum(0.36 if c in _NARROW else 0.95 if c in _WIDE or c.isupper() else 0.64
             for c in text)
    return em * size * (1.08 if bold else 1.0)


def fit(text: str, width: float, size: float, bold: bool = False) -> str:
    """``text`` cut short with "…" so that :func:`text_width` is at most ``width``."""
    if text_width(text, size, bold) <= width:
        return text
    while text and text_width(text + "…", size, bold) > width:
        text = text[:-1]
    return text.rstrip() + "…"


@dataclass(frozen=True)
class Scale:
    """Data → pixel along one axis, linear or logarithmic."""

    lo: float
    hi: float
    start: float
    stop: float
    log: bool = False

    def __call__(self, value: float) -> float:
        if self.log:
            a, b, v = math.log10(self.lo), math.log10(self.hi), math.log10(value)
        else:
            a, b, v = self.lo, self.hi, value
        t = 0.5 if b == a else (v - a) / (b - a)
        return self.start + t * (self.stop - self.start)

    def ticks(self) -> list[float]:
        if self.log:
            first, last = math.floor(math.log10(self.lo)), math.ceil(math.log10(self.hi))
            step = max(1, math.ceil((last - first) / 7))
            return [10.0 ** e for e in range(first, last + 1, step)
                    if self.lo * (1 - 1e-9) <= 10.0 ** e <= self.hi * (1 + 1e-9)]
        span = self.hi - self.lo
        if span <= 0:
            return [self.lo]
        raw = span / 6
        power = 10 ** math.floor(math.log10(raw))
        step = next(m * power for m in (1, 2, 2.5, 5, 10) if m * power >= raw)
        first = math.ceil(self.lo / step) * step
        return [first + k * step for k in range(int((self.hi - first) / step + 1e-9) + 1)]


def extent(values: Sequence[float], log: bool) -> tuple[float, float] | None:
    """The plotted range of ``values``: finite ones (and > 0 on a log axis), padded."""
    kept = [v for v in values if math.isfinite(v) and (v > 0 or not log)]
    if not kept:
        return None
    lo, hi = min(kept), max(kept)
    if log:  # whole decades, at least one; in log space so that 1e-300..1e300 works
        a, b = math.log10(lo), math.log10(hi)
        if b - a < 1:
            a, b = (a + b) / 2 - 0.5, (a + b) / 2 + 0.5
        first, last = max(math.floor(a), -307), min(math.ceil(b), 308)
        return 10.0 ** first, 10.0 ** last
    if hi == lo:
        pad = abs(lo) * 0.1 or 1.0
        return lo - pad, hi + pad
    pad = hi * 0.05 - lo * 0.05
    return lo - pad, hi + pad


def _open(title: str, height: int = HEIGHT) -> list[str]:
    """The ``<svg>`` element (``width`` its own: shown unshrunk where there is room) and
    its title, the whole of it in ``<title>``, the visible line cut to the chart's width."""
    shown = fit(title, WIDTH - 16, SIZES["ct"], bold=True)
    return [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {WIDTH} {height}" '
            f'width="{WIDTH}" height="{height}" '
            f'class="chart" role="img" aria-label="{escape(title)}">',
            f'<title>{escape(title)}</title>',
            f'<text x="8" y="18" class="ct">{escape(shown)}</text>']


def _axes(x: Scale, y: Scale, xlabel: str, ylabel: str) -> list[str]:
    out = [f'<rect x="{LEFT}" y="{TOP}" width="{WIDTH - LEFT - RIGHT}" '
           f'height="{HEIGHT - TOP - BOTTOM}" class="frame"/>']
    for t in x.ticks():
        px = x(t)
        out.append(f'<line x1="{px:.1f}" y1="{TOP}" x2="{px:.1f}" y2="{HEIGHT - BOTTOM}" '
                   'class="grid"/>')
        out.append(f'<text x="{px:.1f}" y="{HEIGHT - BOTTOM + 14}" class="tx">'
                   f'{escape(label(t))}</text>')
    for t in y.ticks():
        py = y(t)
        out.append(f'<line x1="{LEFT}" y1="{py:.1f}" x2="{WIDTH - RIGHT}" y2="{py:.1f}" '
                   'class="grid"/>')
        out.append(f'<text x="{LEFT - 4}" y="{py + 4:.1f}" class="ty">{escape(label(t))}</text>')
    xlabel = fit(xlabel, WIDTH - LEFT - RIGHT, SIZES["xl"])
    ylabel = fit(ylabel, HEIGHT - TOP - BOTTOM + 20, SIZES["yl"])
    out.append(f'<text x="{(LEFT + WIDTH - RIGHT) / 2:.0f}" y="{HEIGHT - 6}" class="xl">'
               f'{escape(xlabel)}</text>')
    out.append(f'<text x="14" y="{(TOP + HEIGHT - BOTTOM) / 2:.0f}" class="yl" '
               f'transform="rotate(-90 14 {(TOP + HEIGHT - BOTTOM) / 2:.0f})">'
               f'{escape(ylabel)}</text>')
    return out


#: Vertical step of the legend's entries.
LEGEND_STEP = 15


def legend_bottom(count: int, top: int = TOP) -> int:
    """The lowest y a legend of ``count`` entries reaches: a chart is made at least that
    tall, so that a long legend is not cut off by the chart's edge."""
    return top + 8 + LEGEND_STEP * max(count - 1, 0) + 8


def _legend(names: Sequence[str], styles: Sequence[tuple[str, str]], top: int = TOP) -> list[str]:
    out = []
    for k, (name, (stroke, pattern)) in enumerate(zip(names, styles, strict=True)):
        y = top + 8 + LEGEND_STEP * k
        x = WIDTH - RIGHT + 10
        extra = f' stroke-dasharray="{pattern}"' if pattern else ""
        out.append(f'<line x1="{x}" y1="{y}" x2="{x + 18}" y2="{y}" stroke="{stroke}" '
                   f'stroke-width="2.5"{extra}/>')
        text = fit(name, WIDTH - x - 23 - 4, SIZES["lg"])
        out.append(f'<text x="{x + 23}" y="{y + 4}" class="lg">{escape(text)}</text>')
    return out


@dataclass(frozen=True)
class Series:
    name: str
    x: Sequence[float]
    y: Sequence[float]
    stroke: str = PALETTE[0]
    pattern: str = ""


@dataclass(frozen=True)
class Marker:
    """A vertical (``x``) or horizontal (``y``) reference line with a label."""

    label: str
    x: float | None = None
    y: float | None = None
    style: str = "ref"
    #: Label line, to stagger the labels of nearby markers.
    row: int = 0


@dataclass(frozen=True)
class LineChart:
    title: str
    xlabel: str
    ylabel: str
    series: Sequence[Series]
    xlog: bool = False
    ylog: bool = False
    markers: Sequence[Marker] = field(default_factory=tuple)

    def _extents(self) -> tuple[tuple[float, float] | None, tuple[float, float] | None]:
        """The ranges of the axes: every series' points and every marker's place."""
        xs = [v for s in self.series for v in s.x] + [m.x for m in self.markers if m.x is not None]
        ys = [v for s in self.series for v in s.y] + [m.y for m in self.markers if m.y is not None]
        return extent(xs, self.xlog), extent(ys, self.ylog)

    def svg(self) -> str:
        xr, yr = self._extents()
        # below the plot the right column is free: a long legend runs on there
        out = _open(self.title, max(HEIGHT, legend_bottom(len(self.series))))
        if xr is None or yr is None:
            out.append(f'<text x="{LEFT + 10}" y="{TOP + 30}" class="lg">no value to plot '
                       f'on {"log" if self.ylog else "linear"} axes</text></svg>')
            return "\n".join(out)
        x = Scale(*xr, LEFT, WIDTH - RIGHT, self.xlog)
        y = Scale(*yr, HEIGHT - BOTTOM, TOP, self.ylog)
        out += _axes(x, y, self.xlabel, self.ylabel)
        for s in self.series:
            out += _series_svg(s, x, y, self.xlog, self.ylog)
        for m in _packed(self.markers, x):
            out += _marker_svg(m, x, y)
        out += _legend([s.name for s in self.series], [(s.stroke, s.pattern) for s in self.series])
        out.append("</svg>")
        return "\n".join(out)


def _series_svg(s: Series, x: Scale, y: Scale, xlog: bool, ylog: bool) -> list[str]:
    """A series as polylines, one per run of plottable points (a lone point: a dot)."""
    out = []
    for segment in _segments(s, xlog, ylog):
        points = " ".join(f"{x(a):.1f},{y(b):.1f}" for a, b in segment)
        extra = f' stroke-dasharray="{s.pattern}"' if s.pattern else ""
        if len(segment) == 1:
            (a, b), = segment
            out.append(f'<circle cx="{x(a):.1f}" cy="{y(b):.1f}" r="2.5" '
                       f'fill="{s.stroke}"/>')
        else:
            out.append(f'<polyline points="{points}" fill="none" stroke="{s.stroke}" '
                       f'stroke-width="1.8"{extra}/>')
    return out


def _label_span(text: str, px: float, right: float) -> tuple[float, float]:
    """The horizontal extent (px) :func:`_marker_label` gives a vertical marker's label."""
    width = text_width(text, SIZES["ml"]) + 3
    after, before = right - px - 3, px - 3 - 4
    if width - 3 <= after or after >= before:
        return px, px + min(width, after + 3)
    return px - min(width, before + 3), px


def _packed(markers: Sequence[Marker], x: Scale) -> list[Marker]:
    """The markers with the labels of vertical ones on label lines where none overlaps
    another: each, from the left, on the first line whose labels end before it starts
    (nearby tones on a log axis otherwise write over each other)."""
    ends: list[float] = []
    out = []
    placed = sorted(((x(m.x), k) for k, m in enumerate(markers)
                     if m.x is not None and x.lo <= m.x <= x.hi))
    rows: dict[int, int] = {}
    for px, k in placed:
        lo, hi = _label_span(markers[k].label, px, WIDTH - RIGHT)
        line = next((i for i, end in enumerate(ends) if end + 2 <= lo), len(ends))
        if line == len(ends):
            ends.append(hi)
        ends[line] = hi
        rows[k] = line
    for k, m in enumerate(markers):
        out.append(replace(m, row=rows[k]) if k in rows else m)
    return out


def _marker_svg(m: Marker, x: Scale, y: Scale) -> list[str]:
    """A marker's vertical line (at ``m.x``) and horizontal line (at ``m.y``), each
    with its label, where they fall within the axes."""
    out = []
    if m.x is not None and x.lo <= m.x <= x.hi:
        px = x(m.x)
        out.append(f'<line x1="{px:.1f}" y1="{TOP}" x2="{px:.1f}" '
                   f'y2="{HEIGHT - BOTTOM}" class="{m.style}"/>')
        out.append(_marker_label(m.label, px, TOP + 11 + 11 * m.row, WIDTH - RIGHT))
    if m.y is not None and y.lo <= m.y <= y.hi:
        py = y(m.y)
        out.append(f'<line x1="{LEFT}" y1="{py:.1f}" x2="{WIDTH - RIGHT}" '
                   f'y2="{py:.1f}" class="{m.style}"/>')
        text = fit(m.label, WIDTH - LEFT - RIGHT - 6, SIZES["mr"])
        out.append(f'<text x="{WIDTH - RIGHT - 3}" y="{py - 4:.1f}" class="mr">'
                   f'{escape(text)}</text>')
    return out


def _marker_label(text: str, px: float, y: float, right: float) -> str:
    """A vertical marker's label: right of the line, or left of it (anchored at its end)
    where it would run past ``right`` and there is more room on the left; cut to its room."""
    after, before = right - px - 3, px - 3 - 4
    if text_width(text, SIZES["ml"]) <= after or after >= before:
        return (f'<text x="{px + 3:.1f}" y="{y}" class="ml">'
                f'{escape(fit(text, after, SIZES["ml"]))}</text>')
    return (f'<text x="{px - 3:.1f}" y="{y}" class="ml" text-anchor="end">'
            f'{escape(fit(text, before, SIZES["ml"]))}</text>')


def _segments(s: Series, xlog: bool, ylog: bool) -> list[list[tuple[float, float]]]:
    out: list[list[tuple[float, float]]] = [[]]
    for a, b in zip(s.x, s.y, strict=True):
        ok = (math.isfinite(a) and math.isfinite(b) and (a > 0 or not xlog)
              and (b > 0 or not ylog))
        if ok:
            out[-1].append((float(a), float(b)))
        elif out[-1]:
            out.append([])
    return [seg for seg in out if seg]


def bar_chart(title: str, xlabel: str, names: Sequence[str], values: Sequence[float],
              fills: Sequence[str], reference: Marker | None = None) -> str:
    """Horizontal bars on a log axis (one per name), with an optional vertical reference."""
    row = 18
    top = TOP + 12  # room for the reference label under the title
    height = top + BOTTOM + row * max(len(names), 1)
    xs = [*values, *([reference.x] if reference and reference.x is not None else [])]
    xr = extent(xs, True)
    out = _open(title, height)
    if xr is None:
        out.append(f'<text x="{LEFT + 10}" y="{top + 30}" class="lg">no value to plot</text>'
                   "</svg>")
        return "\n".join(out)
    left = 170
    x = Scale(*xr, left, WIDTH - 40, True)
    bottom = height - BOTTOM
    out.append(f'<rect x="{left}" y="{top}" width="{WIDTH - 40 - left}" '
               f'height="{bottom - top}" class="frame"/>')
    for t in x.ticks():
        px = x(t)
        out.append(f'<line x1="{px:.1f}" y1="{top}" x2="{px:.1f}" y2="{bottom}" class="grid"/>')
        out.append(f'<text x="{px:.1f}" y="{bottom + 14}" class="tx">{escape(label(t))}</text>')
    for k, (name, value, fill) in enumerate(zip(names, values, fills, strict=True)):
        y = top + row * k
        text = fit(name, left - 5 - 4, SIZES["ty"])
        out.append(f'<text x="{left - 5}" y="{y + 13}" class="ty">{escape(text)}</text>')
        if math.isnan(value):  # unknown (an axis not recorded): never drawn as 0
            out.append(f'<text x="{left + 4}" y="{y + 13}" class="lg">?</text>')
        elif value > 0:
            end = min(max(x(value), left), WIDTH - 40) if math.isfinite(value) else WIDTH - 40
            out.append(f'<rect x="{left}" y="{y + 3}" width="{end - left:.1f}" height="{row - 6}" '
                       f'fill="{fill}"/>')
            if not math.isfinite(value):
                out.append(f'<text x="{end - 4}" y="{y + 13}" class="ty">∞</text>')
        else:
            out.append(f'<text x="{left + 4}" y="{y + 13}" class="lg">0</text>')
    if reference is not None and reference.x is not None:
        px = x(reference.x)
        out.append(f'<line x1="{px:.1f}" y1="{top - 4}" x2="{px:.1f}" y2="{bottom}" '
                   f'class="{reference.style}"/>')
        out.append(_marker_label(reference.label, px, top - 6, WIDTH - 4))
    middle = (left + WIDTH - 40) / 2  # centred there: as wide as twice its nearer edge
    xlabel = fit(xlabel, 2 * min(middle - 8, WIDTH - 8 - middle), SIZES["xl"])
    out.append(f'<text x="{middle:.0f}" y="{height - 6}" class="xl">{escape(xlabel)}</text>')
    out.append("</svg>")
    return "\n".join(out)


def share_chart(title: str, names: Sequence[str], parts: Sequence[str],
                shares: Sequence[Sequence[float]]) -> str:
    """100 % stacked horizontal bars: row k splits into ``shares[k]`` (summing to 1 or 0;
    a row with a NaN part, unknown, says so instead of a bar)."""
    row = 18
    height = max(TOP + BOTTOM + row * max(len(names), 1), legend_bottom(len(parts)))
    left, right = 170, WIDTH - RIGHT - 10
    out = _open(title, height)
    bottom = height - BOTTOM
    for k, name in enumerate(names):
        y = TOP + row * k
        text = fit(name, left - 5 - 4, SIZES["ty"])
        out.append(f'<text x="{left - 5}" y="{y + 13}" class="ty">{escape(text)}</text>')
        start = float(left)
        total = sum(v for v in shares[k] if math.isfinite(v))
        if any(v != v for v in shares[k]):  # a part unknown (NaN): so is every share
            out.append(f'<text x="{left + 4}" y="{y + 13}" class="lg">? unknown</text>')
            continue
        if total <= 0:
            out.append(f'<text x="{left + 4}" y="{y + 13}" class="lg">no error</text>')
            continue
        for p, value in enumerate(shares[k]):
            if not math.isfinite(value) or value <= 0:
                continue
            w = (right - left) * value / total
            out.append(f'<rect x="{start:.1f}" y="{y + 3}" width="{w:.1f}" height="{row - 6}" '
                       f'fill="{color(p)}"><title>{escape(name)}: {escape(parts[p])} '
                       f'{100 * value / total:.1f} %</title></rect>')
            start += w
    for t in (0, 0.25, 0.5, 0.75, 1.0):
        px = left + t * (right - left)
        out.append(f'<text x="{px:.1f}" y="{bottom + 14}" class="tx">{100 * t:.0f} %</text>')
    out += _legend(list(parts), [(color(p), "") for p in range(len(parts))])
    out.append(f'<text x="{(left + right) / 2:.0f}" y="{height - 6}" class="xl">share of '
               "Δ_V(RMS)² (eq. 16)</text>")
    out.append("</svg>")
    return "\n".join(out)


def stacked_bar_chart(title: str, xlabel: str, names: Sequence[str], parts: Sequence[str],
                      lengths: Sequence[Sequence[float]], open_end: Sequence[bool],
                      reference: Marker | None = None,
                      tips: Sequence[Sequence[str]] | None = None) -> str:
    """Horizontal bars on a linear axis from 0, row k made of ``lengths[k]`` end to end
    (one colour per part, legend at the right); ``open_end[k]``: the bar is a lower
    bound, drawn with a '≥ ?' past its end. An optional vertical reference line.
    ``tips[k][p]``: the tooltip's value of part p of row k (default: its length)."""
    row = 18
    top = TOP + 12
    height = max(top + BOTTOM + row * max(len(names), 1), legend_bottom(len(parts), top))
    left, right = 170, WIDTH - RIGHT - 10
    totals = [sum(v for v in r if math.isfinite(v) and v > 0) for r in lengths]
    hi = max([*totals, *([reference.x] if reference and reference.x is not None else []), 0.0])
    out = _open(title, height)
    if hi <= 0:
        out.append(f'<text x="{left}" y="{top + 30}" class="lg">no value to plot</text></svg>')
        return "\n".join(out)
    x = Scale(0.0, hi * 1.08, left, right)
    bottom = height - BOTTOM
    out.append(f'<rect x="{left}" y="{top}" width="{right - left}" height="{bottom - top}" '
               'class="frame"/>')
    for t in x.ticks():
        px = x(t)
        out.append(f'<line x1="{px:.1f}" y1="{top}" x2="{px:.1f}" y2="{bottom}" class="grid"/>')
        out.append(f'<text x="{px:.1f}" y="{bottom + 14}" class="tx">{escape(label(t))}</text>')
    for k, name in enumerate(names):
        out += _stacked_row(name, parts, lengths[k], open_end[k], x, top + row * k, row,
                            None if tips is None else tips[k])
    if reference is not None and reference.x is not None:
        px = x(reference.x)
        out.append(f'<line x1="{px:.1f}" y1="{top - 4}" x2="{px:.1f}" y2="{bottom}" '
                   f'class="{reference.style}"/>')
        out.append(_marker_label(reference.label, px, top - 6, WIDTH - 4))
    out += _legend(list(parts), [(color(p), "") for p in range(len(parts))], top)
    out.append(f'<text x="{(left + right) / 2:.0f}" y="{height - 6}" class="xl">'
               f'{escape(fit(xlabel, right - left, SIZES["xl"]))}</text>')
    out.append("</svg>")
    return "\n".join(out)


def _stacked_row(name: str, parts: Sequence[str], lengths: Sequence[float], open_end: bool,
                 x: Scale, y: float, row: int, tips: Sequence[str] | None = None) -> list[str]:
    """One bar of :func:`stacked_bar_chart`: its name, its parts end to end, '≥ ?'."""
    out = [f'<text x="{x.start - 5}" y="{y + 13}" class="ty">'
           f'{escape(fit(name, x.start - 9, SIZES["ty"]))}</text>']
    start = 0.0
    for p, value in enumerate(lengths):
        if not math.isfinite(value) or value <= 0:
            continue
        a, b = x(start), x(start + value)
        out.append(f'<rect x="{a:.1f}" y="{y + 3}" width="{max(b - a, 0.5):.1f}" '
                   f'height="{row - 6}" fill="{color(p)}"><title>{escape(name)}: '
                   f'{escape(parts[p])} {escape(label(value) if tips is None else tips[p])}'
                   '</title></rect>')
        start += value
    if open_end:
        out.append(f'<text x="{x(start) + 3:.1f}" y="{y + 13}" class="lg">≥ ?</text>')
    return out
