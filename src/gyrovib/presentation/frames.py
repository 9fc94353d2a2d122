"""Results as tidy pandas DataFrames (optional extra ``gyrovib[pandas]``).

Each function takes a result of :mod:`gyrovib.api` and returns one row per
observation, with the columns of the command's ``--format csv`` (the same
names, docs/output.md); what only the JSON has is added, its nested keys
joined with ``_``. :func:`column_name` maps a JSON key path to its column
(``additive_terms.k2`` → ``additive_k2``, ``checks.k3.bound`` → ``bound_k3``,
``exact.rms`` → ``exact_rms``, ``pass`` → ``passed``: a Python keyword
cannot be used in ``DataFrame.query``):

==========================  =================================================
result                      one row per
==========================  =================================================
``AnalysisResult``          sensor × profile (``analyze``)
``BoundsResult``            profile (``bounds``)
``SelectionResult``         sensor × profile (``select``)
``SweepResult``             sensor × profile × rate (``sweep``)
==========================  =================================================

The JSON ``rate`` list Ω_K is split into ``rate_x1``, ``rate_x2``,
``rate_x3`` (a sweep's rate is ``rate_x3``). Where the JSON writes ``null``
for an unbounded number (a bound or a margin that is +inf), the frame keeps
the float: ``inf``; the paper's
values for a profile the paper's formulas do not cover are ``NaN``. The
JSON's document-level fields (tool, version, method, unit, budget, ...) are
in ``frame.attrs``. Term names are taken from the result's term tuples, so a
new term appears as a new column without changes here.

pandas is imported when a frame is built, never at ``import gyrovib``; when it
is missing the error names the extra to install.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from gyrovib.core.analysis import ALL_TERMS as JSON_TERMS
from gyrovib.core.analysis import MULTIPLICATIVE_TERMS
from gyrovib.core.envelope import COEFFICIENTS as WORST_COEFFICIENTS
from gyrovib.core.synthesis import BOUNDED, ODD_PARTS, PARTS
from gyrovib.presentation.reasons import reason
from gyrovib.records import MISSING_PANDAS as MISSING_PANDAS
from gyrovib.records import Column, columns_of, dataframe
from gyrovib.records import MissingDependency as MissingDependency

if TYPE_CHECKING:
    from gyrovib.api import AnalysisResult, BoundsResult, SelectionResult, SweepResult

AXES = ("x1", "x2", "x3")

#: A row of a sensors × profiles result: (sensor index, profile index).
Cell = tuple[int, int]


def column_name(kind: str, path: str) -> str:
    """The column of the JSON key path ``path`` (dots between keys) in the frame and the
    CSV of command ``kind`` (``analyze``, ``bounds``, ``select``, ``sweep``)."""
    parts = path.split(".")
    if path == "pass":
        return "passed"
    if parts[0] == "rate" and len(parts) == 2:
        return f"rate_{parts[1]}"
    own = _COLUMNS.get(kind)
    named = None if own is None else own(parts)
    return "_".join(parts) if named is None else named


def _sweep_column(parts: list[str]) -> str | None:
    return "rate_x3" if parts == ["rate"] else None


def _analyze_column(parts: list[str]) -> str | None:
    if len(parts) == 2 and parts[0] in ("additive_terms", "multiplicative_coefficients"):
        return f"{parts[0].split('_')[0]}_{parts[1]}"
    return None


def _bounds_column(parts: list[str]) -> str | None:
    if len(parts) == 2 and parts[0] in ("bounds", "parts"):
        return parts[1]
    if parts[0] == "spec_bounds":
        rest = parts[1:-1] if parts[-1] == "value" else parts[1:]
        return "spec_" + "_".join(rest)
    return None


def _select_column(parts: list[str]) -> str | None:
    return f"{parts[2]}_{parts[1]}" if len(parts) == 3 and parts[0] == "checks" else None


#: Each command's own column names, where they differ from the key path joined by ``_``.
_COLUMNS: dict[str, Callable[[list[str]], str | None]] = {
    "sweep": _sweep_column, "analyze": _analyze_column, "bounds": _bounds_column,
    "select": _select_column}


def _named(kind: str, columns: dict[str, Any]) -> dict[str, Any]:
    return {column_name(kind, key): value for key, value in columns.items()}


def _rate_columns(rates: Any, rows: Any) -> dict[str, Any]:
    """``rate.x1..x3`` of Ω_K per profile (``rates`` (profiles, 3)), taken at ``rows``."""
    return {f"rate.{axis}": rates[rows, k] for k, axis in enumerate(AXES)}


def _of_cell(values: list[Any], k: int | None = None) -> Callable[[Cell], Any]:
    """Read a (sensors, profiles[, k]) nested list at a row (and its ``k``-th entry)."""
    if k is None:
        return lambda c: values[c[0]][c[1]]
    return lambda c: values[c[0]][c[1]][k]


def _of_profile(values: list[Any], k: int) -> Callable[[Cell], Any]:
    """Read a (profiles, k) nested list at a row's profile."""
    return lambda c: values[c[1]][k]


def analysis_columns(result: AnalysisResult, *, csv: bool) -> tuple[Column[Cell], ...]:
    """``analyze``'s records, declared once, one row per sensor × profile (profiles
    outermost, the JSON's order): the columns of ``--format csv`` (``csv``) or of the
    DataFrame, in order. The frame has every term (``additive_g2`` with or without linear
    vibration) and, beyond the CSV, ``source``, a datasheet sensor's ``envelope_*`` and
    the ``worst_phases`` found; a value that is not known is None (CSV: empty)."""
    return (*_value_columns(result, csv), *_tail_columns(result, csv))


def _value_columns(result: AnalysisResult, csv: bool) -> list[Column[Cell]]:
    """The row's names, its carrier rate and its numbers: terms, coefficients, the error."""
    e = result.error
    terms = [[[*t, *g] for t, g in zip(ts, gs, strict=True)]
             for ts, gs in zip(e.additive_terms.tolist(), e.extra_terms.tolist(), strict=True)]
    qs = e.multiplicative_coefficients.tolist()
    rates = np.asarray(result.rates, dtype=float).reshape(-1, 3).tolist()
    parts = {name: np.asarray(getattr(e, name)).tolist()
             for name in ("additive", "multiplicative", "total", "rms")}
    shown = [k for k, t in enumerate(JSON_TERMS) if not csv or t != "g2" or result.has_linear]
    columns: list[Column[Cell]] = [
        Column("sensor", None, lambda c: result.sensors[c[0]]),
        Column("profile", None, lambda c: result.profiles[c[1]]),
        *(Column(f"rate_{axis}", "rate", _of_profile(rates, k))
          for k, axis in enumerate(AXES)),
        *(Column(f"additive_{JSON_TERMS[k]}", "rate", _of_cell(terms, k))
          for k in shown),
        *(Column(f"multiplicative_{q}", "rate", _of_cell(qs, k))
          for k, q in enumerate(MULTIPLICATIVE_TERMS[:e.multiplicative_coefficients.shape[-1]])),
        *(Column(name, "rate", _of_cell(values))
          for name, values in parts.items()),
    ]
    if result.stderr is not None:
        stderr = np.asarray(result.stderr).tolist()
        columns.append(Column("stderr", "rate", lambda c: stderr[c[0]][c[1]]))
    return columns


def _tail_columns(result: AnalysisResult, csv: bool) -> list[Column[Cell]]:
    """What follows the numbers: the sensor's form and envelope (frame only), its lot's
    uncertainty, saturation, the phases found (frame only) and the warnings."""
    columns: list[Column[Cell]] = []
    if not csv:
        columns.append(Column("source", None, lambda c: result.source(c[0])))
        columns += _envelope_columns(result)
    if result.uncertainty is not None:
        u = np.asarray(result.uncertainty).tolist()
        columns.append(Column("uncertainty_total", "rate", (lambda c: _known(u[c[0]][c[1]]))
                              if csv else (lambda c: u[c[0]][c[1]])))  # CSV: unknown empty
        columns.append(Column("lot_mean", None, lambda c: result.is_lot(c[0])))
    saturated = result.saturated
    columns.append(Column("saturated", None,
                          lambda c: bool(saturated is not None and saturated[c[0], c[1]])))
    if result.worst_phases and not csv:
        columns.append(Column("worst_phases", None, lambda c: None if c not in
                              result.worst_phases else [dict(g) for g in
                                                        result.worst_phases[c]]))
    columns.append(Column("warnings", None, lambda c: tuple(result.warnings.get(c, ()))))
    return columns


def _known(value: float) -> float | None:
    """A finite number, or None (unknown)."""
    return value if math.isfinite(value) else None


def analysis_cells(result: AnalysisResult) -> list[Cell]:
    """The rows of ``analyze``'s records: (sensor, profile), profiles outermost."""
    return [(i, j) for j in range(len(result.profiles)) for i in range(len(result.sensors))]


def analysis_frame(result: AnalysisResult) -> Any:
    """``analyze``: one row per sensor × profile, profiles outermost (the JSON's order)."""
    cells = analysis_cells(result)
    attrs: dict[str, Any] = {"method": result.method, "unit": result.unit}
    if result.samples is not None:
        attrs.update(samples=result.samples, seed=result.seed)
    return dataframe(columns_of(analysis_columns(result, csv=False), cells), attrs)


def _envelope_columns(result: AnalysisResult) -> list[Column[Cell]]:
    """A datasheet sensor's worst polynomial and RMS bound (section 11): NaN where not
    known."""
    if result.worst_coefficients is None or result.rms_bound is None:
        return []
    worst = np.asarray(result.worst_coefficients).tolist()
    bound = np.asarray(result.rms_bound).tolist()
    return [*(Column(f"envelope_worst_coefficients_{name}", None,
                     _of_cell(worst, k))
              for k, name in enumerate(WORST_COEFFICIENTS)),
            Column("envelope_rms_bound", "rate", lambda c: bound[c[0]][c[1]])]


def _bounds_columns(bounds: Any, rows: Any) -> dict[str, Any]:
    out = {f"bounds.{n}": np.asarray(getattr(bounds, n))[rows] for n in BOUNDED}
    # the VRE bound (docs/model.md section 8): JSON null, here inf, without linear vibration
    vre = np.full(len(rows), np.inf) if bounds.vre is None else np.asarray(bounds.vre)[rows]
    out["bounds.vre"] = vre
    present = PARTS + tuple(n for n in ODD_PARTS if getattr(bounds, n) is not None)
    out.update({f"parts.{n}": np.asarray(getattr(bounds, n))[rows] for n in present})
    return out


def bounds_frame(result: BoundsResult) -> Any:
    """``bounds``: one row per profile; an unconstrained bound is ``inf``."""
    rows = np.arange(len(result.profiles))
    columns: dict[str, Any] = {
        "profile": list(result.profiles),
        **_rate_columns(np.asarray(result.rates).reshape(-1, 3), rows),
        **_bounds_columns(result.bounds, rows),
    }
    sb = result.spec_bounds
    if sb is not None:  # bounds --range: the allowable datasheet figures
        n = len(result.profiles)
        columns.update({
            "spec_bounds.nonlinearity.value": np.asarray(sb.nonlinearity)[rows],
            "spec_bounds.nonlinearity.unit": ["%FS"] * n,
            "spec_bounds.nonlinearity.fit": [sb.fit] * n,
            "spec_bounds.nonlinearity.measure": [sb.measure] * n,
            "spec_bounds.nonlinearity.of": [sb.of] * n,
            "spec_bounds.nonlinearity.range": [sb.range] * n,
            "spec_bounds.vre": np.asarray(sb.vre)[rows],
        })
    return dataframe(_named("bounds", columns), {"method": result.method, "unit": result.unit,
                                              "budget": result.budget})


def selection_frame(result: SelectionResult) -> Any:
    """``select``: one row per sensor × profile.

    ``passed`` (the JSON's ``pass``: ``df.query("not passed")`` works),
    ``status`` (pass, fail, unverified), ``unknown``, ``rms``, ``margin`` and
    ``value_<coefficient>``, ``bound_…``, ``pass_…`` (the JSON's
    ``checks.<coefficient>.value|bound|pass``) are the JSON's per-profile cell;
    ``sensor_pass`` and ``sensor_status`` are the sensor's overall ``pass`` and
    ``status``; ``rate_*`` and ``profile_bounds_*`` are the profile's entry of
    the JSON's ``profiles`` list (its bounds for ν_sensor = 1).
    """
    n_s, n_p = len(result.sensors), len(result.profiles)
    s_idx, p_idx = (a.reshape(-1) for a in np.indices((n_s, n_p)))
    cells = list(zip(s_idx.tolist(), p_idx.tolist(), strict=True))
    columns: dict[str, Any] = {
        "sensor": [result.sensors[i] for i in s_idx],
        "profile": [result.profiles[j] for j in p_idx],
        "sensor_pass": np.asarray(result.sensor_pass, dtype=bool)[s_idx],
        "sensor_status": [result.sensor_status(int(i)) for i in s_idx],
        # "passed", not the JSON's "pass": a Python keyword breaks df.query("not pass")
        "pass": np.asarray(result.passed, dtype=bool).reshape(-1),
        "status": [result.status(i, j) for i, j in cells],
        "unknown": [list(result.unknown.get((i, j), ())) for i, j in cells],
        "criterion_margin": np.asarray(result.margin if result.criterion_margin is None
                                       else result.criterion_margin).reshape(-1),
        "disagrees": [list(result.disagrees.get((i, j), ())) for i, j in cells],
        "rms": np.asarray(result.rms).reshape(-1),
        "margin": np.asarray(result.margin).reshape(-1),
        "saturated": np.asarray(result.saturated, dtype=bool).reshape(-1),
        "reason": [reason(result, i, j) for i, j in cells],
    }
    spec_rows = np.array([result.source(int(i)) == "specs" for i in s_idx], dtype=bool)
    columns.update(_coefficient_check_columns(result, spec_rows))
    columns["source"] = [result.source(int(i)) for i in s_idx]
    if result.total is not None:
        columns["total"] = np.asarray(result.total).reshape(-1)
    columns.update(_datasheet_check_columns(result, spec_rows))
    columns.update(_yield_columns(result, s_idx))
    columns.update(_rate_columns(np.asarray(result.rates).reshape(-1, 3), p_idx))
    for key, column in _bounds_columns(result.profile_bounds, p_idx).items():
        columns[f"profile_{key}"] = column
    attrs = {"method": result.method, "unit": result.unit, "budget": result.budget,
             "criterion": result.criterion, "require": result.require,
             "requirement_met": result.requirement_met}
    if result.yields is not None:
        attrs.update({"yield": result.yields.target, "seed": result.yields.seed})
    return dataframe(_named("select", columns), attrs)


def _coefficient_check_columns(result: SelectionResult, spec_rows: Any) -> dict[str, Any]:
    """``checks.<coefficient>.value|bound|pass`` and the VRE check (docs/model.md
    section 8); a spec-form row has no coefficient checks (JSON: none; CSV: empty): NaN,
    None."""
    rows = len(spec_rows)
    values = np.asarray(result.values).reshape(rows, -1)
    bounds = np.asarray(result.bounds).reshape(rows, -1)
    checks = np.asarray(result.check_pass, dtype=bool).reshape(rows, -1)
    # a bound a fitted profile's recording leaves unknown decides nothing (None)
    unknown = np.isnan(bounds) & (values != 0)
    out: dict[str, Any] = {}
    for b, name in enumerate(BOUNDED):
        out[f"checks.{name}.value"] = np.where(spec_rows, np.nan, values[:, b])
        out[f"checks.{name}.bound"] = np.where(spec_rows, np.nan, bounds[:, b])
        out[f"checks.{name}.pass"] = (checks[:, b] if not (spec_rows.any()
                                                           or unknown[:, b].any()) else
                                      [None if sp or u else bool(c) for sp, u, c in
                                       zip(spec_rows, unknown[:, b], checks[:, b],
                                           strict=True)])
    if result.vre_pass is not None:
        n_s, n_p = len(result.sensors), len(result.profiles)
        out["checks.vre.value"] = np.asarray(result.vre_value).reshape(-1)
        out["checks.vre.bound"] = np.asarray(result.vre_bound).reshape(-1)
        out["checks.vre.pass"] = [result.vre_check(i, j) for i in range(n_s)
                                  for j in range(n_p)]
    return out


def _datasheet_check_columns(result: SelectionResult, spec_rows: Any) -> dict[str, Any]:
    """Datasheet (spec-form) sensors' nonlinearity check: NaN, None on coefficient rows."""
    if result.nl_value is None:
        return {}
    n_p = len(result.profiles)
    return {
        "checks.nonlinearity.value": np.asarray(result.nl_value).reshape(-1),
        "checks.nonlinearity.bound": np.asarray(result.nl_bound).reshape(-1),
        "checks.nonlinearity.pass": [
            result.nl_check(k // n_p, k % n_p) if sp else None
            for k, sp in enumerate(spec_rows.tolist())],
        "checks.nonlinearity.unit": ["%FS" if sp else None for sp in spec_rows.tolist()],
    }


def _yield_columns(result: SelectionResult, s_idx: Any) -> dict[str, Any]:
    """``--yield`` (docs/model.md section 14): NaN, None off the lots."""
    y = result.yields
    if y is None:
        return {}
    return {
        "yield_value": np.asarray(y.value).reshape(-1),
        "yield_method": [y.method if y.is_lot(int(i)) else None for i in s_idx],
        "yield_interval_low": np.asarray(y.low).reshape(-1),
        "yield_interval_high": np.asarray(y.high).reshape(-1),
        "yield_draws": [y.draws if y.is_lot(int(i)) else None for i in s_idx],
    }


def sweep_frame(result: SweepResult) -> Any:
    """``sweep``: one row per sensor × profile × rate Ω_K3 (``rate``), exact and paper.

    Rows in the JSON's order: profiles outermost, then sensors, then rates.
    """
    n_s, n_p, n_r = len(result.sensors), len(result.profiles), len(result.rates)
    p_idx, s_idx, r_idx = (a.reshape(-1) for a in np.indices((n_p, n_s, n_r)))
    columns: dict[str, Any] = {
        "sensor": [result.sensors[i] for i in s_idx],
        "profile": [result.profiles[j] for j in p_idx],
        "rate": np.asarray(result.rates)[r_idx],
    }
    for method in ("exact", "paper"):
        err = getattr(result, method)
        for name in ("total", "rms"):
            columns[f"{method}.{name}"] = np.asarray(getattr(err, name))[s_idx, p_idx, r_idx]
    columns["saturated"] = np.asarray(result.saturated, dtype=bool)[s_idx, p_idx, r_idx]
    return dataframe(_named("sweep", columns), {"method": "exact", "unit": result.unit,
                            "methods": ["exact", "paper"],
                            "paper_refused": dict(result.paper_refused)})


def to_frame(result: Any) -> Any:
    """The tidy DataFrame of any result of :mod:`gyrovib.api` (dispatch on its type)."""
    builders: dict[str, Callable[[Any], Any]] = {
        "AnalysisResult": analysis_frame, "BoundsResult": bounds_frame,
        "SelectionResult": selection_frame, "SweepResult": sweep_frame,
    }
    builder = builders.get(type(result).__name__)
    if builder is None:
        raise TypeError(f"no DataFrame form for {type(result).__name__}")
    return builder(result)
