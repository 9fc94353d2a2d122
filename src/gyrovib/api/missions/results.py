"""The result of ``gyrovib mission`` (docs/model.md section 12): immutable rows, one per
sensor × mission × axis, each with its segments."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from gyrovib.frozen import Frozen
from gyrovib.presentation.reasons import unverified_text

if TYPE_CHECKING:
    import pandas as pd

    from gyrovib.api.noise.results import Budget


@dataclass(frozen=True, eq=False, repr=False)
class SegmentResult(Frozen):
    """One segment for one sensor: profile id, duration (s), carrier rate Ω_K about
    x1, x2, x3 of the sensor (output unit), Δ_V and Δ_V(RMS) (output unit), saturated."""

    profile: str
    duration: float
    rate: tuple[float, float, float]
    total: float
    rms: float
    saturated: bool


@dataclass(frozen=True, eq=False, repr=False)
class MissionRow(Frozen):
    """One sensor over one mission in one placement (docs/model.md section 12).

    ``mean`` Δ̄_V and ``rms`` Δ̄_RMS in the result's unit; ``angle`` θ_V in its
    ``angle_unit``; ``worst_index`` (0-based), ``worst_profile``, ``worst_total``:
    the segment of largest |Δ_V,s|. ``axis``: the vehicle axis of the sensitive
    axis x3 ("X", "Y", "Z") in a triad, else None; ``worst_axis``: the triad's
    worst axis (largest |θ_V|), else None. ``passed``: None without a budget.
    A spec-form sensor's ``mean`` is the worst case over its datasheet envelope of
    the whole mission (one conversion function for every segment), and its
    ``angle`` that mean times the mission's duration. ``unknown``: the
    unpublished datasheet figures that can matter in some segment (``vre``,
    ``m31``, ``m32``; docs/model.md section 11); ``unverified``: the row passes
    on the published figures but an unknown one can decide it (then ``passed``
    is False), see :attr:`status`. ``budget``: the whole angle budget in deg
    (docs/model.md section 15; :mod:`gyrovib.api.noise`), None before it is computed;
    ``timeline``: the budget at the end of each segment (θ_V(t) summed segment by
    segment, the noise over the time flown so far), empty before it is computed. For a
    datasheet sensor each segment's angle is that segment's own worst case, so the
    staircase may end above the row's ``angle`` (the worst case of one conversion
    function over the whole mission).
    """

    sensor: str
    mission: str
    placement: str
    axis: str | None
    mean: float
    angle: float
    rms: float
    worst_index: int
    worst_profile: str
    worst_total: float
    segments: tuple[SegmentResult, ...]
    saturated: bool
    passed: bool | None
    source: str = "coefficients"
    worst_axis: str | None = None
    unknown: tuple[str, ...] = ()
    unverified: bool = False
    budget: Budget | None = None
    timeline: tuple[Budget, ...] = ()

    @property
    def duration(self) -> float:
        """Σ T_s, seconds."""
        return sum(s.duration for s in self.segments)

    @property
    def status(self) -> str | None:
        """``"pass"``, ``"fail"`` or ``"unverified"``; None without a budget."""
        if self.passed is None:
            return None
        return "unverified" if self.unverified else "pass" if self.passed else "fail"

    @property
    def reason(self) -> str | None:
        """Why an unverified row is open (:func:`gyrovib.presentation.reasons.unverified_text`)."""
        if not self.unverified:
            return None

        return unverified_text(self.unknown, spec=self.source == "specs")


@dataclass(frozen=True, eq=False, repr=False)
class MissionResult(Frozen):
    """Every chosen sensor over every chosen mission (rows in sensor, mission, axis order).

    ``unit``: the rate unit of every rate value; ``angle_unit``: deg (deg/s, deg/h),
    rad (rad/s) or rev (rpm); ``budget`` (on Δ̄_RMS, in ``unit``) or
    ``angle_budget`` (on |θ_V|, in ``angle_unit``), at most one, None without;
    ``sensor_pass``: per sensor (in ``sensors`` order) whether it passes every
    mission on every axis (None without a budget); ``requirement_met``: the
    ``require`` condition (any: one sensor passes; all: every sensor does);
    ``notes``: warnings about the input (a segment longer than 100 years).
    ``coverage``: k of the rows' budgets (docs/model.md section 15), and then
    ``angle_budget`` is judged on their total. ``ranks``: per sensor its rank by budget
    total (1: smallest) or None where it is not ranked (a total that is a lower bound,
    or unverified); None for a result that is not ranked (``select --mission`` ranks).
    """

    unit: str
    angle_unit: str
    budget: float | None
    angle_budget: float | None
    require: str
    sensors: tuple[str, ...]
    missions: tuple[str, ...]
    rows: tuple[MissionRow, ...]
    sensor_pass: tuple[bool | None, ...]
    requirement_met: bool
    assume_unknown: str = "none"
    notes: tuple[str, ...] = ()
    coverage: float = 1.0
    ranks: tuple[int | None, ...] | None = None

    def sensor_status(self, k: int) -> str | None:
        """Sensor ``k`` over every mission and axis: ``fail`` if a row fails on its
        published figures, else ``unverified`` if one is, else ``pass`` (None without a
        budget)."""
        if self.sensor_pass[k] is None:
            return None
        statuses = {r.status for r in self.rows if r.sensor == self.sensors[k]}
        for status in ("fail", "unverified"):
            if status in statuses:
                return status
        return "pass"

    def to_frame(self) -> pd.DataFrame:
        """One row per sensor × mission × axis (pandas): the columns of the CSV."""
        # lazy: pandas is optional (pip install 'gyrovib[pandas]')
        import pandas as pd

        return pd.DataFrame([_record(r) for r in self.rows])


def _record(r: MissionRow) -> dict[str, Any]:
    return {"sensor": r.sensor, "mission": r.mission, "placement": r.placement,
            "axis": r.axis, "mean": r.mean, "angle": r.angle, "rms": r.rms,
            "worst_segment": r.worst_index + 1, "worst_profile": r.worst_profile,
            "worst_total": r.worst_total, "duration": r.duration, "saturated": r.saturated,
            "source": r.source, "passed": r.passed, "status": r.status,
            "unknown": " ".join(r.unknown), **budget_columns(r),
            "typical": " ".join(r.budget.typical) if r.budget is not None else ""}


#: The budget's columns of the DataFrame and the CSV (deg; None where unknown), then the
#: allowance's (the largest |θ_V| in deg, N, B, K, R in their figures' units that meet
#: the angle budget; None where none passes or without an angle budget).
BUDGET_COLUMNS = ("theta_arw", "theta_bias_instability", "theta_rrw", "theta_repeatability",
                  "budget_total", "coverage", "allowed_vibration", "allowed_arw",
                  "allowed_bias_instability", "allowed_rrw", "allowed_repeatability")


def budget_columns(r: MissionRow) -> dict[str, float | None]:
    """A row's budget as the DataFrame's columns (None: unknown, or not computed)."""
    b = r.budget
    if b is None:
        return dict.fromkeys(BUDGET_COLUMNS)
    a = b.allowed
    allowed = ((None,) * 5 if a is None else
               (a.vibration, a.arw, a.bias_instability, a.rrw, a.repeatability))
    return dict(zip(BUDGET_COLUMNS, (b.arw, b.bias_instability, b.rrw, b.repeatability,
                                     b.total, b.coverage, *allowed), strict=True))


def frame_columns() -> tuple[str, ...]:
    """The DataFrame's (and the CSV's) column names, in order."""
    return ("sensor", "mission", "placement", "axis", "mean", "angle", "rms", "worst_segment",
            "worst_profile", "worst_total", "duration", "saturated", "source", "passed",
            "status", "unknown", *BUDGET_COLUMNS, "typical")
