"""``gyrovib mission`` with the whole error budget (docs/model.md section 15): the
vibration view of :mod:`gyrovib.api.commands.mission`, each row given its
:class:`~gyrovib.api.noise.Budget`, and an angle budget judged on the total.

A row passes ``--angle-budget`` θ* when no segment saturates the sensor and
total = |θ_V| + k·RSS(noise) ≤ θ*. A noise figure the catalogue does not give is
unknown, never 0: the total is then a lower bound, and a row that passes on it is
``unverified`` (its names join the row's ``unknown``), unless
``assume_unknown="zero"``, as for an unpublished VRE.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

from gyrovib.api.commands.mission import mission as vibration_mission
from gyrovib.api.datasheet import spec_bounds
from gyrovib.api.evaluation.unknown import any_missing
from gyrovib.api.missions.results import MissionResult, MissionRow
from gyrovib.api.noise.budget import TERM_OF, allowance, budget, timeline
from gyrovib.api.noise.figures import FIGURES, noise_bounds, noise_values, typical_figures
from gyrovib.catalog.loader import Catalog
from gyrovib.core.mission import ANGLE_IN_RAD, ANGLE_UNITS
from gyrovib.errors import ModelError, OptionError

#: Degrees per unit of a mission's angle (deg, rad, rev).
_DEG_PER = {name: ANGLE_IN_RAD[name] / ANGLE_IN_RAD["deg"] for name in ("deg", "rad", "rev")}


def check_coverage(coverage: float) -> float:
    """The coverage factor k: finite and > 0."""
    if not (math.isfinite(coverage) and coverage > 0):
        raise OptionError(argument="coverage", value=f"{coverage:g}",
                          reason="give a positive coverage factor "
                                 "(1: one standard deviation, 2: about 95 %)")
    return float(coverage)


def mission(catalog: Catalog, *, coverage: float = 1.0, angle_budget: float | None = None,
            **options: Any) -> MissionResult:
    """Every chosen sensor over every chosen mission with its angle budget in deg.

    The keywords are those of :func:`gyrovib.api.commands.mission.mission`;
    ``angle_budget`` (radians) judges the budget's total; ``coverage`` is k.
    """
    k = check_coverage(coverage)
    result = vibration_mission(catalog, angle_budget=angle_budget, **options)
    noise = {e.sensor.id: e.sensor.noise for e in catalog.sensors}
    per_deg = _DEG_PER[result.angle_unit]
    per_step = per_deg * ANGLE_UNITS[result.unit][1]  # deg per (rate unit × s)
    rows = [_with_budget(r, noise_values(noise[r.sensor], r.axis), per_deg, per_step, k,
                         noise_bounds(noise[r.sensor], r.axis),
                         typical_figures(noise[r.sensor], r.axis)) for r in result.rows]
    _refuse_overflow(catalog, rows)
    if result.angle_budget is not None:
        theta = result.angle_budget * _DEG_PER[result.angle_unit]
        rows = [_judged(r, theta, result.assume_unknown) for r in rows]
    return _verdicts(result, rows, k)


def _with_budget(row: MissionRow, figures: dict[str, float | None], per_deg: float,
                 per_step: float, coverage: float, bounds: tuple[str, ...],
                 typical: tuple[str, ...] = ()) -> MissionRow:
    """The row's budget (``per_deg``: deg per angle unit; ``bounds``: the figures that
    are only upper bounds; ``typical``: those given as ``typ``), and its timeline
    (``per_step``: deg per rate unit × second)."""
    steps = [s.total * s.duration * per_step for s in row.segments]
    return replace(row, budget=budget(row.angle * per_deg, figures, row.duration, coverage,
                                      bounds, typical),
                   timeline=timeline(steps, [s.duration for s in row.segments], figures,
                                     coverage, bounds, typical))


def _refuse_overflow(catalog: Catalog, rows: Sequence[MissionRow]) -> None:
    """A budget term or total past double precision (a noise figure over an enormous
    duration) is refused at the mission's duration, naming the sensor and the term: it
    cannot be a float, and ∞ must not read as a figure."""
    for row in rows:
        b = row.budget
        if b is None or math.isnan(b.vibration):  # unknown θ_V: not an overflow
            continue
        terms = {name: getattr(b, name) for name in TERM_OF.values()}
        bad = [n for n, v in terms.items() if v is not None and not math.isfinite(v)]
        if not bad and math.isfinite(b.total):
            continue
        entry = next(e for e in catalog.missions if e.mission.id == row.mission)
        what = f"its {bad[0]} term" if bad else "its budget total"
        raise ModelError(entry.source.problem(
            f"mission {row.mission!r}, sensor {row.sensor!r}: {what} over "
            f"{row.duration:.6g} s is beyond double precision (about 1.8e308 deg): check "
            "the durations (seconds unless written with min or h) and the noise figures",
            ("missions", entry.index, "segments", 0, "duration")),
            reason="budget overflows")


def _judged(row: MissionRow, theta_deg: float, assume_unknown: str) -> MissionRow:
    """The row's verdict on its total; noise figures not given join its unknown."""
    assert row.budget is not None
    names = row.unknown + tuple(n for n in FIGURES if TERM_OF[n] in row.budget.unknown)
    passed = not row.saturated and row.budget.total <= theta_deg
    open_ = any_missing(names) or spec_bounds.is_unverified(passed, names, assume_unknown)
    allowed = allowance(row.budget, theta_deg, row.duration)
    return replace(row, passed=passed and not open_, unverified=open_, unknown=names,
                   budget=replace(row.budget, allowed=allowed))


def _verdicts(result: MissionResult, rows: Sequence[MissionRow], coverage: float
              ) -> MissionResult:
    judged = result.budget is not None or result.angle_budget is not None
    sensor_pass = tuple(None if not judged else all(bool(r.passed) for r in rows
                                                    if r.sensor == s)
                        for s in result.sensors)
    if not judged:
        met = True
    elif result.require == "all":
        met = all(bool(p) for p in sensor_pass)
    else:
        met = any(bool(p) for p in sensor_pass)
    return replace(result, rows=tuple(rows), sensor_pass=sensor_pass, requirement_met=met,
                   coverage=coverage)


def ranked(result: MissionResult) -> MissionResult:
    """The sensors ordered by their largest budget total over the rows (smallest first;
    ``select --mission``): the rows follow their sensor, in their own order.

    Only a sensor whose every total is a figure is ranked: one whose total somewhere is a
    lower bound (a noise figure unknown) or whose verdict is unverified is not ranked on
    it, and follows the ranked ones in the catalogue's order (README: unverified parts
    are not ranked)."""
    def key(k: int) -> tuple[bool, float]:
        rows = [r for r in result.rows if r.sensor == result.sensors[k]]
        if not rankable(rows):
            return True, 0.0
        totals = [r.budget.total for r in rows if r.budget is not None]
        return False, max(totals, default=math.inf)

    keys = [key(k) for k in range(len(result.sensors))]
    order = sorted(range(len(result.sensors)), key=lambda k: keys[k])
    sensors = tuple(result.sensors[k] for k in order)
    rows = tuple(r for s in sensors for r in result.rows if r.sensor == s)
    ranks = tuple(None if keys[k][0] else n + 1 for n, k in enumerate(order))
    return replace(result, sensors=sensors, rows=rows, ranks=ranks,
                   sensor_pass=tuple(result.sensor_pass[k] for k in order))


def rankable(rows: Sequence[MissionRow]) -> bool:
    """Whether a sensor's rows can rank it: every budget total a figure (no lower bound),
    no verdict unverified."""
    return all(r.budget is not None and not r.budget.lower_bound and not r.unverified
               for r in rows)
