"""``mission``: every sensor over every mission (docs/model.md section 12).

Each segment s is a profile p_s flown for T_s seconds at the carrier rate
Ω_K,s (the segment's ``rate``, else the profile's own), in the sensor axes of
the mission's placement (:func:`gyrovib.api.placement.placement.place_profile`). The
distinct (placement, profile, rate) triples are evaluated together in one
:func:`gyrovib.api.analyze` call (so a profile flown in several segments is
prepared once per rate), and :func:`gyrovib.core.mission.totals` gives the
mean error Δ̄_V, the angle θ_V, the mean RMS Δ̄_RMS and the worst segment.

A spec-form (datasheet) sensor's mean error is the worst case over its envelope
of the whole mission: the mission's Δ̄_V is one linear functional of the
conversion function (:func:`gyrovib.core.mission.combined_functional` of the
segments' term functionals, and the g² moments weighted likewise), so it is one
more programme of docs/model.md section 11 (:func:`gyrovib.core.envelope.worst_case`),
never larger than the duration-weighted sum of the per-segment worst cases.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from gyrovib import units
from gyrovib.api.commands.analyze import analysis_of
from gyrovib.api.datasheet import spec_bounds, specs
from gyrovib.api.evaluation.unknown import any_missing, depends_on
from gyrovib.api.missions.results import MissionResult, MissionRow, SegmentResult
from gyrovib.api.placement.placement import place_profile
from gyrovib.api.study.prepare import float_guard
from gyrovib.api.study.study import Study, check_peak_factor
from gyrovib.catalog.loader import Catalog, MissionEntry, ProfileEntry
from gyrovib.core import placement as placements
from gyrovib.core.envelope import worst_case
from gyrovib.core.mission import ANGLE_IN_RAD, ANGLE_UNITS, combined_functional, totals
from gyrovib.core.placement import Placement
from gyrovib.errors import ModelError, OptionError
from gyrovib.frozen import Frozen
from gyrovib.limits import DEFAULT_PEAK_FACTOR
from gyrovib.models import Mission
from gyrovib.models.mission import MAX_DURATION, MAX_DURATION_YEARS

if TYPE_CHECKING:
    from gyrovib.api.evaluation.results import AnalysisResult
    from gyrovib.api.study.prepare import Group, Prepared


@dataclass(frozen=True, eq=False, repr=False)
class _Run(Frozen):
    """One mission in one placement: the columns of its segments in the analysis."""

    mission: Mission
    placement: Placement
    triad: bool
    columns: tuple[int, ...]
    durations: tuple[float, ...]


def chosen_missions(catalog: Catalog, missions: Sequence[str] = ()) -> tuple[MissionEntry, ...]:
    """The missions named (all when none are), in catalogue order."""
    if not catalog.missions:
        files = ", ".join(s.name for s in catalog.sources) or "the catalogue"
        raise OptionError(f"no missions in {files}: give a file with 'missions:' (or no FILE "
                          "at all for the bundled catalogues)")
    ids = [e.mission.id for e in catalog.missions]
    unknown = [m for m in dict.fromkeys(missions) if m not in ids]
    if unknown:
        raise OptionError(f"unknown mission {unknown[0]!r}; known: {', '.join(ids)}")
    if not missions:
        return catalog.missions
    wanted = set(missions)
    return tuple(e for e in catalog.missions if e.mission.id in wanted)


def _placements(entry: MissionEntry, override: Placement | tuple[Placement, ...] | None
                ) -> tuple[tuple[Placement, ...], bool]:
    """The mission's placements (``override``, else its own), and whether they are a triad."""
    chosen = placements.parse(entry.mission.placement_text) if override is None else override
    return (chosen, True) if isinstance(chosen, tuple) else ((chosen,), False)


def _segment_entries(catalog: Catalog, chosen: Sequence[MissionEntry],
                     override: Placement | tuple[Placement, ...] | None
                     ) -> tuple[list[ProfileEntry], list[_Run]]:
    """The distinct placed profiles (ids made unique) and each run's columns among them."""
    by_id = {e.profile.id: e for e in catalog.profiles}
    keys: dict[tuple[Placement, str, tuple[float, ...] | None], int] = {}
    entries: list[ProfileEntry] = []
    runs: list[_Run] = []
    for m in chosen:
        places, triad = _placements(m, override)
        for placement in places:
            columns = []
            for seg in m.mission.segments:
                rate = None if seg.rate is None else tuple(
                    float(v) * units.scale(m.unit) for v in seg.rate)  # deg/s, vehicle axes
                key = (placement, seg.profile, rate)
                if key not in keys:
                    base = by_id[seg.profile]
                    profile = base.profile
                    if rate is not None:
                        s = units.scale(base.unit)
                        profile = profile.model_copy(
                            update={"rate": tuple(v / s for v in rate)})
                    profile = place_profile(profile, placement).model_copy(
                        update={"id": f"{seg.profile}#{len(entries)}"})
                    keys[key] = len(entries)
                    entries.append(ProfileEntry(base.source, base.index, profile))
                columns.append(keys[key])
            runs.append(_Run(m.mission, placement, triad, tuple(columns),
                             tuple(float(s.duration) for s in m.mission.segments)))
    return entries, runs


def angle_in_rad(text: str) -> float:
    """An angle with its unit (``"0.5deg"``, ``"2 mrad"``, ``"30 arcmin"``) in radians;
    positive and finite. Raises :class:`ValueError` with a message for the user."""

    m = re.match(r"^\s*([-+]?(?:[0-9]*\.?[0-9]+)(?:[eE][-+]?[0-9]+)?)\s*([A-Za-zµ]+)\s*$",
                 text)
    if m is None or m.group(2) not in ANGLE_IN_RAD:
        raise ValueError(f"give a number with an angle unit ({', '.join(ANGLE_IN_RAD)}), "
                         "e.g. 0.5deg or '2 mrad'")
    value = float(m.group(1)) * ANGLE_IN_RAD[m.group(2)]
    if not (math.isfinite(value) and value > 0):
        raise ValueError("the angle budget must be positive")
    return value


def angle_unit(unit: str) -> str:
    """deg for deg/s and deg/h, rad for rad/s, rev for rpm."""
    return ANGLE_UNITS[units.canonical_unit(unit)][0]


def mission(
    catalog: Catalog,
    *,
    missions: Sequence[str] = (),
    sensors: Sequence[str] = (),
    budget: float | None = None,
    angle_budget: float | None = None,
    unit: str = "deg/s",
    require: str = "any",
    placement: Placement | tuple[Placement, ...] | None = None,
    peak_factor: float = DEFAULT_PEAK_FACTOR,
    assume_unknown: str = "none",
) -> MissionResult:
    """Every chosen sensor over every chosen mission (docs/model.md section 12).

    ``budget``: Δ* on the mean RMS Δ̄_RMS, in deg/s; ``angle_budget``: θ* on
    |θ_V|, in radians (at most one of the two). ``unit``: the output rate unit
    (the angle is in deg, rad or rev: :func:`angle_unit`). ``placement``
    replaces every mission's own (a :class:`~gyrovib.core.placement.Placement`
    or the :data:`~gyrovib.core.placement.TRIAD`). A sensor passes a mission
    when no segment saturates it and the budget is met, on every axis of a triad.

    Unknown is not zero (docs/model.md section 11, as ``select``): a datasheet
    sensor that passes on its published figures while an unpublished one can
    decide it in some segment (the VRE under linear vibration; m31, m32 under
    cross-axis vibration correlated with x3) is ``unverified`` there, not
    passing (:func:`gyrovib.api.datasheet.spec_bounds.is_unverified`), unless
    ``assume_unknown="zero"``.
    """
    _check_options(budget, angle_budget, require, assume_unknown)
    unit = units.canonical_unit(unit)
    a_unit, a_factor = ANGLE_UNITS[unit]
    chosen = chosen_missions(catalog, missions)
    notes = duration_notes(chosen)
    runs, evaluated = _evaluate(catalog, chosen, sensors, placement, unit, peak_factor)
    limits = _Limits(
        theta=None if angle_budget is None else angle_budget / _rad_per(a_unit),
        rms=None if budget is None else budget / units.scale(unit))
    rows: list[MissionRow] = []
    for i in range(len(evaluated.result.sensors)):
        rows.extend(_with_worst_axis(
            [_mission_row(evaluated, i, r, run, a_factor, limits, assume_unknown)
             for r, run in enumerate(runs)]))
    check_angles(rows, chosen)
    sensor_pass, met = _requirement(rows, evaluated.result.sensors,
                                    budget is None and angle_budget is None, require)
    return MissionResult(unit=unit, angle_unit=a_unit, budget=limits.rms,
                         angle_budget=limits.theta, require=require,
                         sensors=evaluated.result.sensors,
                         missions=tuple(m.mission.id for m in chosen), rows=tuple(rows),
                         sensor_pass=sensor_pass, requirement_met=met,
                         assume_unknown=assume_unknown, notes=notes)


def _check_options(budget: float | None, angle_budget: float | None, require: str,
                   assume_unknown: str) -> None:
    """The option errors of :func:`mission`, in the order the user reads them."""
    if budget is not None and angle_budget is not None:
        raise OptionError(reason="give {budget} (on the mean RMS) or {angle_budget} (on the "
                                 "angle), not both", others=("budget", "angle_budget"))
    if require not in ("any", "all"):
        raise OptionError(argument="require", value=repr(require), reason="use any or all")
    spec_bounds.check_assumption(assume_unknown)


@dataclass(frozen=True, eq=False, repr=False)
class _Evaluated(Frozen):
    """The analysis of the runs' distinct placed profiles (a column each), per sensor:
    its saturation flags, each sensor's source, and the spec-form sensors' mission
    worst means and unknown figures per (sensor, run) (:func:`_spec_means`)."""

    result: AnalysisResult
    saturated: np.ndarray
    sources: tuple[str, ...]
    spec_mean: dict[tuple[int, int], float]
    unknown: dict[tuple[int, int], tuple[str, ...]]


@dataclass(frozen=True, eq=False, repr=False)
class _Limits(Frozen):
    """The budget in the output units: θ* on |θ_V| or Δ* on Δ̄_RMS (or neither)."""

    theta: float | None
    rms: float | None

    def passed(self, saturated: bool, angle: float, rms: float) -> bool | None:
        """Whether a row meets the budget (None: no budget)."""
        if self.theta is not None:
            return not saturated and abs(angle) <= self.theta
        if self.rms is not None:
            return not saturated and rms <= self.rms
        return None


def _evaluate(catalog: Catalog, chosen: Sequence[MissionEntry], sensors: Sequence[str],
              placement: Placement | tuple[Placement, ...] | None, unit: str,
              peak_factor: float) -> tuple[list[_Run], _Evaluated]:
    """The runs of the chosen missions and one analysis of all their segments."""

    entries, runs = _segment_entries(catalog, chosen, placement)
    derived = Catalog(catalog.sources, catalog.sensors, tuple(entries), catalog.allocation,
                      catalog.missions)
    check_peak_factor(peak_factor)
    # one Study of the segments' distinct placed profiles: the analysis and the
    # datasheet sensors' mission worst cases share its vibrations
    study = Study.of(derived, sensors=sensors, profiles=[e.profile.id for e in entries])
    result = analysis_of(study, unit=unit, peak_factor=peak_factor,
                         g2_unknown_as_zero=True)
    saturated = (np.zeros(result.error.total.shape, dtype=bool) if result.saturated is None
                 else np.asarray(result.saturated))
    sources = tuple(result.sources or ("coefficients",) * len(result.sensors))
    spec_mean, unknown = _spec_means(study, sources, runs, unit)
    return runs, _Evaluated(result, saturated, sources, spec_mean, unknown)


def _segment_results(evaluated: _Evaluated, i: int, run: _Run) -> tuple[SegmentResult, ...]:
    """Sensor ``i``'s result in each segment of ``run``."""
    result, saturated = evaluated.result, evaluated.saturated
    total, rms = result.error.total, result.error.rms
    return tuple(
        SegmentResult(profile=seg.profile, duration=float(seg.duration),
                      rate=(float(result.rates[c, 0]), float(result.rates[c, 1]),
                            float(result.rates[c, 2])),
                      total=float(total[i, c]), rms=float(rms[i, c]),
                      saturated=bool(saturated[i, c]))
        for seg, c in zip(run.mission.segments, run.columns, strict=True))


def _mission_row(evaluated: _Evaluated, i: int, r: int, run: _Run, a_factor: float,
                 limits: _Limits, assume_unknown: str) -> MissionRow:
    """Sensor ``i`` over run ``r``: its mean, angle, mean RMS, worst segment and verdict."""
    cols = list(run.columns)
    error = evaluated.result.error
    agg = totals(run.durations, error.total[i, cols], error.rms[i, cols], a_factor)
    mean = float(agg.mean)
    if (i, r) in evaluated.spec_mean:
        mean = evaluated.spec_mean[(i, r)]
    names = evaluated.unknown.get((i, r), ())
    gap = any_missing(names)  # a segment's recording lacks what this error needs
    angle = mean * agg.duration * a_factor
    rms, worst = float(agg.rms), float(agg.worst_total)
    if gap:  # unknown, never the number computed with 0 there (docs/model.md section 13)
        mean = angle = rms = worst = math.nan
    sat = bool(np.any(evaluated.saturated[i, cols]))
    passed = limits.passed(sat, angle, rms)
    open_ = passed is not None and (gap or spec_bounds.is_unverified(
        passed, names, assume_unknown))
    if open_:
        passed = False
    w = int(agg.worst_index)
    return MissionRow(
        sensor=evaluated.result.sensors[i], mission=run.mission.id,
        placement="triad" if run.triad else str(run.placement),
        axis=run.placement.axis if run.triad else None,
        mean=mean, angle=angle, rms=rms, worst_index=w,
        worst_profile=run.mission.segments[w].profile,
        worst_total=worst, segments=_segment_results(evaluated, i, run),
        saturated=sat, passed=passed, source=evaluated.sources[i], unknown=names,
        unverified=open_)


def _requirement(rows: Sequence[MissionRow], sensors: Sequence[str], no_budget: bool,
                 require: str) -> tuple[tuple[bool | None, ...], bool]:
    """Whether each sensor passes every mission (None: no budget), and whether the
    ``require`` condition (any or all of them) is met (always, with no budget)."""
    if no_budget:
        return tuple(None for _ in sensors), True
    sensor_pass = tuple(all(bool(r.passed) for r in rows if r.sensor == s) for s in sensors)
    return sensor_pass, (all if require == "all" else any)(sensor_pass)


def _duration_place(entry: MissionEntry, segment: int) -> tuple[object, ...]:
    return ("missions", entry.index, "segments", segment, "duration")


def duration_notes(chosen: Sequence[MissionEntry]) -> tuple[str, ...]:
    """A warning per segment longer than :data:`~gyrovib.models.mission.MAX_DURATION`
    (100 years: a typo, surely), at its ``duration``; raises :class:`ModelError` where a
    mission's durations sum beyond double precision (Σ T_s would be inf and every mean
    and angle meaningless)."""
    notes: list[str] = []
    for entry in chosen:
        durations = [float(s.duration) for s in entry.mission.segments]
        if not math.isfinite(sum(durations)):  # a float sum overflows to inf, not raises
            raise ModelError(entry.source.problem(
                f"mission {entry.mission.id!r}: its durations add up to more than double "
                f"precision holds (about 1.8e308 s); no mean or angle can be computed: "
                f"check the durations (seconds unless written with min or h)",
                _duration_place(entry, 0)), reason="mission duration overflows")
        for k, seconds in enumerate(durations):
            if seconds > MAX_DURATION:
                notes.append(str(entry.source.problem(
                    f"mission {entry.mission.id!r}, segment {k + 1}: {seconds:.6g} s "
                    f"({seconds / MAX_DURATION * MAX_DURATION_YEARS:.5g} years) is longer "
                    f"than {MAX_DURATION_YEARS} years: a typo? (durations are in seconds "
                    "unless written with min or h)", _duration_place(entry, k))))
    return tuple(notes)


def check_angles(rows: Sequence[MissionRow], chosen: Sequence[MissionEntry]) -> None:
    """Raise :class:`ModelError` at the first segment of a mission whose mean error or
    angle θ_V = Σ T_s·Δ_V,s overflowed (a finite Σ T_s times an error can still be inf)."""
    by_id = {e.mission.id: e for e in chosen}
    bad = next((r for r in rows if not (math.isfinite(r.angle) and math.isfinite(r.mean))
                and not any_missing(r.unknown)), None)  # unknown (NaN) is not overflow
    if bad is None:
        return
    raise ModelError(by_id[bad.mission].source.problem(
        f"mission {bad.mission!r}, sensor {bad.sensor!r}: the angle θ_V = Σ T_s·Δ_V,s "
        "overflows floating point; check the durations (seconds unless written with min "
        "or h)", _duration_place(by_id[bad.mission], 0)),
        reason="mission angle overflows")


def _rad_per(angle_unit_name: str) -> float:

    return ANGLE_IN_RAD[angle_unit_name]


def _with_worst_axis(rows: list[MissionRow]) -> list[MissionRow]:
    """A triad's three rows of one mission name the axis of the largest |θ_V|."""

    out: list[MissionRow] = []
    k = 0
    while k < len(rows):
        row = rows[k]
        if row.axis is None:
            out.append(row)
            k += 1
            continue
        group = [r for r in rows[k:k + 3]]
        # an axis whose θ_V is unknown may be the worst: then the worst axis is unknown
        worst = (None if any(math.isnan(r.angle) for r in group)
                 else max(group, key=lambda r: (r.saturated, abs(r.angle))).axis)
        out.extend(replace(r, worst_axis=worst) for r in group)
        k += 3
    return out


def _spec_means(study: Study, sources: Sequence[str], runs: Sequence[_Run],
                unit: str) -> tuple[dict[tuple[int, int], float],
                                    dict[tuple[int, int], tuple[str, ...]]]:
    """(sensor, run) → a spec-form sensor's worst mean error over the whole mission, and
    the unknown figures that can decide it in some segment (none: no entry): a
    datasheet part's unpublished ones, and a coefficient sensor's g² figure not given.

    One :func:`~gyrovib.core.envelope.worst_case` per sensor group and run, on the
    mission's functional Σ T_s c_s / Σ T_s and g² moment Σ T_s S_s / Σ T_s; the
    unknown figures are :func:`gyrovib.api.datasheet.spec_bounds.unknown_figures_at` of the
    run's segments, merged. The datasheet sensors are ``study`` narrowed to them (its
    vibrations computed once for the analysis and for this).
    """
    out: dict[tuple[int, int], float] = {}
    unknown = _g2_unknown(study, sources, runs)
    for key, parts in _not_recorded(study, runs).items():
        unknown[key] = (*parts, *unknown.get(key, ()))
    rows = [i for i, src in enumerate(sources) if src == "specs"]
    if not rows:
        return out, unknown

    where = {e.sensor.id: i for i, e in enumerate(study.sensors)}
    scale = units.scale(unit)
    with float_guard():
        prepared = study.narrowed(rows).prepare(methods=("exact",), phase_search=True)
        for key, names in _spec_unknown(prepared, runs, where).items():
            unknown[key] = (*unknown.get(key, ()), *names)
        for group in prepared.groups:
            out.update(_group_means(prepared, group, runs, where, scale))
    return out, unknown


def _g2_unknown(study: Study, sources: Sequence[str], runs: Sequence[_Run]
                ) -> dict[tuple[int, int], tuple[str, ...]]:
    """A coefficient-form sensor that gives no g² figure: its g² term is unknown, not
    zero, in a run with linear vibration in some segment (as select reads it)."""

    unknown: dict[tuple[int, int], tuple[str, ...]] = {}
    for i, e in enumerate(study.sensors):
        if sources[i] != "specs" and specs.g2_unknown(e.sensor):
            for r, run in enumerate(runs):
                if any(study.linear[c] is not None for c in run.columns):
                    unknown[(i, r)] = ("vre",)
    return unknown


def _not_recorded(study: Study, runs: Sequence[_Run]) -> dict[tuple[int, int], tuple[str, ...]]:
    """(sensor, run) → what a segment's profile, fitted from a recording, did not record
    and the sensor's error depends on (docs/model.md section 13: unknown, not 0)."""
    out: dict[tuple[int, int], tuple[str, ...]] = {}
    for r, run in enumerate(runs):
        missing = tuple(dict.fromkeys(n for c in run.columns
                                      for n in study.profiles[c].profile.not_recorded))
        for i, parts in enumerate(depends_on(study.sensors, missing)):
            if parts:
                out[(i, r)] = parts
    return out


def _spec_unknown(prepared: Prepared, runs: Sequence[_Run], where: dict[str, int]
                  ) -> dict[tuple[int, int], tuple[str, ...]]:
    """The unpublished figures that can decide each datasheet sensor in some segment
    of each run (none: no entry), keyed by the sensor's index in the whole study."""

    unknown: dict[tuple[int, int], tuple[str, ...]] = {}
    figures_unknown = spec_bounds.unknown_figures_at(
        prepared, np.arange(len(prepared.sensors)),
        specs.figures(list(prepared.sensors)).has_vre, "exact")
    for k, e in enumerate(prepared.sensors):
        for r, run in enumerate(runs):
            names = spec_bounds.merge_unknown(figures_unknown.names(k, c)
                                              for c in run.columns)
            if names:
                unknown[(where[e.sensor.id], r)] = names
    return unknown


def _group_means(prepared: Prepared, group: Group, runs: Sequence[_Run], where: dict[str, int],
                 scale: float) -> dict[tuple[int, int], float]:
    """The worst mean error over each whole run of one group's datasheet sensors, in the
    output unit (``scale`` of it in deg/s), keyed by (sensor in the study, run)."""

    out: dict[tuple[int, int], float] = {}
    members = [prepared.sensors[int(i)] for i in group.index.tolist()]
    if not members:
        return out
    m = specs.multipliers_of(group, prepared, "exact")
    t = specs.terms_of(m)                                   # (P, 8, 5)
    s2 = specs.mean_square_acceleration(m)                  # (P,)
    figs = specs.figures(members)
    for r, run in enumerate(runs):
        cols = list(run.columns)
        tm = combined_functional(run.durations, t[cols])
        sm = combined_functional(run.durations, s2[cols])
        wc = worst_case(tm[None], np.atleast_1d(sm), figs.range, figs.limit,
                        figs.fit, figs.measure, asymmetry=figs.asymmetry,
                        vre=figs.vre)
        values = np.asarray(wc.total, dtype=float).reshape(len(members), -1)[:, 0]
        for e, v in zip(members, values.tolist(), strict=True):
            out[(where[e.sensor.id], r)] = v / scale
    return out
