"""Renderers of several recordings (docs/fleet.md): ``analyze --recording A --recording B``
as table, JSON, CSV and markdown (each recording as for one, then each sensor's worst),
and the envelope's summary of ``gyrovib profile A B …`` (keys: docs/output.md)."""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from gyrovib import units
from gyrovib.records import Column
from gyrovib.render import recording as one
from gyrovib.render.common import dumps, header
from gyrovib.render.formats import Cell, csv_of, markdown_of

if TYPE_CHECKING:
    from gyrovib.api.fleet.envelope import Envelope
    from gyrovib.api.fleet.run import RecordingsAnalysis
    from gyrovib.api.recordings.analysis import RecordingAnalysis
    from gyrovib.api.recordings.results import RecordingFit


def _name(analysis: Any) -> str:
    return os.path.basename(str(analysis.fit.file))


def _saturated_on(result: RecordingsAnalysis, k: int) -> list[str]:
    return [_name(a) for a in result.analyses if bool(a.saturated[k])]


def to_json(result: RecordingsAnalysis) -> str:
    """``analyze --recording A --recording B --format json``: ``recordings`` (each as the
    one-recording document's ``results``, ``recording``, ``warnings``) and ``worst``."""

    scale = units.scale(result.unit)
    document = header("recording", result.unit)
    document["recordings"] = [
        {"results": one.rows_json(a), "recording": one.recording_info(a.fit, scale),
         "warnings": list(a.fit.warnings)} for a in result.analyses]
    worst = []
    for k, sensor in enumerate(result.sensors):
        i = result.worst[k]
        row = one.rows_json(result.analyses[i])[k] if i >= 0 else {"sensor": sensor}
        worst.append({**row, "recording": _name(result.analyses[i]) if i >= 0 else None,
                      "index": i if i >= 0 else None,
                      "saturated_on": _saturated_on(result, k)})
    document["worst"] = worst
    return dumps(document)


def _in_recording(by_name: list[dict[str, Callable[[int], Any]]],
                  name: str) -> Callable[[tuple[int, int]], Any]:
    """Column ``name`` of a (recording, sensor) row, read from that recording's records."""
    return lambda r: by_name[r[0]][name](r[1])


def to_csv(result: RecordingsAnalysis) -> str:
    """One row per recording × sensor: the one-recording records after ``recording``."""
    first = result.analyses[0].records()
    by_name = [{c.name: c.value for c in a.records()} for a in result.analyses]
    columns = (Column("recording", None, lambda r: _name(result.analyses[r[0]])),
               *(replace(c, value=_in_recording(by_name, c.name)) for c in first))
    return csv_of(columns, [(n, i) for n, a in enumerate(result.analyses)
                            for i in range(len(a.sensors))])


def _worst_cells(result: RecordingsAnalysis) -> tuple[Cell[int], ...]:
    """The table of each sensor's worst recording, one row per sensor (its index); a
    sensor unknown on some recording has no worst: '?'."""
    def of_worst(text: Callable[[RecordingAnalysis, int], str], unknown: str
                 ) -> Callable[[int], str]:
        def cell(k: int) -> str:
            i = result.worst[k]
            return unknown if i < 0 else text(result.analyses[i], k)
        return cell

    return (Cell("sensor", result.sensors.__getitem__),
            Cell("worst Δ_V,rec", of_worst(lambda a, k: one._known(a.recorded[k]), "?")),
            Cell("recording", of_worst(lambda a, k: _name(a), "—")),
            Cell("fitted Δ̄_V", of_worst(lambda a, k: one._known(a.fitted[k]), "?")),
            Cell("ratio", of_worst(lambda a, k: one._fmt(a.ratio[k], 3), "?")),
            Cell("saturated on", lambda k: ", ".join(_saturated_on(result, k)) or "—"))


def to_table(result: RecordingsAnalysis, width: int | None = None, color: bool = False,
             ascii: bool = False) -> str:
    """Each recording's table and honesty table, then each sensor's worst recording (plain
    text: ``width``, ``color`` and ``ascii`` are not used)."""
    n = len(result.analyses)
    parts = [f"recording {i + 1} of {n}: {_name(a)}\n{one.to_table(a)}"
             for i, a in enumerate(result.analyses)]
    out = [f"worst recording per sensor (largest |Δ_V,rec|), {result.unit}",
           *one.plain_table(_worst_cells(result), range(len(result.sensors)),
                            left=(0, 2, 5))]
    return "\n".join(parts) + "\n" + "\n".join(out) + "\n"


def to_markdown(result: RecordingsAnalysis) -> str:
    """Each recording's markdown, then the worst per sensor."""
    out = [one.to_markdown(a) for a in result.analyses]
    table = [f"Worst recording per sensor (largest |Δ_V,rec|, {result.unit})", "",
             markdown_of(_worst_cells(result), range(len(result.sensors)))[:-1]]
    return "\n".join(out) + "\n" + "\n".join(table) + "\n"


def envelope_table(env: Envelope) -> str:
    """``gyrovib profile A B …`` on standard error: each recording's honesty table, then
    what the envelope profile holds of the envelope spectrum, per axis."""
    fit = env.fit
    n = len(env.recordings)
    parts = [f"recording {i + 1} of {n}\n{one.honesty_table(f)}" for i, f in enumerate(env.fits)]
    lines = [f"envelope of {n} recordings: profile {fit.profile_id}, f_c {fit.crossover:g} Hz, "
             f"{fit.duration:.6g} s analysed in all",
             f"{'axis':<5} {'variance (deg/s)²':>18} {'held':>8}"]
    for axis, h, on in zip(one.AXES, fit.honesty, fit.rate_axes, strict=True):
        held = "—" if not math.isfinite(h.held) else f"{100 * h.held:.1f} %"
        variance = one._fmt(h.variance) if on else "?"  # not recorded: unknown
        lines.append(f"{axis:<5} {variance:>18} {held if on else '?':>8}")
    part = fit.angular
    lines.append(f"fitted: {len(part.tones)} tone(s), {len(part.harmonics)} harmonic group(s), "
                 f"mission of {len(fit.mission_rates)} segment(s), mean rate Ω_K = "
                 f"[{one.rate_text(fit)}] deg/s")
    lines.append("variance: of the envelope spectrum over f_c…fs/2 and its lines; held: the "
                 "share of it the fitted profile holds")
    if not all(fit.rate_axes):
        lines.append(one.NOT_RECORDED_NOTE)
    lines += [f"warning: {w}" for w in fit.warnings]
    return "\n".join(parts) + "\n" + "\n".join(lines) + "\n"


def _envelope_axes(fit: RecordingFit) -> dict[str, Any]:
    return {a: {"variance": one._num(h.variance), "held": one._num(h.held)}
            for a, h in zip(one.AXES, fit.honesty, strict=True)}


def profile_json(fit: RecordingFit) -> str:
    """``gyrovib profile RECORDING --format json``: ``recording`` (as ``analyze
    --recording`` writes it), the fit's ``warnings`` and the catalogue text ``profile``."""
    document = header("profile", "deg/s")
    document.update({"recording": one.recording_info(fit), "warnings": list(fit.warnings),
                     "profile_id": fit.profile_id, "profile": fit.yaml})
    return dumps(document)


def envelope_json(env: Envelope) -> str:
    """``gyrovib profile A B … --format json``: ``recordings`` (one entry each, as one
    recording's ``recording`` with its ``profile_id`` and ``warnings``), ``envelope``
    (what its fit holds per axis, and its own ``warnings``) and the catalogue text
    ``profile``."""
    fit = env.fit
    document = header("profile", "deg/s")
    document["recordings"] = [{**one.recording_info(f), "profile_id": f.profile_id,
                               "warnings": list(f.warnings)} for f in env.fits]
    document["envelope"] = {"recordings": len(env.recordings), "profile_id": fit.profile_id,
                            "crossover": fit.crossover, "duration": fit.duration,
                            "mission_segments": len(fit.mission_durations),
                            "axes": _envelope_axes(fit), "warnings": list(fit.warnings)}
    document["profile"] = fit.yaml
    return dumps(document)
