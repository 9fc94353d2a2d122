"""The records of analyze, bounds, select and sweep, each declared once next to its result:
its columns in order, with units, read from one row (:class:`~gyrovib.records.Column`).
The renderers write the CSV and the JSON entries from them (:mod:`gyrovib.render.formats`)
and ``to_frame()`` the tidy DataFrame (:func:`declared`), so their names cannot drift:

==========================  =================================================
result                      one row per
==========================  =================================================
``AnalysisResult``          sensor × profile (``analyze``)
``BoundsResult``            profile (``bounds``)
``SelectionResult``         sensor × profile (``select``)
``SweepResult``             sensor × profile × rate (``sweep``)
==========================  =================================================

A column is named as the command's ``--format csv`` names it (docs/output.md); one that
only the JSON has is named by its key path joined with ``_``. The JSON ``rate`` list Ω_K
is split into ``rate_x1``, ``rate_x2``, ``rate_x3`` (a sweep's rate is ``rate_x3``). The
frame keeps the float where the JSON writes ``null`` for an unbounded number: ``inf``;
an unknown one is NaN. Term names are taken from the result's term tuples, so a new term
appears as a new column without changes here.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING, Any, overload

import numpy as np

from gyrovib.core.analysis import ALL_TERMS as JSON_TERMS
from gyrovib.core.analysis import MULTIPLICATIVE_TERMS
from gyrovib.core.envelope import COEFFICIENTS as WORST_COEFFICIENTS
from gyrovib.core.synthesis import BOUNDED, ODD_PARTS, PARTS
from gyrovib.reasons import reason
from gyrovib.records import Column, known
from gyrovib.units import coefficient_unit

if TYPE_CHECKING:
    from gyrovib.api import AnalysisResult, BoundsResult, SelectionResult, SweepResult

AXES = ("x1", "x2", "x3")

#: A row of a sensors × profiles result: (sensor index, profile index).
Cell = tuple[int, int]


def _of_cell(values: list[Any], k: int | None = None) -> Callable[[Cell], Any]:
    """Read a (sensors, profiles[, k]) nested list at a row (and its ``k``-th entry)."""
    if k is None:
        return lambda c: values[c[0]][c[1]]
    return lambda c: values[c[0]][c[1]][k]


class _Index:
    """The sensor and the profile indices of a list of rows, as arrays (the last list's
    kept: the columns of a block of rows are read one after the other)."""

    def __init__(self) -> None:
        self._last: tuple[Sequence[Cell], Any] | None = None

    def __call__(self, rows: Sequence[Cell]) -> Any:
        if isinstance(rows, _Cells):
            return rows.indices()
        if self._last is None or self._last[0] is not rows or len(self._last[1][0]) != len(
                rows):
            index = np.fromiter(itertools.chain.from_iterable(rows), dtype=np.intp,
                                count=2 * len(rows)).reshape(-1, 2)
            self._last = (rows, (index[:, 0], index[:, 1]))
        return self._last[1]


def _cells(array: Any, index: _Index) -> dict[str, Any]:
    """``value`` and ``many`` of a column read from a (sensors, profiles) array at a row
    (:class:`~gyrovib.records.Column`): one row's value, or the values of a list of rows
    as an array (``index``: their indices)."""
    values = np.asarray(array)
    listed = functools.cache(values.tolist)
    return {"value": lambda c: listed()[c[0]][c[1]], "many": lambda rows: values[index(rows)]}


def _per(values: Sequence[Any], index: _Index, axis: int) -> dict[str, Any]:
    """``value`` and ``many`` of a column that is the entry of ``values`` of the row's
    sensor (``axis`` 0) or profile (1); floats kept as an array of them, else objects."""
    floats = bool(values) and isinstance(values[0], float)
    array = np.array(values, dtype=float if floats else object)
    return {"value": lambda c: values[c[axis]], "many": lambda rows: array[index(rows)[axis]]}


def _of_profile_row(read: Callable[[int], Any]) -> Callable[[Cell], Any]:
    """A per-profile column read at a sensor × profile row."""
    return lambda c: read(c[1])


def _constant(value: Any) -> Callable[[Any], Any]:
    """The same value on every row."""
    return lambda _: value


def analysis_columns(result: AnalysisResult) -> tuple[Column[Cell], ...]:
    """``analyze``'s records, declared once, one row per sensor × profile (profiles
    outermost): the columns of the DataFrame, of ``--format csv`` (those that do not skip
    it) and of the JSON's ``results`` entries (each at its key path), in order.

    The CSV has ``additive_g2`` only when some profile has a linear vibration, and not
    ``source``, a datasheet sensor's ``envelope_*`` nor the ``worst_phases`` found; the
    JSON has the envelope on a datasheet sensor's rows only, ``uncertainty`` where it is
    known, ``lot_mean`` on a lot's rows and ``worst_phases`` where phases were searched.
    A value that is not known is NaN (JSON: null, CSV: empty); an error that overflowed
    is refused by the JSON, never written as a number."""
    index = _Index()  # the rows' indices, shared by the columns read from arrays
    return (*_value_columns(result, index), *_tail_columns(result, index))


def _value_columns(result: AnalysisResult, index: _Index) -> list[Column[Cell]]:
    """The row's names, its carrier rate and its numbers: terms, coefficients, the error."""
    e = result.error
    terms = [*np.moveaxis(e.additive_terms, -1, 0), *np.moveaxis(e.extra_terms, -1, 0)]
    qs = np.moveaxis(e.multiplicative_coefficients, -1, 0)
    rates = np.asarray(result.rates, dtype=float).reshape(-1, 3).tolist()
    g2 = () if result.has_linear else ("csv",)  # the CSV's g² column: with linear vibration
    columns: list[Column[Cell]] = [
        Column("sensor", None, **_per(result.sensors, index, 0)),
        Column("profile", None, **_per(result.profiles, index, 1)),
        *(Column(f"rate_{axis}", "rate", key=f"rate.{k}", finite=True,
                 **_per([rate[k] for rate in rates], index, 1))
          for k, axis in enumerate(AXES)),
        *(Column(f"additive_{t}", "rate", skip=g2 if t == "g2" else (),
                 key=f"additive_terms.{t}", finite=True, **_cells(terms[k], index))
          for k, t in enumerate(JSON_TERMS)),
        *(Column(f"multiplicative_{q}", "rate", key=f"multiplicative_coefficients.{q}",
                 finite=True, **_cells(qs[k], index))
          for k, q in enumerate(MULTIPLICATIVE_TERMS[:len(qs)])),
        *(Column(name, "rate", finite=True, **_cells(getattr(e, name), index))
          for name in ("additive", "multiplicative", "total", "rms")),
    ]
    if result.stderr is not None:  # numeric: a standard error that is not finite is null
        columns.append(Column("stderr", "rate", **_cells(result.stderr, index)))
    return columns


def _tail_columns(result: AnalysisResult, index: _Index) -> list[Column[Cell]]:
    """What follows the numbers: the sensor's form and envelope (not in the CSV), its
    lot's uncertainty, saturation, the phases found (not in the CSV) and the warnings."""
    sources = [result.source(i) for i in range(len(result.sensors))]
    columns: list[Column[Cell]] = [Column("source", None, skip=("csv",),
                                          **_per(sources, index, 0))]
    columns += _envelope_columns(result)
    if result.uncertainty is not None:
        u = np.asarray(result.uncertainty).tolist()
        columns += [Column("uncertainty_total", "rate", lambda c: u[c[0]][c[1]], cell=known,
                           key="uncertainty.total",
                           only=lambda c: math.isfinite(u[c[0]][c[1]])),
                    Column("lot_mean", None, lambda c: result.is_lot(c[0]),
                           only=lambda c: result.is_lot(c[0]))]
    shape = (len(result.sensors), len(result.profiles))
    saturated = np.zeros(shape, bool) if result.saturated is None else result.saturated
    columns.append(Column("saturated", None, **_cells(np.asarray(saturated, dtype=bool), index)))
    if result.worst_phases:
        phases = result.worst_phases
        columns.append(Column("worst_phases", None, lambda c: None if c not in phases
                              else [dict(g) for g in phases[c]], skip=("csv",),
                              only=lambda c: c in phases))
    warnings = result.warnings
    columns.append(Column("warnings", None, lambda c: tuple(warnings.get(c, ())),
                          many=lambda rows: [tuple(warnings.get(c, ())) for c in zip(
                              *(a.tolist() for a in index(rows)), strict=True)]))
    return columns


class _Cells(Sequence[Cell]):
    """The (sensor, profile) rows ``start`` to ``stop`` of ``n_sensors`` sensors, profiles
    outermost: each pair made when it is read (a catalogue's results are many rows), and
    their indices as arrays at once (:meth:`indices`)."""

    def __init__(self, n_sensors: int, start: int, stop: int) -> None:
        self._n, self._start, self._stop = n_sensors, start, max(start, stop)

    def __len__(self) -> int:
        return self._stop - self._start

    @overload
    def __getitem__(self, k: int) -> Cell: ...

    @overload
    def __getitem__(self, k: slice) -> _Cells: ...

    def __getitem__(self, k: int | slice) -> Cell | _Cells:
        if isinstance(k, slice):
            start, stop, step = k.indices(len(self))
            if step != 1:
                raise ValueError("analyze's rows are sliced in order")
            return _Cells(self._n, self._start + start, self._start + stop)
        if not -len(self) <= k < len(self):
            raise IndexError(k)
        profile, sensor = divmod(self._start + k % len(self), self._n)
        return sensor, profile

    def __iter__(self) -> Iterator[Cell]:
        n = self._n
        return ((k % n, k // n) for k in range(self._start, self._stop))

    def indices(self) -> tuple[Any, Any]:
        """The rows' sensor and profile indices, as arrays."""
        k = np.arange(self._start, self._stop)
        return k % self._n, k // self._n


def analysis_cells(result: AnalysisResult) -> Sequence[Cell]:
    """The rows of ``analyze``'s records: (sensor, profile), profiles outermost."""
    n_s = len(result.sensors)
    return _Cells(n_s, 0, n_s * len(result.profiles))


def _analysis_attrs(result: AnalysisResult) -> dict[str, Any]:
    """``analyze``'s document-level fields, the frame's ``attrs``."""
    attrs: dict[str, Any] = {"method": result.method, "unit": result.unit}
    if result.samples is not None:
        attrs.update(samples=result.samples, seed=result.seed)
    return attrs


def _envelope_columns(result: AnalysisResult) -> list[Column[Cell]]:
    """A datasheet sensor's worst polynomial and RMS bound (section 11): NaN on a
    coefficient-form sensor's rows, whose JSON has no ``envelope``; not in the CSV."""
    if result.worst_coefficients is None or result.rms_bound is None:
        return []
    worst = np.asarray(result.worst_coefficients).tolist()
    bound = np.asarray(result.rms_bound).tolist()
    specs = [result.source(i) == "specs" for i in range(len(result.sensors))]

    def spec_row(c: Cell) -> bool:
        return specs[c[0]]

    return [*(Column(f"envelope_worst_coefficients_{name}", None, _of_cell(worst, k),
                     skip=("csv",), key=f"envelope.worst_coefficients.{name}",
                     only=spec_row, finite=True)
              for k, name in enumerate(WORST_COEFFICIENTS)),
            Column("envelope_rms_bound", "rate", lambda c: bound[c[0]][c[1]], skip=("csv",),
                   key="envelope.rms_bound", only=spec_row, finite=True)]


def _of_row(values: Any) -> Callable[[int], float]:
    """Read a float per row from an array over the rows."""
    listed = np.asarray(values, dtype=float).tolist()
    return lambda j: listed[j]


def _limit_columns(b: Any, unit: str, bounds: str = "",
                   parts: str = "") -> list[Column[int]]:
    """A profile's coefficient bounds, its candidates (k4/k5 and those of locked harmonics,
    docs/model.md section 10) and its VRE bound (section 8; a CSV column only with linear
    vibration, else the frame's ``inf``), named with the prefixes ``bounds`` and
    ``parts`` (JSON: under ``bounds`` and ``parts``, null where unbounded)."""
    present = PARTS + tuple(n for n in ODD_PARTS if getattr(b, n) is not None)
    vre = f"{unit}/g^2"
    return [*(Column(bounds + n, coefficient_unit(n, unit), _of_row(getattr(b, n)),
                     key=f"bounds.{n}") for n in BOUNDED),
            *(Column(parts + n, coefficient_unit(n, unit), _of_row(getattr(b, n)),
                     key=f"parts.{n}") for n in present),
            Column(bounds + "vre", vre, _constant(math.inf), skip=("csv",), key="bounds.vre")
            if b.vre is None else Column(bounds + "vre", vre, _of_row(b.vre), key="bounds.vre")]


def profile_columns(profiles: tuple[str, ...], rates: Any, b: Any, unit: str,
                    prefix: str = "") -> list[Column[int]]:
    """One row per profile (its index): its id, its carrier rate Ω_K (JSON: the ``rate``
    list) and its bounds (:func:`_limit_columns`, their names after ``prefix``): the
    ``profiles`` entries of ``bounds`` and ``select``."""
    table = np.asarray(rates, dtype=float).reshape(-1, 3)
    return [Column("profile", None, lambda j: profiles[j]),
            *(Column(f"rate_{axis}", "rate", _of_row(table[:, k]), key=f"rate.{k}")
              for k, axis in enumerate(AXES)),
            *_limit_columns(b, unit, prefix and prefix + "bounds_", prefix and prefix + "parts_")]


def bounds_columns(result: BoundsResult) -> tuple[Column[int], ...]:
    """``bounds``'s records, declared once, one row per profile (its index): the CSV's
    columns, the frame's and the JSON's ``profiles`` entries, in order. An unconstrained
    bound is ``inf`` (JSON: null); ``vre`` is a CSV column only when some profile has
    linear vibration (the frame: ``inf`` without); ``--range`` adds the allowable
    datasheet figures (the frame and the JSON also their reading)."""
    columns = profile_columns(result.profiles, result.rates, result.bounds, result.unit)
    sb = result.spec_bounds
    if sb is not None:  # bounds --range: the allowable datasheet figures
        nl = "spec_bounds.nonlinearity"
        columns += [Column("spec_nonlinearity", "%FS", _of_row(sb.nonlinearity),
                           key=f"{nl}.value"),
                    *(Column(f"spec_nonlinearity_{key}", None, _constant(value),
                             skip=("csv",), key=f"{nl}.{key}")
                      for key, value in (("unit", "%FS"), ("fit", sb.fit),
                                         ("measure", sb.measure), ("of", sb.of),
                                         ("range", sb.range))),
                    Column("spec_vre", f"{result.unit}/g^2", _of_row(sb.vre),
                           key="spec_bounds.vre")]
    return tuple(columns)


def selection_cells(result: SelectionResult) -> list[Cell]:
    """The rows of ``select``'s records: (sensor, profile), sensors outermost."""
    return [(i, j) for i in range(len(result.sensors)) for j in range(len(result.profiles))]


def _float_cell(values: Any) -> Callable[[Cell], float]:
    listed = np.asarray(values, dtype=float).tolist()
    return lambda c: listed[c[0]][c[1]]


#: Outside a sensor × profile entry of ``select``'s JSON: the sensor's (its ``sensor``,
#: ``pass``, ``status``, ``source``) and the profile's (``rate``, its bounds and parts).
_ENTRY = ("json",)


def selection_columns(result: SelectionResult) -> tuple[Column[Cell], ...]:
    """``select``'s records, declared once, one row per sensor × profile (sensors
    outermost): the columns of the DataFrame and of ``--format csv`` (those that do not
    skip it), and the keys of the JSON's sensor × profile entries (those that do not skip
    ``json``; the JSON keeps the others in the sensor's entry and in ``profiles``).

    ``passed`` is the JSON's ``pass`` (a Python keyword breaks ``df.query("not pass")``);
    ``value_<coefficient>``, ``bound_…``, ``pass_…`` its ``checks.<coefficient>``, empty
    (NaN, None) on a datasheet sensor's rows; the frame adds the sensor's ``status``, the
    profile's ``rate_*`` and ``profile_bounds_*``/``profile_parts_*`` (the JSON's
    ``profiles`` entry), and keeps ``unknown`` and ``disagrees`` as lists (the CSV: their
    names joined by spaces)."""
    specs = [result.source(i) == "specs" for i in range(len(result.sensors))]
    margin = result.margin if result.criterion_margin is None else result.criterion_margin
    sensor_pass = np.asarray(result.sensor_pass, dtype=bool).tolist()
    columns: tuple[Column[Cell], ...] = (
        Column("sensor", None, lambda c: result.sensors[c[0]], skip=_ENTRY),
        Column("profile", None, lambda c: result.profiles[c[1]]),
        Column("passed", None, lambda c: bool(result.passed[c[0], c[1]]), key="pass"),
        Column("sensor_pass", None, lambda c: sensor_pass[c[0]], skip=_ENTRY),
        Column("sensor_status", None, lambda c: result.sensor_status(c[0]),
               skip=("csv", *_ENTRY)),
        Column("rms", "rate", _float_cell(result.rms)),
        Column("margin", None, _float_cell(result.margin)),
        *_coefficient_checks(result, specs),
        *_datasheet_checks(result, specs),
        *_yield_cells(result),
        Column("saturated", None, lambda c: bool(result.saturated is not None
                                                 and result.saturated[c[0], c[1]])),
        Column("status", None, lambda c: result.status(*c)),
        Column("unknown", None, lambda c: list(result.unknown.get(c, ())), cell=" ".join),
        Column("criterion_margin", None, _float_cell(margin)),
        Column("disagrees", None, lambda c: list(result.disagrees.get(c, ())), cell=" ".join),
        Column("reason", None, lambda c: None if result.passed[c[0], c[1]]
               else reason(result.failures(*c))),
    )
    profiles = profile_columns(result.profiles, result.rates, result.profile_bounds,
                               result.unit, "profile_")
    return (*columns, *(Column(c.name, c.unit, _of_profile_row(c.value), key=c.key,
                               skip=("csv", *_ENTRY)) for c in profiles[1:]))


def _coefficient_checks(result: SelectionResult, specs: list[bool]) -> list[Column[Cell]]:
    """``checks.<coefficient>.value|bound|pass`` (eq. 23, 25): NaN, None on a datasheet
    (spec-form) sensor's rows, which have no coefficient checks; a check against a bound
    a fitted profile's recording leaves unknown decides nothing (None,
    :meth:`~gyrovib.api.SelectionResult.check`)."""
    array = np.asarray(result.values, dtype=float)
    unknown = (np.isnan(result.bounds) & (array != 0)).tolist()
    values, bounds = array.tolist(), np.asarray(result.bounds, dtype=float).tolist()
    checks = np.asarray(result.check_pass, dtype=bool).tolist()

    def read(table: list[Any], b: int, empty: Any) -> Callable[[Cell], Any]:
        return lambda c: empty if specs[c[0]] else table[c[0]][c[1]][b]

    def coefficient_row(c: Cell) -> bool:
        return not specs[c[0]]

    columns: list[Column[Cell]] = []
    for b, name in enumerate(BOUNDED):
        key = f"checks.{name}."
        columns += [Column(f"value_{name}", None, read(values, b, math.nan),
                           key=key + "value", only=coefficient_row),
                    Column(f"bound_{name}", None, read(bounds, b, math.nan),
                           key=key + "bound", only=coefficient_row),
                    Column(f"pass_{name}", None, _check(checks, unknown, specs, b),
                           key=key + "pass", only=coefficient_row)]
    return columns


def _check(checks: list[Any], unknown: list[Any], specs: list[bool],
           b: int) -> Callable[[Cell], bool | None]:
    """Coefficient ``b``'s check at a row: None on a datasheet row or where it is unknown."""
    return lambda c: (None if specs[c[0]] or unknown[c[0]][c[1]][b]
                      else checks[c[0]][c[1]][b])


def _datasheet_checks(result: SelectionResult, specs: list[bool]) -> list[Column[Cell]]:
    """A datasheet sensor's ``source``, ``total`` and nonlinearity check (%FS; NaN, None
    on coefficient rows), then the VRE check (docs/model.md section 8). The CSV has them
    with datasheet sensors (the VRE check also where it can bind: linear vibration); its
    cells are empty where a row has no such check."""
    with_specs = "specs" in result.sources
    vre = result.has_linear and result.vre_pass is not None
    csv = () if with_specs else ("csv",)
    columns: list[Column[Cell]] = [Column("source", None, lambda c: result.source(c[0]),
                                          skip=(*csv, *_ENTRY))]
    if result.total is not None:
        columns.append(Column("total", "rate", _float_cell(result.total), skip=csv))
    if result.nl_value is not None:
        columns += _nonlinearity_checks(result, specs, csv)
    if result.vre_pass is not None:
        columns += _vre_checks(result, specs, () if with_specs or vre else ("csv",), vre)
    return columns


def _nonlinearity_checks(result: SelectionResult, specs: list[bool],
                         csv: tuple[str, ...]) -> list[Column[Cell]]:
    """A datasheet sensor's nonlinearity check (%FS; NaN, None on coefficient rows), with
    its unit on datasheet rows (not in the CSV)."""
    def spec_row(c: Cell) -> bool:
        return specs[c[0]]

    key = "checks.nonlinearity."
    return [Column("value_nonlinearity", "%FS", _float_cell(result.nl_value), skip=csv,
                   key=key + "value", only=spec_row),
            Column("bound_nonlinearity", "%FS", _float_cell(result.nl_bound), skip=csv,
                   key=key + "bound", only=spec_row),
            Column("pass_nonlinearity", None,
                   lambda c: result.nl_check(*c) if specs[c[0]] else None, skip=csv,
                   key=key + "pass", only=spec_row),
            Column("unit_nonlinearity", None, lambda c: "%FS" if specs[c[0]] else None,
                   skip=("csv",), key=key + "unit", only=spec_row)]


def _vre_checks(result: SelectionResult, specs: list[bool], csv: tuple[str, ...],
                vre: bool) -> list[Column[Cell]]:
    """The VRE check (docs/model.md section 8): the CSV's cells empty on a coefficient row
    where it cannot bind (no linear vibration)."""
    blank = None if vre else (lambda c: not specs[c[0]])
    return [Column("value_vre", None, _float_cell(result.vre_value), skip=csv,
                   key="checks.vre.value", blank=blank),
            Column("bound_vre", None, _float_cell(result.vre_bound), skip=csv,
                   key="checks.vre.bound", blank=blank),
            Column("pass_vre", None, lambda c: result.vre_check(*c), skip=csv,
                   key="checks.vre.pass", blank=blank)]


def _yield_cells(result: SelectionResult) -> list[Column[Cell]]:
    """``--yield`` (docs/model.md section 14): NaN, None off the lots; an exact yield's
    interval NaN."""
    y = result.yields
    if y is None:
        return []
    value, low, high = (_float_cell(a) for a in (y.value, y.low, y.high))

    def lot(c: Cell) -> bool:
        return y.is_lot(c[0])

    return [
        Column("yield_value", None, value, key="yield.value", only=lot),
        Column("yield_method", None, lambda c: y.method if lot(c) else None,
               key="yield.method", only=lot),
        Column("yield_interval_low", None, low, key="yield.interval.0", only=lot),
        Column("yield_interval_high", None, high, key="yield.interval.1", only=lot),
        Column("yield_draws", None, lambda c: y.draws if lot(c) else None, key="yield.draws",
               only=lot)]


#: A row of a sweep: (sensor, profile, rate) indices.
SweepCell = tuple[int, int, int]


def sweep_cells(result: SweepResult) -> list[SweepCell]:
    """The rows of ``sweep``'s records: profiles outermost, then sensors, then rates (the
    JSON's order)."""
    n_r = len(result.rates)
    return [(i, j, r) for j in range(len(result.profiles)) for i in range(len(result.sensors))
            for r in range(n_r)]


def sweep_columns(result: SweepResult) -> tuple[Column[SweepCell], ...]:
    """``sweep``'s records, declared once, one row per sensor × profile × rate Ω_K3: the
    columns of ``--format csv`` and of the DataFrame. The paper's values are unknown (CSV:
    empty, frame: NaN) for a profile its formulas do not cover."""
    rates = np.asarray(result.rates, dtype=float).tolist()
    refused = [p in result.paper_refused for p in result.profiles]
    saturated = result.saturated

    def read(method: str, name: str) -> Callable[[SweepCell], float]:
        # the values are listed at the first read: the CSV's fast writer takes only the names
        values = functools.cache(lambda: np.asarray(getattr(getattr(result, method), name),
                                                    dtype=float).tolist())
        if method == "paper":
            return lambda c: math.nan if refused[c[1]] else values()[c[0]][c[1]][c[2]]
        return lambda c: values()[c[0]][c[1]][c[2]]

    return (Column("sensor", None, lambda c: result.sensors[c[0]]),
            Column("profile", None, lambda c: result.profiles[c[1]]),
            Column("rate_x3", "rate", lambda c: rates[c[2]]),
            *(Column(f"{method}_{name}", "rate", read(method, name))
              for method in ("exact", "paper") for name in ("total", "rms")),
            Column("saturated", None, lambda c: saturated is not None
                   and bool(saturated[c])))


def _bounds_attrs(result: BoundsResult) -> dict[str, Any]:
    return {"method": result.method, "unit": result.unit, "budget": result.budget}


def _selection_attrs(result: SelectionResult) -> dict[str, Any]:
    attrs = {"method": result.method, "unit": result.unit, "budget": result.budget,
             "criterion": result.criterion, "require": result.require,
             "requirement_met": result.requirement_met}
    if result.yields is not None:
        attrs.update({"yield": result.yields.target, "seed": result.yields.seed})
    return attrs


def _sweep_attrs(result: SweepResult) -> dict[str, Any]:
    return {"method": "exact", "unit": result.unit, "methods": ["exact", "paper"],
            "paper_refused": dict(result.paper_refused)}


#: Each result's records, its rows and its document-level fields (the frame's ``attrs``).
_DECLARED: dict[str, tuple[Callable[[Any], Sequence[Column[Any]]],
                           Callable[[Any], Sequence[Any]], Callable[[Any], dict[str, Any]]]] = {
    "AnalysisResult": (analysis_columns, analysis_cells, _analysis_attrs),
    "BoundsResult": (bounds_columns, lambda r: range(len(r.profiles)), _bounds_attrs),
    "SelectionResult": (selection_columns, selection_cells, _selection_attrs),
    "SweepResult": (sweep_columns, sweep_cells, _sweep_attrs),
}


def declared(result: Any) -> tuple[Sequence[Column[Any]], Sequence[Any], dict[str, Any]]:
    """A result's records, its rows and its document-level fields (the frame's ``attrs``):
    what ``to_frame()`` makes its DataFrame of."""
    found = _DECLARED.get(type(result).__name__)
    if found is None:
        raise TypeError(f"no DataFrame form for {type(result).__name__}")
    columns, rows, attrs = found
    return columns(result), rows(result), attrs(result)
