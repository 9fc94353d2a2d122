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

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from gyrovib.core.analysis import ALL_TERMS as JSON_TERMS
from gyrovib.core.analysis import MULTIPLICATIVE_TERMS
from gyrovib.core.envelope import COEFFICIENTS as WORST_COEFFICIENTS
from gyrovib.core.synthesis import BOUNDED, ODD_PARTS, PARTS
from gyrovib.presentation.reasons import reason
from gyrovib.records import MISSING_PANDAS as MISSING_PANDAS
from gyrovib.records import MissingDependency as MissingDependency
from gyrovib.records import dataframe

if TYPE_CHECKING:
    from gyrovib.api import AnalysisResult, BoundsResult, SelectionResult, SweepResult

AXES = ("x1", "x2", "x3")


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


def analysis_frame(result: AnalysisResult) -> Any:
    """``analyze``: one row per sensor × profile, profiles outermost (the JSON's order)."""
    n_s, n_p = len(result.sensors), len(result.profiles)
    p_idx, s_idx = (a.reshape(-1) for a in np.indices((n_p, n_s)))
    err = result.error
    terms = np.asarray(err.additive_terms)[s_idx, p_idx].reshape(n_s * n_p, -1)
    qs = np.asarray(err.multiplicative_coefficients)[s_idx, p_idx].reshape(n_s * n_p, -1)
    columns: dict[str, Any] = {
        "sensor": [result.sensors[i] for i in s_idx],
        "profile": [result.profiles[j] for j in p_idx],
        **_rate_columns(np.asarray(result.rates).reshape(-1, 3), p_idx),
    }
    extra = np.asarray(err.extra_terms)[s_idx, p_idx].reshape(n_s * n_p, -1)
    values = np.concatenate([terms, extra], axis=1)
    columns.update({f"additive_terms.{t}": values[:, k] for k, t in enumerate(JSON_TERMS)})
    columns.update({f"multiplicative_coefficients.{q}": qs[:, k] for k, q in
                    enumerate(MULTIPLICATIVE_TERMS[:qs.shape[1]])})
    for name in ("additive", "multiplicative", "total", "rms"):
        columns[name] = np.asarray(getattr(err, name))[s_idx, p_idx]
    if result.stderr is not None:
        columns["stderr"] = np.asarray(result.stderr)[s_idx, p_idx]
    columns["source"] = [result.source(int(i)) for i in s_idx]
    columns.update(_envelope_columns(result, s_idx, p_idx))
    columns["saturated"] = np.asarray(result.saturated, dtype=bool)[s_idx, p_idx]
    columns.update(_phase_columns(result, s_idx, p_idx))
    columns["warnings"] = [tuple(result.warnings.get((int(i), int(j)), ()))
                           for i, j in zip(s_idx, p_idx, strict=True)]
    attrs: dict[str, Any] = {"method": result.method, "unit": result.unit}
    if result.samples is not None:
        attrs.update(samples=result.samples, seed=result.seed)
    return dataframe(_named("analyze", columns), attrs)


def _envelope_columns(result: AnalysisResult, s_idx: Any, p_idx: Any) -> dict[str, Any]:
    """A datasheet sensor's worst polynomial and RMS bound (section 11); a lot's
    uncertainty (section 14): NaN where not known."""
    out: dict[str, Any] = {}
    if result.worst_coefficients is not None and result.rms_bound is not None:
        worst = np.asarray(result.worst_coefficients)[s_idx, p_idx]
        for k, name in enumerate(WORST_COEFFICIENTS):
            out[f"envelope.worst_coefficients.{name}"] = worst[:, k]
        out["envelope.rms_bound"] = np.asarray(result.rms_bound)[s_idx, p_idx]
    if result.uncertainty is not None:
        out["uncertainty_total"] = np.asarray(result.uncertainty)[s_idx, p_idx]
        out["lot_mean"] = [result.is_lot(int(i)) for i in s_idx]
    return out


def _phase_columns(result: AnalysisResult, s_idx: Any, p_idx: Any) -> dict[str, Any]:
    """The phases found for ``phase: worst`` orders (None elsewhere), when any were."""
    if not result.worst_phases:
        return {}
    return {"worst_phases": [
        None if (int(i), int(j)) not in result.worst_phases
        else [dict(g) for g in result.worst_phases[(int(i), int(j))]]
        for i, j in zip(s_idx, p_idx, strict=True)]}


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
    out: dict[str, Any] = {}
    for b, name in enumerate(BOUNDED):
        out[f"checks.{name}.value"] = np.where(spec_rows, np.nan, values[:, b])
        out[f"checks.{name}.bound"] = np.where(spec_rows, np.nan, bounds[:, b])
        out[f"checks.{name}.pass"] = (checks[:, b] if not spec_rows.any() else
                                      [None if sp else bool(c) for sp, c in
                                       zip(spec_rows, checks[:, b], strict=True)])
    if result.vre_pass is not None:
        out["checks.vre.value"] = np.asarray(result.vre_value).reshape(-1)
        out["checks.vre.bound"] = np.asarray(result.vre_bound).reshape(-1)
        out["checks.vre.pass"] = np.asarray(result.vre_pass, dtype=bool).reshape(-1)
    return out


def _datasheet_check_columns(result: SelectionResult, spec_rows: Any) -> dict[str, Any]:
    """Datasheet (spec-form) sensors' nonlinearity check: NaN, None on coefficient rows."""
    if result.nl_value is None:
        return {}
    return {
        "checks.nonlinearity.value": np.asarray(result.nl_value).reshape(-1),
        "checks.nonlinearity.bound": np.asarray(result.nl_bound).reshape(-1),
        "checks.nonlinearity.pass": [
            bool(v) if sp else None for sp, v in
            zip(spec_rows, np.asarray(result.nl_pass).reshape(-1), strict=True)],
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
