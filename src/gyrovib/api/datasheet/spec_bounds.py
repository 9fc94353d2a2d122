"""The datasheet checks of ``select`` and the allowable figures of ``bounds --range``.

Spec-form sensors (docs/model.md section 11) against their spec bounds, and the
bounds themselves. Apart from :mod:`gyrovib.api.datasheet.specs` (which still gives
their names) so that ``analyze`` does not define their classes.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from gyrovib import units
from gyrovib.api.datasheet.specs import (
    SpecResults,
    mean_square_acceleration,
    multipliers_of,
    spec_groups,
    terms_of,
)
from gyrovib.api.study.prepare import Prepared
from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import Multipliers
from gyrovib.core.linear import mean_square
from gyrovib.errors import OptionError
from gyrovib.frozen import Frozen

# ----------------------------------------------------------------- select


@dataclass(frozen=True, eq=False, repr=False)
class SpecChecks(Frozen):
    """A spec sensor's datasheet against its own spec bounds, (M, P), deg/s and g.

    ``nl_value``: its nonlinearity in %FS (of its own range or span);
    ``nl_bound``: the allowable NL in the same %FS for Δ* (inf where the
    profile does not excite the envelope); ``vre_value``: its VRE spec in
    deg/s/g² (NaN: none given, taken as 0); ``vre_bound``: the allowable VRE
    (inf without linear vibration). Passes use ``rtol``.
    """

    nl_value: FloatArray
    nl_bound: FloatArray
    nl_pass: NDArray[np.bool_]
    vre_value: FloatArray
    vre_bound: FloatArray
    vre_pass: NDArray[np.bool_]


def spec_checks(prepared: Prepared, spec: SpecResults, method: str, budget: float,
                weights: tuple[float, float] = (1.0, 1.0), rtol: float = 1e-9) -> SpecChecks:
    """NL ≤ NL_max and VRE ≤ VRE_max for every spec sensor × profile (docs/model.md section 11).

    NL_max = w_NL·Δ*/W(1) comes from :func:`gyrovib.core.envelope.spec_bounds_many` for
    the sensor's own range, fit, measure and ``of``, under its own response
    (every distinct datasheet definition of a group in one call).
    """
    # lazy: the datasheet envelope (and HiGHS) only for datasheet sensors
    from gyrovib.core.envelope import spec_bounds_many

    figs = spec.figures
    m_count, n_p = spec.index.size, len(prepared.profiles)
    nl_bound = np.full((m_count, n_p), np.inf)
    vre_bound = np.full((m_count, n_p), np.inf)
    for group, rows in spec_groups(prepared, spec.index):
        m = multipliers_of(group, prepared, method)
        t = terms_of(m)
        s = mean_square_acceleration(m)
        keys: dict[tuple[float, str, str, str], list[int]] = {}
        for k in rows:
            keys.setdefault((float(figs.range[k]), figs.fit[k], figs.measure[k], figs.of[k]),
                            []).append(k)
        # every distinct definition in one call: neighbouring ranges share their work
        defs = list(keys)
        nl_max, vre_max = spec_bounds_many(
            budget, t, s, [d[0] for d in defs], [d[1] for d in defs], [d[2] for d in defs],
            [d[3] for d in defs], weights)
        for d_index, members in enumerate(keys.values()):
            nl_bound[members] = nl_max[d_index][None]
            vre_bound[members] = vre_max[d_index][None]
    nl_value = np.broadcast_to(figs.percent[:, None], (m_count, n_p)).copy()
    vre_value = np.where(figs.has_vre, figs.vre, np.nan)[:, None] * np.ones((1, n_p))
    nl_pass = nl_value <= nl_bound * (1.0 + rtol)
    vre_pass = np.nan_to_num(vre_value) <= vre_bound * (1.0 + rtol)
    return SpecChecks(nl_value, nl_bound, nl_pass, vre_value, vre_bound, vre_pass)


#: The figures a datasheet may leave unpublished, in the order they are reported.
UNKNOWN_FIGURES: tuple[str, ...] = ("vre", "m31", "m32")
#: What an unpublished datasheet figure is taken as: ``none`` (nothing: the
#: verdict stays open, ``unverified``) or ``zero`` (the reading of old).
ASSUMPTIONS = ("none", "zero")


def checks_of(prepared: Prepared, spec: SpecResults | None, method: str, budget: float,
              weights: tuple[float, float] = (1.0, 1.0),
              rtol: float = 1e-9) -> SpecChecks | None:
    """:func:`spec_checks` of the datasheet sensors' worst case ``spec`` (None: none)."""
    return None if spec is None else spec_checks(prepared, spec, method, budget, weights, rtol)


def check_assumption(assume_unknown: str) -> None:
    """Refuse an ``assume_unknown`` that is not one of :data:`ASSUMPTIONS`."""
    if assume_unknown not in ASSUMPTIONS:
        raise OptionError(f"unknown assumption {assume_unknown!r}; use one of "
                          f"{', '.join(ASSUMPTIONS)}")


def is_unverified(passed: bool, unknown: Sequence[str], assume_unknown: str) -> bool:
    """Unknown is not zero (docs/model.md section 11): a verdict that passes on the
    published figures, where an unpublished figure (``unknown``, names of
    :data:`UNKNOWN_FIGURES`) can still decide it, is *unverified* — not passing —
    unless ``assume_unknown`` is ``"zero"``. One rule for ``select`` and ``mission``."""
    return bool(passed) and bool(unknown) and assume_unknown != "zero"


def merge_unknown(names: Iterable[Sequence[str]]) -> tuple[str, ...]:
    """The union of several cells' unknown figures (e.g. a mission's segments), in the
    order of :data:`UNKNOWN_FIGURES`."""
    found = {n for group in names for n in group}
    return tuple(n for n in UNKNOWN_FIGURES if n in found)


@dataclass(frozen=True, eq=False, repr=False)
class UnknownFigures(Frozen):
    """Where a spec sensor's unpublished figure can matter, (M, P) (docs/model.md section 11).

    ``vre``: no VRE spec and the profile has linear vibration (Σ⟨a_j²⟩ > 0);
    ``m31``, ``m32``: datasheets never give them, and the profile's C31 (C32)
    ≠ 0. ``mean_square`` Σ_j⟨a_j²⟩ (g², per profile); ``c31``, ``c32`` the
    multipliers (deg/s², (M, P)): what the unknown figure multiplies.
    """

    vre: NDArray[np.bool_]
    m31: NDArray[np.bool_]
    m32: NDArray[np.bool_]
    mean_square: FloatArray
    c31: FloatArray
    c32: FloatArray

    def names(self, k: int, j: int) -> tuple[str, ...]:
        """The unknown figures of spec sensor ``k`` that can matter under profile ``j``."""
        return tuple(n for n in UNKNOWN_FIGURES if bool(getattr(self, n)[k, j]))


def unknown_figures(prepared: Prepared, spec: SpecResults, method: str) -> UnknownFigures:
    """Which unpublished figures of each spec sensor can change its verdict, per profile.

    An unpublished figure is unknown, not zero: the VRE where the profile has
    linear vibration, m31 (m32) where its x1 (x2) vibration is correlated
    with x3 (C31, C32 ≠ 0, the terms m3i·C3i of eq. (2) then rectify).
    """
    return unknown_figures_at(prepared, spec.index, spec.figures.has_vre, method)


def unknown_figures_at(prepared: Prepared, index: NDArray[np.intp], has_vre: NDArray[np.bool_],
                       method: str) -> UnknownFigures:
    """:func:`unknown_figures` of the spec sensors at ``index`` (rows of
    ``prepared.sensors``) whose VRE is published where ``has_vre``."""
    m_count, n_p = index.size, len(prepared.profiles)
    msq = np.array([0.0 if v is None else float(mean_square(v.moments()))
                    for v in prepared.linear] if prepared.linear else [0.0] * n_p,
                   dtype=float).reshape(n_p)
    c31 = np.zeros((m_count, n_p))
    c32 = np.zeros((m_count, n_p))
    for group, rows in spec_groups(prepared, index):
        m = multipliers_of(group, prepared, method)
        c31[rows] = np.broadcast_to(np.asarray(m.c31, dtype=float), (n_p,))[None]
        c32[rows] = np.broadcast_to(np.asarray(m.c32, dtype=float), (n_p,))[None]
    vre = (~np.asarray(has_vre, dtype=bool))[:, None] & (msq > 0)[None, :]
    return UnknownFigures(vre=vre, m31=c31 != 0, m32=c32 != 0, mean_square=msq,
                          c31=c31, c32=c32)


def selection_fields(n_s: int, n_p: int, spec: SpecResults | None, checks: SpecChecks | None,
                     total: FloatArray, unit: str,
                     vre: tuple[FloatArray, FloatArray, NDArray[np.bool_]]) -> dict[str, Any]:
    """The spec-form fields of a :class:`~gyrovib.api.SelectionResult`.

    ``total`` (|Δ_V|, the worst case for spec sensors) always; ``vre`` the
    coefficient sensors' VRE check (effective VRE and its bound in deg/s per g²,
    pass; docs/model.md section 8), whose spec-form rows are replaced by the datasheet
    VRE against its allowable value (section 11); ``sources`` and the
    nonlinearity check (NaN on coefficient rows) only with spec sensors.
    """
    s = units.scale(unit)
    vre_value, vre_bound = np.array(vre[0], dtype=float), np.array(vre[1], dtype=float)
    vre_pass = np.array(vre[2], dtype=bool)
    out: dict[str, Any] = {"total": total / s}
    if spec is None or checks is None:
        out.update(vre_value=vre_value / s, vre_bound=vre_bound / s, vre_pass=vre_pass)
        return out
    sources = ["coefficients"] * n_s
    for i in spec.index.tolist():
        sources[i] = "specs"

    def full(values: NDArray[Any], fill: float = np.nan) -> FloatArray:
        array = np.full((n_s, n_p), fill)
        array[spec.index] = values
        return array

    vre_value[spec.index] = checks.vre_value
    vre_bound[spec.index] = checks.vre_bound
    vre_pass[spec.index] = checks.vre_pass
    out.update(
        sources=tuple(sources),
        nl_value=full(checks.nl_value), nl_bound=full(checks.nl_bound),
        nl_pass=full(checks.nl_pass, True).astype(bool),
        vre_value=vre_value / s, vre_bound=vre_bound / s, vre_pass=vre_pass,
    )
    return out


# ----------------------------------------------------------------- bounds


@dataclass(frozen=True, eq=False, repr=False)
class DatasheetBounds(Frozen):
    """Allowable datasheet figures for a part of range R, per profile (``bounds --range``).

    ``nonlinearity``: NL_max in %FS of R (``of`` range) or of 2R (span), inf
    where the profile does not excite the envelope; ``vre``: VRE_max in the
    output unit per g² (inf without linear vibration); ``range`` R in the
    output unit; ``fit``, ``measure``, ``of``: the definition the NL is read
    with; ``weights``: the NL:VRE split; ``w1``: W(1), the worst case for a
    limit b = 1 (rate per rate); ``share_nl``, ``share_vre``: the fractions
    of Δ* (docs/model.md section 11: NL_max·W(1) = share_nl·Δ*).
    """

    range: float
    fit: str
    measure: str
    of: str
    weights: tuple[float, float]
    nonlinearity: FloatArray
    vre: FloatArray
    w1: FloatArray
    share_nl: FloatArray
    share_vre: FloatArray


def datasheet_bounds(m: Multipliers | None, n_profiles: int, budget: float, range_: float,
                     unit: str, fit: str = "least-squares", measure: str = "max",
                     of: str = "range",
                     weights: tuple[float, float] = (1.0, 1.0)) -> DatasheetBounds:
    """NL_max and VRE_max of :func:`gyrovib.core.envelope.spec_bounds`, in output units.

    ``budget`` and ``range_`` in deg/s; ``m`` the profiles' multipliers (the
    profile alone, ν_sensor = 1), None when there are no profiles.
    """
    # lazy: the datasheet envelope (and HiGHS) only for datasheet sensors
    from gyrovib.core.envelope import spec_bounds

    s = units.scale(unit)
    if m is None or n_profiles == 0:
        empty = np.zeros(0)
        return DatasheetBounds(range_ / s, fit, measure, of, weights, empty, empty, empty,
                               empty, empty)
    sb = spec_bounds(budget, terms_of(m), mean_square_acceleration(m), range_, fit, measure,
                     of, weights)
    return DatasheetBounds(range_ / s, fit, measure, of, weights, sb.nonlinearity,
                           sb.vre / s, sb.w1, sb.share_nl, sb.share_vre)
