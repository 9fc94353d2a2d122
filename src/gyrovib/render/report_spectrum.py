"""The spectrum of a profile in ``gyrovib report``: its charts (the angular spectrum or
tones, random vibration given as RMS, the linear vibration, the isolation mount) as
inline SVG from :mod:`gyrovib.render.svg`, and a one-line summary in words."""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from gyrovib.api.report.views import Spectrum
from gyrovib.render.common import fmt
from gyrovib.render.svg import LineChart, Marker, Series, bar_chart, color, dash


def _psd_series(psd: Iterable[tuple[str, Sequence[float], Sequence[float]]]) -> list[Series]:
    """One line per axis of a PSD, each with its own colour and dash."""
    return [Series(f"PSD {axis}", list(f), list(g), color(k), dash(k))
            for k, (axis, f, g) in enumerate(psd)]


def _tone_markers(tones: Iterable[tuple[float, Sequence[float]]],
                  suffix: str = "") -> list[Marker]:
    """A vertical marker per tone, labelled with its x3 amplitude (+ ``suffix``)."""
    return [Marker(f"{fmt(freq, 3)} Hz, a3 = {fmt(amp[2], 3)}{suffix}", x=freq, style="tone",
                   row=k % 3)
            for k, (freq, amp) in enumerate(tones)]


def _tone_dots(label: str, tones: Sequence[tuple[float, Sequence[float]]]) -> list[Series]:
    """Tones without a spectrum: their x3 amplitudes on the y axis, as dots (a NaN
    after each point keeps them unjoined)."""
    nan = float("nan")
    return [Series(label, [v for t in tones for v in (t[0], nan)],
                   [v for t in tones for v in (t[1][2], nan)], color(0))]


def _frequency_chart(title: str, ylabel: str, series: list[Series],
                     markers: list[Marker]) -> str:
    return LineChart(title, "frequency (Hz)", ylabel, series, xlog=True, ylog=True,
                     markers=markers).svg()


def _angular_chart(spectrum: Spectrum, unit: str) -> str | None:
    """The angular PSD with its tones as markers, or the tones alone as dots."""
    # phase-locked orders (docs/model.md section 10) are lines at n·f0, like tones
    tones = [*spectrum.tones,
             *((n * f0, amp) for f0, orders in spectrum.locked for n, amp in orders)]
    if not (spectrum.psd or tones):
        return None
    series = _psd_series(spectrum.psd)
    if series:
        ylabel = f"PSD ({unit})²/Hz"
    else:
        series = _tone_dots("tone amplitude x3", tones)
        ylabel = f"amplitude ({unit})"
    return _frequency_chart(f"Spectrum: {spectrum.profile}", ylabel, series,
                            _tone_markers(tones))


def _rms_chart(spectrum: Spectrum, unit: str) -> str | None:
    """Random vibration given as RMS per axis (no spectrum): a bar per axis."""
    if spectrum.rms is None or spectrum.psd:
        return None
    return bar_chart(f"Spectrum: {spectrum.profile} (random given as RMS per axis)",
                     f"σ ({unit}, log)", ["x1", "x2", "x3"], list(spectrum.rms),
                     [color(k) for k in range(3)])


def _linear_chart(spectrum: Spectrum) -> str | None:
    """The linear vibration, on its own axes and in its own unit."""
    if not (spectrum.linear_psd or spectrum.linear_tones):
        return None
    lu = spectrum.linear_unit
    series = _psd_series(spectrum.linear_psd)
    if series:
        ylabel = f"PSD ({lu})²/Hz"
    else:
        series = _tone_dots("tone amplitude a3", spectrum.linear_tones)
        ylabel = f"amplitude ({lu})"
    return _frequency_chart(f"Linear vibration: {spectrum.profile}", ylabel, series,
                            _tone_markers(spectrum.linear_tones, f" {lu}"))


def _mount_chart(spectrum: Spectrum) -> str | None:
    """The isolation mount's transmissibility ν(f)."""
    if spectrum.mount is None:
        return None
    f, nu = spectrum.mount
    return LineChart(f"Isolation mount ν(f): {spectrum.profile}", "frequency (Hz)",
                     "transmissibility ν", [Series("mount", list(f), list(nu))],
                     xlog=True, ylog=True).svg()


def spectrum_charts(spectrum: Spectrum, unit: str) -> list[str]:
    """The profile's spectrum charts (SVG), in this order: the angular spectrum, the
    random RMS bars, the linear vibration, the isolation mount; those that apply."""
    charts = (_angular_chart(spectrum, unit), _rms_chart(spectrum, unit),
              _linear_chart(spectrum), _mount_chart(spectrum))
    return [c for c in charts if c is not None]


def _tones_text(spectrum: Spectrum, unit: str) -> str:
    return "tones: " + "; ".join(
        f"{fmt(f, 4)} Hz, amplitude ({', '.join(fmt(a, 3) for a in amp)}) {unit}"
        for f, amp in spectrum.tones)


def _locked_text(spectrum: Spectrum, unit: str) -> str:
    return "phase-locked harmonics: " + "; ".join(
        f"f0 = {fmt(f0, 4)} Hz, orders " + ", ".join(
            f"{n} (a3 = {fmt(amp[2], 3)} {unit})" for n, amp in orders)
        for f0, orders in spectrum.locked)


def spectrum_text(spectrum: Spectrum, unit: str) -> str:
    """The profile's vibration in words, for the line under its title."""
    parts = []
    if spectrum.tones:
        parts.append(_tones_text(spectrum, unit))
    if spectrum.rms is not None:
        parts.append(f"random, σ = ({', '.join(fmt(v, 3) for v in spectrum.rms)}) {unit} "
                     "(given as RMS, no spectrum)")
    if spectrum.psd:
        parts.append("random PSD on " + ", ".join(a for a, _, _ in spectrum.psd))
    if spectrum.mount is not None:
        parts.append("isolation mount")
    if spectrum.locked:
        parts.append(_locked_text(spectrum, unit))
    if spectrum.linear_rms is not None:
        parts.append("linear vibration, RMS at the sensor ("
                     + ", ".join(fmt(v, 3) for v in spectrum.linear_rms) + ") g")
    return "; ".join(parts) or "no vibration"
