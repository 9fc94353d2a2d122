"""The fitted profile of a recording as catalogue YAML (``gyrovib: 1``), with its provenance.

The text is data for the catalogue loader (``gyrovib validate`` accepts it),
so it is built here, beside the fit, and not by a renderer. The carrier
histogram — the fitted mission of docs/model.md section 13 — is a
``missions:`` entry (``<profile id>-mission``: one segment per histogram bin,
its duration and carrier rate), which ``gyrovib mission`` evaluates; the rate
random part's coherences are written as ``[ρ31, ρ32, ρ12]`` (section 12).
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

import numpy as np

from gyrovib.catalog.loader import merge, parse_catalog
from gyrovib.catalog.writer import flow_list, measured, measured_list, measured_table, quoted
from gyrovib.errors import GyrovibError, OptionError, literal
from gyrovib.models.profile import correlation_problem

if TYPE_CHECKING:
    from gyrovib.api.recordings.results import FittedPart, RecordingFit
    from gyrovib.core._types import Table


def _triple(values: object) -> str:
    return measured_list(np.asarray(values, dtype=float).tolist())


def _table(table: Table) -> str:
    return measured_table(*table)


def _coherence(values: object) -> str:
    """``[ρ31, ρ32, ρ12]`` as written, still a correlation matrix once rounded.

    The measured coherences come from one band's cross-spectra, so they form a
    correlation matrix; 6 significant figures can break that by rounding where
    it is nearly singular (e.g. two fully correlated pairs). ρ12 is then held
    inside its feasible interval ρ31·ρ32 ± √((1−ρ31²)(1−ρ32²)) and written
    with more figures.
    """

    r31, r32, r12 = (float(v) for v in np.asarray(values, dtype=float))
    text = _triple((r31, r32, r12))
    r31, r32, written = _read(text)
    if correlation_problem(written, r31, r32) is None:
        return text
    centre = r31 * r32
    half = float(np.sqrt(max((1.0 - r31 * r31) * (1.0 - r32 * r32), 0.0)))
    r12 = float(np.clip(r12, centre - half * (1 - 1e-9), centre + half * (1 - 1e-9)))
    return flow_list((measured(r31), measured(r32), f"{r12:.15g}"))


def _read(text: str) -> tuple[float, float, float]:
    a, b, c = (float(v) for v in text.strip("[]").split(","))
    return a, b, c


def _part(part: FittedPart, indent: str, *, rate: bool) -> list[str]:
    out: list[str] = []
    if part.tones:
        out.append(f"{indent}harmonic:")
        for t in part.tones:
            out.append(f"{indent}  - {{frequency: {measured(t.frequency)}, amplitude: "
                       f"{_triple(t.amplitude)}, phase: {_triple(t.phase)}}}")
    if rate and part.harmonics:
        out.append(f"{indent}harmonics:")
        for h in part.harmonics:
            out.append(f"{indent}  - fundamental: {measured(h.fundamental)}")
            out.append(f"{indent}    orders:")
            for order, amp in zip(h.orders, h.amplitude, strict=True):
                out.append(f"{indent}      - {{order: {order}, amplitude: {_triple(amp)}, "
                           "phase: worst}")
    if any(t is not None for t in part.psd):
        out.append(f"{indent}random:")
        out.append(f"{indent}  psd:")
        for axis, table in zip(("x1", "x2", "x3"), part.psd, strict=True):
            if table is not None:
                out.append(f"{indent}    {axis}: {_table(table)}")
        text = _coherence(part.coherence) if rate else _triple(part.coherence)
        out.append(f"{indent}  coherence: {text}")
    return out


def profile_yaml(fit: RecordingFit, *, independent_tones: bool = False) -> str:
    """The catalogue text of ``fit``'s profile: provenance and mission as comments."""
    base = os.path.basename(fit.file)
    lines = [
        "# Fitted by `gyrovib profile` from a recording (docs/model.md section 13).",
        f"# file: {base}",
        *([f"# source: {fit.source}"] if fit.source is not None else []),
        f"# sha256: {fit.sha256}",
        f"# samples: {fit.samples}; fs: {measured(fit.fs)} Hz; crossover f_c: "
        f"{measured(fit.crossover)} Hz; segments: {fit.segments}; duration analysed: "
        f"{measured(fit.duration)} s",
        "# Rates in deg/s (PSD in (deg/s)^2/Hz), accelerations in g (PSD in g^2/Hz).",
        *_shape_comments(fit),
    ]
    missing = missing_parts(fit)
    lines += missing_comments(missing)
    if fit.angular.harmonics:
        lines.append("# Lines at integer multiples of a fundamental are one phase-locked group; "
                     "their relative phases are unobservable in a PSD, so each order is "
                     "'phase: worst'.")
    lines.append("# The mission is the joint carrier (Omega_K1, Omega_K2, Omega_K3) in at most "
                 "16 groups (docs/model.md sections 12-13):")
    lines.append("# one segment per group, its time in s at its mean rate on every axis, so "
                 "that a sensor on any axis keeps its carrier.")
    lines += [
        "",
        "gyrovib: 1",
        "units:",
        "  rate: deg/s",
        "  acceleration: g",
        "",
        "profiles:",
        f"  - id: {fit.profile_id}",
        f"    name: {quoted('Fitted from ' + base)}",
        f"    rate: {_triple(fit.rate)}",
    ]
    if missing:
        lines.append(f"    not_recorded: [{', '.join(missing)}]")
    lines += _part(fit.angular, "    ", rate=True)
    if fit.linear is not None and (fit.linear.tones or any(t is not None
                                                           for t in fit.linear.psd)):
        lines.append("    acceleration:")
        lines += _part(fit.linear, "      ", rate=False)
    lines += ["", "missions:", f"  - id: {mission_id(fit)}", "    segments:"]
    for rate, t in zip(fit.mission_rates, fit.mission_durations, strict=True):
        lines.append(f"      - {{profile: {fit.profile_id}, duration: {measured(t)}, "
                     f"rate: {_triple(rate)}}}")
    return "\n".join(lines) + "\n"


def missing_parts(fit: RecordingFit) -> tuple[str, ...]:
    """What the fitted recording did not record: rate axes x1, x2, x3 and
    ``acceleration`` (docs/model.md section 13: unknown, never 0)."""
    out = [name for name, on in zip(("x1", "x2", "x3"), fit.rate_axes, strict=True) if not on]
    if fit.linear is None or not np.all(np.isfinite(fit.linear.variance)):
        out.append("acceleration")
    return tuple(out)


def missing_comments(missing: tuple[str, ...]) -> list[str]:
    if not missing:
        return []
    return [f"# Not recorded: {', '.join(missing)}. Unknown, not 0: the profile has no "
            "vibration part for them (a triple",
            "# holds 0 there only because the format has three places), and `not_recorded` "
            "says so: an error",
            "# that depends on them is unknown, and select and mission call its verdict "
            "unverified."]


def _shape_comments(fit: RecordingFit) -> list[str]:
    """How well each fitted random PSD's shape holds (docs/model.md section 13), as comments."""
    out = ["# Shape of each fitted random PSD against the measured one over f_c..fs/2: the "
           "power-weighted",
           "# mean |dB| between them, and the share of the power in bins off by more than 3 dB:"]
    parts = [("rate", fit.angular), ("acceleration", fit.linear)]
    for kind, part in parts:
        if part is None:
            continue
        cells = [f"{axis} {db:.2f} dB, {100 * off:.1f} %"
                 for axis, db, off in zip("XYZ", part.shape_db, part.off_3db, strict=True)
                 if np.isfinite(db)]
        if cells:
            out.append(f"#   {kind}: " + "; ".join(cells))
    return out if len(out) > 2 else []


def mission_id(fit: RecordingFit) -> str:
    """The id of the fitted mission: the profile's, with ``-mission``."""
    return f"{fit.profile_id}-mission"


def with_fitted_profile(catalog: Any, fit: RecordingFit) -> Any:
    """``catalog`` with the fitted profile added (its source named after the recording);
    an id already in the catalogue is refused with a pointer to ``--id``."""

    source = parse_catalog(fit.yaml, f"<fitted from {os.path.basename(fit.file)}>",
                           skip=("sensors",))
    try:
        return merge([*catalog.sources, source])
    except GyrovibError as exc:
        raise OptionError(reason=f"the fitted profile's id {literal(repr(fit.profile_id))} (or "
                                 f"its mission's, {literal(repr(mission_id(fit)))}) is already "
                                 "used in the catalogue: choose another with {profile_id}",
                          others=("profile_id",)) from exc
