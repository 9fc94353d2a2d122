"""``sweep``: eq. (13) and (16) over a range of Ω_K3, exact and paper side by side."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from gyrovib import units
from gyrovib.api.datasheet import specs
from gyrovib.api.evaluation.evaluate import ERROR_PARTS, errors, saturation, sources, worst_case
from gyrovib.api.evaluation.results import SweepResult
from gyrovib.api.evaluation.unknown import unknown_cells, unknown_g2
from gyrovib.api.study.convert import error_arrays, to_unit
from gyrovib.api.study.prepare import check_finite, float_guard
from gyrovib.api.study.study import Study, check_peak_factor
from gyrovib.catalog.loader import Catalog
from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import METHODS, VibrationError
from gyrovib.core.saturation import DEFAULT_PEAK_FACTOR
from gyrovib.errors import OptionError

#: Most rates in one sweep: several tones cost about 10^4 kernel values per rate.
MAX_SWEEP_POINTS = 20_000
#: Most sensor × profile × rate cells of one sweep: each holds ~16 values per
#: method in the result (~260 MB at this many), so a long sweep stays under 400 MB.
MAX_SWEEP_CELLS = 1_000_000
#: Most datasheet-sensor × profile × rate × method worst cases of one sweep: each
#: is a linear programme polished from its neighbour's, 0.1-0.2 ms (5-10 s at this many;
#: the default 401-rate sweep of the bundled catalogue is 45,000).
MAX_SWEEP_PROGRAMMES = 50_000


def check_sweep_size(n_sensors: int, n_spec: int, n_profiles: int, n_rates: int) -> None:
    """Refuse, before any computation, a sweep whose result or whose datasheet worst
    cases would exceed :data:`MAX_SWEEP_CELLS` or :data:`MAX_SWEEP_PROGRAMMES`."""
    cells = n_sensors * n_profiles * n_rates
    if cells > MAX_SWEEP_CELLS:
        most = max(1, MAX_SWEEP_CELLS // max(1, n_sensors * n_profiles))
        raise OptionError(argument="rates", reason=(
            f"{n_rates:,} rates × {n_profiles} profiles × {n_sensors} sensors "
            f"are {cells:,} results, more than the {MAX_SWEEP_CELLS:,} one sweep holds "
            f"(~16 values each per method, to stay under 400 MB); sweep at most {most:,} "
            "rates here, or fewer profiles ({profiles}) or sensors ({sensors})"),
            others=("profiles", "sensors"))
    programmes = n_spec * n_profiles * n_rates * len(METHODS)
    if programmes > MAX_SWEEP_PROGRAMMES:
        most = max(1, MAX_SWEEP_PROGRAMMES // max(1, n_spec * n_profiles * len(METHODS)))
        raise OptionError(argument="rates", reason=(
            f"{n_rates:,} rates × {n_profiles} profiles × {n_spec} datasheet "
            f"sensors need {programmes:,} worst cases over their envelopes (a linear "
            f"programme each, both methods), more than the {MAX_SWEEP_PROGRAMMES:,} "
            f"(about 10 s) one sweep may take; sweep at most {most:,} rates here, or fewer "
            "profiles ({profiles}) or datasheet sensors ({sensors})"),
            others=("profiles", "sensors"))


def _check_size(study: Study, n_rates: int, rms_only: bool) -> None:
    """:func:`check_sweep_size` of a sweep of ``study`` (with ``rms_only``, no datasheet
    worst case is a programme per rate)."""
    n_spec = 0 if rms_only else int(specs.spec_index(study.sensors).size)
    check_sweep_size(len(study.sensors), n_spec, len(study.profiles), n_rates)


def rate_range(start: float, stop: float, count: int) -> FloatArray:
    """``count`` evenly spaced rates from ``start`` to ``stop`` inclusive (deg/s)."""
    if count < 1:
        raise OptionError("a rate range needs a count of at least 1")
    if count > MAX_SWEEP_POINTS:
        raise OptionError(
            f"a rate range of {count} points is too many (at most {MAX_SWEEP_POINTS})"
        )
    if not (np.isfinite(start) and np.isfinite(stop) and np.isfinite(stop - start)):
        raise OptionError("a rate range needs finite start and stop, and a finite span")
    out: FloatArray = np.linspace(start, stop, count)
    return out


def sweep(
    catalog: Catalog,
    rates: Sequence[float] | FloatArray,
    *,
    sensors: Sequence[str] = (),
    profiles: Sequence[str] = (),
    unit: str = "deg/s",
    peak_factor: float = DEFAULT_PEAK_FACTOR,
) -> SweepResult:
    """Eq. (13) and (16) at every Ω_K3 of ``rates`` (deg/s), exact and paper.

    One vectorised evaluation per profile and sensor-response group: the
    multipliers are computed for the whole rate array at once. A value at a
    rate equals :func:`~gyrovib.api.analyze` with that ``rate``. Profiles the
    paper's formulas do not cover get NaN paper values and an entry in
    :attr:`SweepResult.paper_refused`; anything that overflows is refused.
    A spec-form sensor gives its worst case over the envelope at each rate (by
    either method's multipliers), and :attr:`SweepResult.worst_coefficients`
    the exact method's worst polynomial at each rate.
    :attr:`SweepResult.saturated` flags the rates where a sensor saturates
    (|Ω_K3| + the vibration's swing at its nonlinear element, κ =
    ``peak_factor``, above its range; docs/model.md section 9).
    """
    omega = _rates(rates)
    check_peak_factor(peak_factor)
    study = Study.of(catalog, sensors=sensors, profiles=profiles)
    return sweep_of(study, omega, unit=unit, peak_factor=peak_factor)


def _rates(rates: Sequence[float] | FloatArray) -> FloatArray:
    omega = np.asarray(rates, dtype=float).reshape(-1)
    if omega.size == 0 or not np.all(np.isfinite(omega)):
        raise OptionError("the swept rates must be finite, and at least one")
    return omega


def _unknown(prepared: Any, spec: Any, exact: VibrationError,
             paper: VibrationError) -> tuple[tuple[str, str], ...]:
    """NaN, in place, where a cell is unknown, as in analyze: a profile fitted from a
    recording that lacks a part the sensor needs, and a g² figure not given under a
    linear vibration (those cells returned as (sensor, profile) ids)."""
    for error in (exact, paper):
        unknown_cells(prepared, error, {})
    cells = specs.unknown_g2_cells(prepared.sensors, spec,
                                   [v is not None for v in prepared.linear])
    for error in (exact, paper):
        unknown_g2(error, None, cells)
    return tuple((prepared.sensors[i].sensor.id, prepared.profiles[j].profile.id)
                 for i, j in cells)


def sweep_of(study: Study, rates: Sequence[float] | FloatArray, *, unit: str = "deg/s",
             peak_factor: float = DEFAULT_PEAK_FACTOR,
             methods: Sequence[str] = METHODS, rms_only: bool = False) -> SweepResult:
    """:func:`sweep` as a view of a :class:`~gyrovib.api.study.study.Study`.

    ``methods``: the methods evaluated; a method left out (the report draws
    one) has NaN in its arrays — unknown, not zero. ``rms_only``: datasheet
    sensors get Δ_V(RMS) (their per-term bound) alone, the rest NaN — the
    worst |Δ_V| over the envelope is a programme per rate, Δ_V(RMS) is not.
    """
    unit = units.canonical_unit(unit)
    omega = _rates(rates)
    _check_size(study, omega.size, rms_only)
    with float_guard():
        # only the paper's refusals leave empty cells; the exact method's is a
        # ModelError at the profile's place in its file, as in analyze
        prepared = study.prepare(omega=omega, methods=methods, tolerate_refusals=("paper",),
                                 peak_factor=peak_factor)
        shape = (len(prepared.sensors), len(prepared.profiles), omega.size)
        refused: dict[int, str] = {}
        for group in prepared.groups:
            refused.update(group.refused.get("paper", {}))
        results = {m: errors(study, prepared, m, omega, rms_only=rms_only) if m in methods else
                   {name: np.full((*shape, *t), np.nan) for name, t in ERROR_PARTS.items()}
                   for m in METHODS}
        spec = (worst_case(study, prepared, "exact", omega, rms_only=rms_only)
                if "exact" in methods else None)
        worst_x = (specs.sweep_fields(len(prepared.sensors), spec, unit) if spec is not None
                   else {"sources": sources(prepared.sensors)})
        exact = to_unit(VibrationError(**results["exact"]), unit, in_place=True)
        paper = to_unit(VibrationError(**results["paper"]), unit, in_place=True)
        checked = (lambda e: [e.rms]) if rms_only else error_arrays
        if "exact" in methods:
            check_finite(checked(exact), prepared)
        if "paper" in methods:
            check_finite(checked(paper), prepared, exclude=sorted(refused))
        g2_cells = _unknown(prepared, spec, exact, paper)
    return SweepResult(
        unit=unit,
        sensors=tuple(e.sensor.id for e in prepared.sensors),
        profiles=tuple(p.profile.id for p in prepared.profiles),
        rates=omega / units.scale(unit),
        exact=exact,
        paper=paper,
        paper_refused={prepared.profiles[j].profile.id: refused[j] for j in sorted(refused)},
        g2_unknown=g2_cells,
        **(worst_x or {}),
        saturated=saturation(prepared, omega).saturated,
        peak_factor=peak_factor,
    )
