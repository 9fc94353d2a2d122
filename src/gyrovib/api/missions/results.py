"""The result of ``gyrovib mission`` (docs/model.md section 12): immutable rows, one per
sensor × mission × axis, each with its segments and its angle budget (section 15)."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from operator import attrgetter
from typing import TYPE_CHECKING, Any

from gyrovib.frozen import Frozen
from gyrovib.records import Column, frame_of

if TYPE_CHECKING:
    import pandas as pd


@dataclass(frozen=True, eq=False, repr=False)
class Budget(Frozen):
    """A mission's angle budget in deg for one sensor and axis (docs/model.md section 15).

    ``vibration`` θ_V (signed); ``arw`` N√T, ``bias_instability`` B·T, ``rrw``
    K·T^{3/2}/√3, ``repeatability`` R·T, each None where the catalogue does not give the
    figure (unknown, never 0); ``total`` = |θ_V| + k·RSS of the known noise terms, a
    lower bound when one is unknown (``unknown`` names them); ``coverage`` k. ``bounds``
    names the terms whose figure is only an upper bound (its bound is used: the term,
    and the total, are then the most they can be from it).
    ``typical``: the terms whose figure the datasheet gives as typical (``typ``), not
    guaranteed, so a verdict on the total rests on a typical figure. ``allowed``: with an
    angle budget, the largest value of each figure that meets it (:class:`Allowance`).
    """

    vibration: float
    arw: float | None
    bias_instability: float | None
    rrw: float | None
    repeatability: float | None
    total: float
    coverage: float
    unknown: tuple[str, ...]
    unit: str = "deg"
    bounds: tuple[str, ...] = ()
    typical: tuple[str, ...] = ()
    allowed: Allowance | None = None

    @property
    def lower_bound(self) -> bool:
        """Whether ``total`` is only a lower bound (a noise figure is unknown)."""
        return bool(self.unknown)

    @property
    def rests_on_bound(self) -> bool:
        """Whether ``total`` rests on a figure given only as an upper bound."""
        return bool(self.bounds)


@dataclass(frozen=True, eq=False, repr=False)
class Allowance(Frozen):
    """The largest value of each budget figure that still meets an angle budget θ*, the
    others as given (docs/model.md section 15 solved for one figure at a time).

    From total = |θ_V| + k·√(θ_ARW² + θ_B² + θ_RRW² + θ_R²) ≤ θ*: ``vibration`` the
    largest |θ_V| (deg); ``arw`` N (deg/√h), ``bias_instability`` B (deg/h),
    ``rrw`` K (deg/h/√h), ``repeatability`` R (deg/h). None: no value passes, and
    ``limited_by`` names, per such figure, the term that alone uses the allowance.
    ``upper``: the figures whose value is only an upper limit, because another
    noise figure is unknown (it can only take more of the allowance).
    """

    vibration: float | None
    arw: float | None
    bias_instability: float | None
    rrw: float | None
    repeatability: float | None
    limited_by: tuple[tuple[str, str], ...] = ()
    upper: tuple[str, ...] = ()

    def limit(self, term: str) -> str | None:
        """The term that alone uses the allowance where ``term`` has no passing value."""
        return dict(self.limited_by).get(term)


#: The budget's noise terms (docs/model.md section 15), in the order it lists them.
BUDGET_NOISE_TERMS = ("arw", "bias_instability", "rrw", "repeatability")

#: Each budget term's figure unit in an :class:`Allowance` (vibration: the angle, deg).
ALLOWANCE_UNITS = {"vibration": "deg", "arw": "deg/sqrt(h)", "bias_instability": "deg/h",
                   "rrw": "deg/h/sqrt(h)", "repeatability": "deg/h"}


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
        """Sensor ``k`` over every mission and axis (:func:`worst_status`); None: no budget."""
        return None if self.sensor_pass[k] is None else worst_status(
            r.status for r in self.rows if r.sensor == self.sensors[k])

    def sensor_records(self) -> tuple[Column[int], ...]:
        """The JSON's ``sensors``: a row per sensor (its index); its rank if ranked."""
        return (Column("sensor", None, self.sensors.__getitem__),
                Column("pass", None, self.sensor_pass.__getitem__),
                Column("status", None, self.sensor_status),
                *(() if self.ranks is None else (Column("rank", None, self.ranks.__getitem__),)))

    def triads(self) -> tuple[tuple[MissionRow, ...], ...]:
        """The rows of each triad (a sensor × mission on several axes): :data:`TRIAD_COLUMNS`."""
        groups: dict[tuple[str, str], tuple[MissionRow, ...]] = {}
        for r in self.rows:
            groups[r.sensor, r.mission] = (*groups.get((r.sensor, r.mission), ()), r)
        return tuple(g for g in groups.values() if any(r.axis is not None for r in g))

    def records(self) -> tuple[Column[MissionRow], ...]:
        """The columns of the JSON rows, the CSV and the DataFrame, with their units: one
        row per sensor × mission × axis (:data:`COLUMNS`)."""
        return COLUMNS

    def to_frame(self) -> pd.DataFrame:
        """One row per sensor × mission × axis (pandas): the columns of the CSV."""
        return frame_of(self.records(), self.rows)

    def segment_rows(self) -> tuple[SegmentRecord, ...]:
        """One record per sensor × mission × axis × segment, in the rows' order."""
        return tuple(SegmentRecord(row, k) for row in self.rows
                     for k in range(len(row.segments)))

    def segments_frame(self) -> pd.DataFrame:
        """One row per segment (pandas): the columns of ``--segments --format csv``
        (:data:`SEGMENT_COLUMNS`)."""
        return frame_of(SEGMENT_COLUMNS, self.segment_rows())


def worst_status(statuses: Iterable[str | None]) -> str:
    """Several verdicts as one: fail if one fails, else unverified if one is, else pass."""
    found = set(statuses)
    return next((s for s in ("fail", "unverified") if s in found), "pass")


#: The JSON's ``triads``, a row per triad (:meth:`MissionResult.triads`): its worst axis, verdict.
TRIAD_COLUMNS: tuple[Column[tuple[MissionRow, ...]], ...] = (
    Column("sensor", None, lambda g: g[0].sensor),
    Column("mission", None, lambda g: g[0].mission),
    Column("worst_axis", None, lambda g: g[0].worst_axis),
    Column("pass", None, lambda g: None if g[0].passed is None else all(r.passed for r in g)),
    Column("status", None,
           lambda g: None if g[0].passed is None else worst_status(r.status for r in g)),
)


def _has_budget(row: MissionRow) -> bool:
    return row.budget is not None


def _allowance(row: MissionRow) -> Allowance | None:
    """The largest values of the budget's figures that meet the angle budget (None: no
    angle budget)."""
    return None if row.budget is None else row.budget.allowed


def _has_allowance(row: MissionRow) -> bool:
    return _allowance(row) is not None


@dataclass(frozen=True, eq=False, repr=False)
class SegmentRecord(Frozen):
    """Segment ``index`` (0-based) of one row: what one line of the per-segment records
    reads (:data:`SEGMENT_COLUMNS`)."""

    row: MissionRow
    index: int

    @property
    def segment(self) -> SegmentResult:
        return self.row.segments[self.index]

    @property
    def start(self) -> float:
        """Seconds from the mission's start to this segment's."""
        return sum(s.duration for s in self.row.segments[:self.index])

    @property
    def budget(self) -> Budget | None:
        """The budget at the segment's end (θ_V summed so far, the noise over the time
        flown), None when the row has no timeline."""
        return self.row.timeline[self.index] if self.row.timeline else None


def _rate(k: int) -> Callable[[SegmentRecord], float]:
    """The segment's carrier rate about x(k+1)."""
    return lambda r: r.segment.rate[k]


def _timed(record: SegmentRecord) -> bool:
    return bool(record.row.timeline)


#: What only the JSON has (the CSV and the frame leave it out).
_JSON = ("csv", "frame")


def _budget_columns(of: Callable[[Any], Budget | None], only: Callable[[Any], bool],
                    vibration: tuple[str, ...],
                    after: str | None = None) -> tuple[Column[Any], ...]:
    """The columns of a budget (deg; None without one): θ_V (``vibration``: the outputs
    that leave it out), each noise term, the total and the coverage factor; its unit (the
    JSON's only); then its marks, which the CSV and the frame put last (after ``after``,
    None: where declared): ``lower_bound`` (the total is only a lower bound, a noise
    figure being unknown), ``rests_on_bound`` (it rests on a figure given only as an upper
    bound) and ``bounds``, the terms that do (the CSV: space-separated)."""
    named = {"vibration": "theta_vibration", "total": "budget_total", "coverage": "coverage"}

    def bounds(r: Any) -> tuple[str, ...] | None:
        return None if (b := of(r)) is None else b.bounds

    return (*(Column(named.get(n, f"theta_{n}"), None if n == "coverage" else "deg",
                     _figure(of, n), key=f"budget.{n}", only=only,
                     skip=vibration if n == "vibration" else ())
              for n in ("vibration", *BUDGET_NOISE_TERMS, "total", "coverage")),
            Column("budget.unit", None, _figure(of, "unit"), skip=_JSON, only=only),
            *(Column(n, None, _figure(of, n), key=f"budget.{n}", only=only, csv_after=after)
              for n in ("lower_bound", "rests_on_bound")),
            Column("bounds", None, lambda r: None if (b := bounds(r)) is None else " ".join(b),
                   key="budget.bounds", only=only, csv_after=after,
                   json_value=lambda r: None if (b := bounds(r)) is None else list(b)))


def _figure(of: Callable[[Any], Any], name: str) -> Callable[[Any], Any]:
    """A figure of a row's budget or allowance (``of``): None where it has none, or the
    figure is unknown (an allowance: no value passes)."""
    return lambda r: None if (b := of(r)) is None else getattr(b, name)


#: The per-segment records (``mission --segments``), declared once: one line per sensor ×
#: mission × axis × segment in the CSV and the frame, and each JSON row's ``segments``
#: (in the JSON's order; the row's keys, ``segment`` and ``start`` only in the CSV,
#: ``end`` placed after ``duration`` there). ``rate`` is the result's unit; the budget at
#: the segment's end (``theta_*``, ``budget_total``) is in deg: θ_V summed segment by
#: segment so far, each noise term over the time flown so far, their total with the
#: coverage factor.
SEGMENT_COLUMNS: tuple[Column[SegmentRecord], ...] = (
    *(Column(n, None, attrgetter(f"row.{n}"), skip=("json",))
      for n in ("sensor", "mission", "placement", "axis")),
    Column("segment", None, lambda r: r.index + 1, skip=("json",)),
    Column("profile", None, lambda r: r.segment.profile),
    Column("start", "s", lambda r: r.start, skip=("json",)),
    Column("duration", "s", lambda r: r.segment.duration),
    *(Column(f"rate_x{k + 1}", "rate", _rate(k), key=f"rate.{k}") for k in range(3)),
    *(Column(n, u, attrgetter(f"segment.{n}")) for n, u in (("total", "rate"), ("rms", "rate"),
                                                            ("saturated", None))),
    Column("end", "s", lambda r: r.start + r.segment.duration, only=_timed,
           csv_after="duration"),
    *_budget_columns(lambda r: r.budget, _timed, vibration=()),
)


#: The records of a mission result, declared once, in the order of a JSON row
#: (docs/output.md): the CSV's header and cells and the DataFrame's columns come from
#: here too, in their own order (``csv_after``). Units: ``rate`` is the result's unit,
#: ``angle`` its angle unit; the budget's terms are in deg, the allowance in each
#: figure's unit. The JSON's ``reason`` (words) is the renderer's.
COLUMNS: tuple[Column[MissionRow], ...] = (
    *(Column(n, u, attrgetter(n)) for n, u in (("sensor", None), ("mission", None),
                                              ("placement", None), ("mean", "rate"),
                                              ("angle", "angle"), ("rms", "rate"))),
    Column("worst_segment", None, lambda r: r.worst_index + 1, key="worst_segment.index",
           json_value=lambda r: r.worst_index),
    Column("worst_profile", None, lambda r: r.worst_profile, key="worst_segment.profile"),
    Column("worst_total", "rate", lambda r: r.worst_total, key="worst_segment.total"),
    Column("duration", "s", lambda r: r.duration, skip=("json",)),
    Column("segments", None, lambda r: tuple(SegmentRecord(r, k)
                                             for k in range(len(r.segments))),
           skip=_JSON, each=SEGMENT_COLUMNS),
    Column("saturated", None, lambda r: r.saturated),
    Column("passed", None, lambda r: r.passed, key="pass"),
    Column("status", None, lambda r: r.status),
    Column("unknown", None, lambda r: " ".join(r.unknown), json_value=lambda r: list(r.unknown)),
    Column("source", None, lambda r: r.source, csv_after="saturated"),
    *_budget_columns(lambda r: r.budget, _has_budget, vibration=_JSON, after="typical"),
    Column("typical", None, lambda r: "" if r.budget is None else " ".join(r.budget.typical),
           key="budget.typical", only=_has_budget, csv_after="allowed_repeatability",
           json_value=lambda r: [] if r.budget is None else list(r.budget.typical)),
    *(Column(f"allowed_{name}", ALLOWANCE_UNITS[name], _figure(_allowance, name),
             key=f"budget.allowed.{name}", only=_has_allowance) for name in ALLOWANCE_UNITS),
    Column("budget.allowed.unit", None, lambda r: dict(ALLOWANCE_UNITS), skip=_JSON,
           only=_has_allowance),
    Column("budget.allowed.limited_by", None,
           lambda r: dict(_figure(_allowance, "limited_by")(r)), skip=_JSON, only=_has_allowance),
    Column("allowed_upper", None, lambda r: None if (a := _allowance(r)) is None
           else " ".join(a.upper), key="budget.allowed.upper", only=_has_allowance,
           csv_after="bounds", json_value=lambda r: _figure(_allowance, "upper")(r)),
    Column("axis", None, lambda r: r.axis, only=lambda r: r.axis is not None,
           csv_after="placement"),
    Column("worst_axis", None, lambda r: r.worst_axis, skip=_JSON,
           only=lambda r: r.axis is not None),
)
