"""The cells of an analysis result that every format of it shares: which terms are
shown and under what label, the marks (saturated, lot, unknown term), u(Δ_V), the
rows' order, warnings grouped, and the notes under a table."""

from __future__ import annotations

from collections.abc import Iterator

from gyrovib.api import AnalysisResult
from gyrovib.api.datasheet.specs import UNKNOWN_TERM_NOTES
from gyrovib.api.evaluation.results import JSON_TERMS as _JSON_TERMS
from gyrovib.core.analysis import ADDITIVE_TERMS
from gyrovib.render.common import fmt, number

_ADDITIVE_LABELS = ("Δ0 A1", "Δ0 k2", "Δ0 k4", "Δ0 m31", "Δ0 m32")
#: The JSON keys of ``additive_terms`` (Δ0(1..5), g2 = Δ0(6), k3, k5): one order for
#: JSON, CSV, tables and frames.
JSON_TERMS = _JSON_TERMS
#: The odd-moment terms of locked harmonics (docs/model.md section 10), k3·M3 and k5·M5:
#: always in JSON (0 where x3 is symmetric), in tables only where a profile has them.
ODD_TERMS: tuple[str, ...] = ("k3", "k5")
_LABELS = dict(zip(JSON_TERMS, (*_ADDITIVE_LABELS, "Δ0 g²", "Δ0 k3", "Δ0 k5"), strict=True))
#: Where Δ0(6), the g² term, stands among :data:`JSON_TERMS`.
G2_INDEX = JSON_TERMS.index("g2")
#: The mark of a saturating sensor in tables (docs/model.md section 9).
SATURATED_MARK = "SAT"


def unknown_term(result: AnalysisResult, i: int, j: int) -> bool:
    """Whether the g² term of sensor ``i`` under profile ``j`` is unknown because its
    figure is (a VRE not published, a g² sensitivity not given): the term reads "?",
    never 0, and so do Δ_VA, Δ_V and Δ_V(RMS), which hold it (NaN in the result)."""
    return any(w in UNKNOWN_TERM_NOTES for w in result.warnings.get((i, j), ()))


def _shown(linear: bool, odd: bool) -> tuple[int, ...]:
    """Indices into :data:`JSON_TERMS` of the terms shown: Δ0(6) with a linear
    vibration, k3/k5 with locked harmonics."""
    return tuple(k for k, t in enumerate(JSON_TERMS)
                 if t in ADDITIVE_TERMS or (t == "g2" and linear) or (t in ODD_TERMS and odd))


def _all_terms(result: AnalysisResult, i: int, j: int) -> list[float]:
    e = result.error
    return [*map(float, e.additive_terms[i, j]), *map(float, e.extra_terms[i, j])]


def _terms(result: AnalysisResult, i: int, j: int, odd: bool) -> list[float]:
    """The additive terms of a row as tables and CSV show them."""
    values = _all_terms(result, i, j)
    return [values[k] for k in _shown(result.has_linear, odd)]


def _labels(result: AnalysisResult, odd: bool) -> tuple[str, ...]:
    return tuple(_LABELS[JSON_TERMS[k]] for k in _shown(result.has_linear, odd))


def _saturated(result: AnalysisResult, i: int, j: int) -> bool:
    sat = result.saturated
    return bool(sat is not None and sat[i, j])


def _saturation_note(result: AnalysisResult) -> str:
    return (f"{SATURATED_MARK}: saturated, |Ω_K3| + Σ tone amplitudes + locked peaks + "
            f"{result.peak_factor:g}σ at the nonlinear element exceeds the sensor's range "
            "(docs/model.md section 9): the error shown does not hold.")


def _u(result: AnalysisResult, i: int, j: int) -> float | None:
    """u(Δ_V) of a cell (docs/model.md section 14), None where the sensor has none."""
    u = result.uncertainty
    return None if u is None else number(u[i, j])


def _u_text(result: AnalysisResult, i: int, j: int) -> str:
    """u(Δ_V) for a table: '-' where not known (no uncertainty, or searched phases)."""
    u = _u(result, i, j)
    return "-" if u is None else fmt(u, 2)


def _lot_name(result: AnalysisResult, i: int) -> str:
    return result.sensors[i] + (f" {LOT_MARK}" if result.is_lot(i) else "")


#: The mark of a lot sensor, analysed at its mean, in tables.
LOT_MARK = "(lot)"
_UNCERTAINTY_NOTE = ("u(Δ_V): standard uncertainty (k = 1) of Δ_V from the coefficients' "
                     "uncertainty, √(gᵀΣg) with Δ_V = gᵀc (docs/model.md section 14); '-' where "
                     "not known. A sensor marked (lot) is a production lot, analysed at "
                     "its mean coefficients; its u is the spread of Δ_V over the lot.")


def _rows(result: AnalysisResult) -> Iterator[tuple[int, int]]:
    for j in range(len(result.profiles)):
        for i in range(len(result.sensors)):
            yield i, j


#: Below this fraction of a row's largest value, a number is rounding noise: shown as 0.
NEGLIGIBLE_IN_ROW = 1e-12


def row_cells(values: list[float], digits: int = 4) -> list[str]:
    """A table row's numbers, those below :data:`NEGLIGIBLE_IN_ROW` of its largest as 0."""
    finite = [abs(v) for v in values if v == v and abs(v) != float("inf")]
    scale = max(finite, default=0.0)
    return ["?" if v != v else "0" if scale > 0 and abs(v) < NEGLIGIBLE_IN_ROW * scale
            else fmt(v, digits) for v in values]  # NaN: unknown


def grouped_warnings(result: AnalysisResult) -> list[tuple[str, list[tuple[int, int]]]]:
    """Each distinct warning once, with the (sensor, profile) cells it applies to, in the
    order they first appear (profile by profile, sensor by sensor)."""
    found: dict[str, list[tuple[int, int]]] = {}
    for j in range(len(result.profiles)):
        for i in range(len(result.sensors)):
            for message in result.warnings.get((i, j), ()):
                found.setdefault(message, []).append((i, j))
    return list(found.items())


def cells_text(result: AnalysisResult, cells: list[tuple[int, int]]) -> str:
    """Where a warning applies, compactly: sensors sharing their profiles named together."""
    by_sensor: dict[int, list[int]] = {}
    for i, j in cells:
        by_sensor.setdefault(i, []).append(j)
    groups: dict[tuple[int, ...], list[int]] = {}
    for i, found in by_sensor.items():
        groups.setdefault(tuple(found), []).append(i)
    every = tuple(range(len(result.profiles)))
    parts = []
    for profiles, sensors in groups.items():
        where = ("every profile" if profiles == every and len(every) > 1
                 else ", ".join(result.profiles[j] for j in profiles))
        parts.append(f"{', '.join(result.sensors[i] for i in sensors)} under {where}")
    return "; ".join(parts)


_SPECS_NOTE = ("Datasheet (spec-form) sensors: Δ_V is the worst |Δ_V| over every conversion "
               "function their datasheet permits, the terms those of the polynomial attaining "
               "it (m31 = m32 = 0), Δ_V(RMS) the RMS of the per-term maxima "
               "(docs/datasheets.md).")


def _numeric_note(result: AnalysisResult) -> str:
    return (f"Numeric: Δ_V is the average of eq. (2) over up to {result.samples} points per "
            f"sensor × profile (seed {result.seed}) minus eq. (2) at rest, ± its standard "
            "error (0 where the phase grid is exact); the other columns apply the term "
            "formulas to the sample moments of the same points.")
