"""``select``: which sensors meet a budget, by the bound checks and eq. (17)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from gyrovib import units
from gyrovib.api.commands.bounds import (
    check_method_budget,
    profile_bounds,
    resolve_allocation,
)
from gyrovib.api.datasheet import spec_bounds, specs
from gyrovib.api.evaluation.checks import PASS_RTOL as PASS_RTOL
from gyrovib.api.evaluation.checks import (
    BoundVerdict,
    CoefficientChecks,
    at_most,
)
from gyrovib.api.evaluation.evaluate import (
    Saturation,
    bound_verdicts,
    errors,
    phase_worst,
    saturation,
    worst_case,
)
from gyrovib.api.evaluation.results import Limit, SelectionResult
from gyrovib.api.evaluation.unknown import (
    unknown_bounds,
    unknown_errors,
    unrecorded_cells,
    unrecorded_limits,
)
from gyrovib.api.lots.yields import (
    DEFAULT_DRAWS,
    DEFAULT_SEED,
    check_yield_options,
    judge,
    lot_yields,
    notes,
    open_lots,
    yield_limits,
)
from gyrovib.api.study.convert import bound_factors, catalog_unit
from gyrovib.api.study.prepare import (
    Group,
    Prepared,
    check_bounds,
    check_finite,
    float_guard,
)
from gyrovib.api.study.study import Study, check_peak_factor
from gyrovib.catalog.loader import Catalog
from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import COEFFICIENTS
from gyrovib.core.linear import effective_vre, mean_square
from gyrovib.core.saturation import DEFAULT_PEAK_FACTOR
from gyrovib.core.synthesis import BOUNDED, AllocationConstants, coefficient_bounds
from gyrovib.errors import OptionError
from gyrovib.models import Allocation

CRITERIA = ("bounds", "rms", "worst", "both")
REQUIREMENTS = ("any", "all")
#: What an unpublished datasheet figure is taken as (:data:`spec_bounds.ASSUMPTIONS`).
ASSUMPTIONS = spec_bounds.ASSUMPTIONS


def _limits(criterion: str, failing: NDArray[np.intp], verdicts: Sequence[BoundVerdict],
            rms: FloatArray, budget: float, total: FloatArray,
            found: Saturation) -> dict[int, Limit]:
    """Per failing sensor, the largest value/bound ratio (or Δ_V(RMS)/Δ*) that counts.

    Under ``bounds`` and ``both`` each form's verdict names its own candidates (a
    coefficient sensor its worst check, a datasheet sensor its nonlinearity and VRE
    against their spec bounds); ``total``: |Δ_V| for the ``worst`` criterion.
    Saturation comes first: a sensor that saturates somewhere is limited by its
    range (``"saturated"``, ratio reach/range, the worst profile).
    """
    limits: dict[int, Limit] = {}
    over = found.reach / found.ranges[:, None]
    where = {int(i): (v, r) for v in verdicts for r, i in enumerate(v.rows.tolist())}
    for i in failing.tolist():
        if found.saturated[i].any():
            js = np.flatnonzero(found.saturated[i])
            j = int(js[np.argmax(over[i, js])])
            limits[int(i)] = Limit("saturated", j, float(over[i, j]))
            continue
        candidates: list[Limit] = []
        if criterion in ("bounds", "both"):
            verdict, row = where[int(i)]
            candidates.extend(verdict.limits(row))
        if criterion in ("rms", "both"):
            jr = int(np.argmax(rms[i]))
            candidates.append(Limit("rms", jr, float(rms[i, jr] / budget)))
        if criterion == "worst":
            jw = int(np.argmax(total[i]))
            candidates.append(Limit("worst", jw, float(total[i, jw] / budget)))
        limits[int(i)] = max(candidates, key=lambda c: c.ratio)
    return limits


def select(
    catalog: Catalog,
    *,
    sensors: Sequence[str] = (),
    profiles: Sequence[str] = (),
    method: str = "exact",
    rate: Sequence[float] | None = None,
    budget: float,
    unit: str = "deg/s",
    criterion: str = "bounds",
    require: str = "any",
    allocation: Allocation | Sequence[float] | None = None,
    spec_weights: tuple[float, float] = (1.0, 1.0),
    peak_factor: float = DEFAULT_PEAK_FACTOR,
    assume_unknown: str = "none",
    yield_target: float | None = None,
    seed: int = DEFAULT_SEED,
    draws: int = DEFAULT_DRAWS,
) -> SelectionResult:
    """Which sensors meet the budget: the bound checks and eq. (17), per profile.

    Each sensor's bounds include its input-side response ν_sensor(f), the one
    written ``at: input`` (an output filter earns no credit; computed once
    per distinct response). ``criterion``: ``bounds`` (every |coefficient| at
    most its bound, and the effective VRE |Δ0(6)|/Σ⟨a_j²⟩ at most the ``vre``
    bound where a profile has linear vibration, docs/model.md section 8), ``rms``
    (Δ_V(RMS) ≤ Δ*, eq. 17, with Δ0(6) in it) or ``both``. A sensor
    passes when it passes under every chosen profile; ``require`` ``any``
    (at least one sensor passes) or ``all`` decides :attr:`requirement_met`.
    ``budget`` and ``rate`` are in deg/s; ``unit`` is the output unit.

    ``worst``: the direct test |Δ_V| ≤ Δ*. A spec-form sensor (docs/model.md
    section 11) is judged by its datasheet: under ``bounds`` its nonlinearity
    (%FS) and VRE against the spec bounds of its own range, fit and measure
    (Δ* split ``spec_weights`` = NL:VRE), under ``rms`` its per-term RMS
    bound, under ``worst`` its worst |Δ_V| over the envelope; its margin is
    always Δ*/worst |Δ_V| (and every sensor's is Δ*/|Δ_V| under ``worst``).

    A sensor that saturates under a profile (docs/model.md section 9: |Ω_K3| +
    Σ tone amplitudes + locked peaks + κσ3 at its nonlinear element above its
    range, κ = ``peak_factor``) fails there whatever the criterion: the
    static model behind both tests does not hold (:attr:`SelectionResult.saturation`).

    An unpublished datasheet figure is unknown, not zero (docs/model.md section 11):
    where a spec-form sensor passes on its published figures but one it lacks
    can matter under the profile (the VRE under linear vibration; m31, m32
    under cross-axis vibration correlated with x3), it is ``unverified`` there:
    not passed, not ranked, with the figures that would decide it
    (:attr:`SelectionResult.questions`). ``assume_unknown="zero"`` takes them
    as 0 instead, and the result records that it did.

    ``yield_target`` Y (0 < Y < 1): a production lot (``lot:``) passes a profile when
    the yield of a part drawn from it is at least Y (docs/model.md section 14,
    :mod:`gyrovib.api.lots.yields`: exact under ``worst``, else Monte Carlo with ``draws``
    draws seeded by ``seed``); without it a lot is judged at its mean.
    """
    _check_options(method, budget, criterion, require, assume_unknown, yield_target, seed,
                   draws)
    resolve_allocation(catalog, method, allocation)  # its refusal before the entries'
    check_peak_factor(peak_factor)
    study = Study.of(catalog, sensors=sensors, profiles=profiles, rate=rate)
    return selection_of(study, method=method, budget=budget, unit=unit, criterion=criterion,
                        require=require, allocation=allocation, spec_weights=spec_weights,
                        peak_factor=peak_factor, assume_unknown=assume_unknown,
                        yield_target=yield_target, seed=seed, draws=draws)


def _check_options(method: str, budget: float, criterion: str, require: str,
                   assume_unknown: str = "none", yield_target: float | None = None,
                   seed: int = DEFAULT_SEED, draws: int = DEFAULT_DRAWS) -> None:
    check_method_budget(method, budget)
    if yield_target is not None:
        check_yield_options(yield_target, draws, seed)
    if criterion not in CRITERIA:
        raise OptionError(f"unknown criterion {criterion!r}; use one of {', '.join(CRITERIA)}")
    if require not in REQUIREMENTS:
        raise OptionError(f"unknown requirement {require!r}; use one of {', '.join(REQUIREMENTS)}")
    spec_bounds.check_assumption(assume_unknown)


def selection_of(study: Study, *, method: str = "exact", budget: float, unit: str = "deg/s",
                 criterion: str = "bounds", require: str = "any",
                 allocation: Allocation | Sequence[float] | None = None,
                 spec_weights: tuple[float, float] = (1.0, 1.0),
                 peak_factor: float = DEFAULT_PEAK_FACTOR,
                 assume_unknown: str = "none",
                 yield_target: float | None = None,
                 seed: int = DEFAULT_SEED,
                 draws: int = DEFAULT_DRAWS) -> SelectionResult:
    """:func:`select` as a view of a :class:`~gyrovib.api.study.study.Study`."""
    _check_options(method, budget, criterion, require, assume_unknown, yield_target, seed,
                   draws)
    unit = units.canonical_unit(unit)
    constants = resolve_allocation(study.catalog, method, allocation)
    with float_guard():
        alone_study, _, alone = profile_bounds(study, method, budget, constants, unit)
        alone = unknown_bounds(alone_study.profiles, alone)
        prepared = study.prepare(methods=(method,), peak_factor=peak_factor)
        limits_deg, vre_bound_deg = _coefficient_limits(prepared, method, budget, constants)
        parts, total, spec = _errors(study, prepared, method)
        rms = parts["rms"]
        # a datasheet sensor saturates against its datasheet range (specs.range)
        found = saturation(prepared)
        checks = CoefficientChecks(_coefficient_values(prepared), limits_deg,
                                   _effective_vre(prepared), vre_bound_deg)
        own = spec_bounds.checks_of(prepared, spec, method, budget, spec_weights, PASS_RTOL)
        values, limits_out = _checked(prepared, checks, rms, total, unit)
        verdicts = bound_verdicts(prepared, checks, own)
        tests = {"bounds": _joined(prepared, verdicts, lambda v: v.passed, False),
                 "rms": at_most(rms, budget), "worst": at_most(total, budget)}
        # saturation fails a sensor whatever the criterion (docs/model.md section 9)
        passed = _decided(criterion, tests) & ~found.saturated
        unknown, questions = _unknowns(prepared, spec, own, method, criterion, passed,
                                       budget, rms, total, unit)
        _unknown_g2(prepared, criterion, passed, budget, rms, total, vre_bound_deg, unit,
                    unknown, questions)
        unverified = _unverified(passed, unknown, assume_unknown)
        unrecorded_cells(prepared, passed, unverified, unknown)
        yields = None if yield_target is None else lot_yields(
            prepared, parts, method, criterion, budget, limits_deg, checks.vre_pass,
            yield_target, seed=seed, draws=draws, rtol=PASS_RTOL)
        if yields is not None:
            passed = judge(yields, passed, found.saturated)
            open_lots(yields, passed, unverified, unknown, questions, assume_unknown)
        sensor_pass = np.all(passed, axis=1)
        # a sensor that fails somewhere on its published figures (not only unverified)
        fails = np.any(~passed & ~unverified, axis=1)
        judged = _joined(prepared, verdicts, lambda v: v.judged(criterion, rms, total), 0.0)
        margin, worst, ranking = _ranking(judged, budget, ~sensor_pass & ~fails)
        limits = _limits(criterion, np.nonzero(fails)[0], verdicts, rms, budget, total, found)
        largest = _joined(prepared, verdicts, lambda v: v.largest, 0.0)
        disagrees = _disagreements(criterion, passed | unverified, found.saturated, tests)
        saturating = _saturating(found.saturated, found.reach, found.ranges, unit)
        if yields is not None:
            limits = yield_limits(yields, limits, sensor_pass, found.saturated)
    met = bool(np.any(sensor_pass)) if require == "any" else bool(np.all(sensor_pass))
    criterion_margin = _criterion_margin(criterion, largest, rms, total, budget)
    rms, total, margin, criterion_margin = unknown_errors(unknown, rms, total, margin,
                                                          criterion_margin)
    fields = spec_bounds.selection_fields(len(prepared.sensors), len(prepared.profiles), spec,
                                          own, total, unit,
                                          (checks.vre, vre_bound_deg, checks.vre_pass))
    limits_out, fields["vre_bound"] = unrecorded_limits(prepared.profiles, limits_out,
                                                        fields["vre_bound"], BOUNDED)
    if fields.get("nl_bound") is not None:  # a datasheet part's NL bound rests on x3
        fields["nl_bound"] = unrecorded_limits(prepared.profiles, fields["nl_bound"][..., None],
                                               fields["vre_bound"], ("k2",))[0][..., 0]
    if assume_unknown != "zero":
        _unknown_vre_shown(fields, unknown)
    s = units.scale(unit)
    return SelectionResult(
        method=method,
        unit=unit,
        budget=budget / s,
        criterion=criterion,
        require=require,
        sensors=tuple(e.sensor.id for e in prepared.sensors),
        profiles=tuple(p.profile.id for p in prepared.profiles),
        rates=prepared.rates / s,
        profile_bounds=alone,
        values=values,
        bounds=limits_out,
        check_pass=checks.check_pass,
        rms=rms / s,
        margin=margin,
        bounds_pass=tests["bounds"],
        rms_pass=tests["rms"],
        passed=passed,
        sensor_pass=sensor_pass,
        worst_margin=worst,
        ranking=ranking,
        limits=limits,
        requirement_met=met,
        allocation=constants,
        **fields,
        saturated=found.saturated,
        saturation=saturating,
        peak_factor=peak_factor,
        unverified=unverified,
        criterion_margin=criterion_margin,
        disagrees=disagrees,
        unknown=unknown,
        questions=questions,
        assume_unknown=assume_unknown,
        coefficient_unit=catalog_unit([e.unit for e in prepared.sensors])
        or catalog_unit([p.unit for p in prepared.profiles]),
        yields=yields,
        notes=notes(prepared, yield_target, yields),
    )


def _coefficient_limits(prepared: Prepared, method: str, budget: float,
                        constants: AllocationConstants) -> tuple[FloatArray, FloatArray]:
    """Each sensor's coefficient bounds, eq. (23)/(25), (sensors, profiles, BOUNDED), and
    its ``vre`` bound (sensors, profiles), deg/s, under its own response."""
    n_s, n_p = len(prepared.sensors), len(prepared.profiles)
    limits = np.full((n_s, n_p, len(BOUNDED)), np.inf)
    vre_bound = np.full((n_s, n_p), np.inf)
    for group in prepared.groups:
        cb = coefficient_bounds(group.multipliers[method], budget, constants)
        limits[group.index] = cb.stacked()[None]
        if cb.vre is not None:
            vre_bound[group.index] = cb.vre[None]
    return limits, vre_bound


def _errors(study: Study, prepared: Prepared, method: str,
            ) -> tuple[dict[str, FloatArray], FloatArray, specs.SpecResults | None]:
    """Every sensor's error terms (deg/s); |Δ_V|, under ``exact`` at the worst phases of
    ``phase: worst`` orders; and the datasheet sensors' worst case."""
    parts = errors(study, prepared, method)
    total = np.abs(parts["total"])
    spec = worst_case(study, prepared, method)
    if method == "exact":
        for group in prepared.groups:
            _worst_phase_totals(prepared, group, total)
    return parts, total, spec


def _coefficient_values(prepared: Prepared) -> FloatArray:
    """|coefficient| of :data:`BOUNDED` per (sensor, profile), deg/s powers."""
    n_s, n_p = len(prepared.sensors), len(prepared.profiles)
    values = np.abs(prepared.coefficients[:, [COEFFICIENTS.index(c) for c in BOUNDED]])
    out: FloatArray = np.broadcast_to(values[:, None, :], (n_s, n_p, len(BOUNDED)))
    return out


def _checked(prepared: Prepared, checks: CoefficientChecks, rms: FloatArray,
             total: FloatArray, unit: str) -> tuple[FloatArray, FloatArray]:
    """The coefficients and their bounds in ``unit``, every array checked finite first."""
    check_finite([rms, total, checks.vre], prepared)
    check_bounds(checks.limits, prepared)
    factors = np.array([bound_factors(unit)[c] for c in BOUNDED])
    values, limits = checks.values * factors, checks.limits * factors
    check_finite([values], prepared, what=f"a coefficient in {unit}")
    check_bounds(limits, prepared)
    return values, limits


def _joined(prepared: Prepared, verdicts: Sequence[BoundVerdict],
            take: Callable[[BoundVerdict], NDArray[Any]], fill: float | bool) -> NDArray[Any]:
    """One (sensors, profiles) array of what ``take`` reads from each form's verdict."""
    out = np.full((len(prepared.sensors), len(prepared.profiles)), fill)
    for verdict in verdicts:
        out[verdict.rows] = take(verdict)
    return out


def _decided(criterion: str, tests: dict[str, NDArray[np.bool_]]) -> NDArray[np.bool_]:
    """The verdict of ``criterion`` (``both``: bounds and rms)."""
    out = np.ones_like(tests["bounds"])
    for name in DECIDED_BY[criterion]:
        out = out & tests[name]
    return out


def _unverified(passed: NDArray[np.bool_], unknown: dict[tuple[int, int], tuple[str, ...]],
                assume_unknown: str) -> NDArray[np.bool_]:
    """The cells that pass on their published figures but whose unknown ones can still
    decide them (docs/model.md section 11); they no longer pass (``passed`` changed)."""
    unverified = np.zeros(passed.shape, dtype=bool)
    for (i, j), names in unknown.items():
        if spec_bounds.is_unverified(bool(passed[i, j]), names, assume_unknown):
            unverified[i, j] = True
            passed[i, j] = False
    return unverified


def _saturating(saturated: NDArray[np.bool_], reach: FloatArray, ranges: FloatArray,
                unit: str) -> dict[tuple[int, int], tuple[float, float]]:
    """Per saturating (sensor, profile): its reach and range, from deg/s (``reach``
    (sensors, profiles), ``ranges`` (sensors,)) into ``unit``."""
    s = units.scale(unit)
    return {(i, j): (float(reach[i, j]) / s, float(ranges[i]) / s)
            for i, j in (tuple(int(v) for v in ij) for ij in np.argwhere(saturated))}


def _ranking(judged: FloatArray, budget: float, open_: NDArray[np.bool_],
             ) -> tuple[FloatArray, FloatArray, tuple[int, ...]]:
    """The margins Δ*/x per cell, each sensor's worst, and the ranking by it (an
    unverified sensor, ``open_``, is not ranked on its margin: it follows the others)."""
    n_s, n_p = judged.shape
    margin = np.where(judged > 0, budget / np.where(judged > 0, judged, 1.0), np.inf)
    worst = margin.min(axis=1) if n_p else np.full(n_s, np.inf)
    ranking = tuple(int(i) for i in sorted(range(n_s),
                                           key=lambda i: (bool(open_[i]), -worst[i], i)))
    return margin, worst, ranking


def _criterion_margin(criterion: str, largest: FloatArray, rms: FloatArray,
                      total: FloatArray, budget: float) -> FloatArray:
    """The margin of the test that decides each cell: 1/largest ratio for the bounds,
    Δ*/x for the direct tests (``both``: the lesser)."""
    bounds_margin = np.where(largest > 0, 1.0 / np.where(largest > 0, largest, 1.0), np.inf)
    margins = {"bounds": bounds_margin, "rms": _inverse(rms, budget),
               "worst": _inverse(total, budget)}
    out: FloatArray = margins[DECIDED_BY[criterion][0]]
    for name in DECIDED_BY[criterion][1:]:
        out = np.minimum(out, margins[name])
    return out


def _unknown_vre_shown(fields: dict[str, Any],
                       unknown: dict[tuple[int, int], tuple[str, ...]]) -> None:
    """A VRE that is not known is neither shown to pass nor shown as 0."""
    if not any("vre" in names for names in unknown.values()):
        return
    shown = np.array(fields["vre_pass"], dtype=bool)
    value = np.array(fields["vre_value"], dtype=float)
    for (i, j), names in unknown.items():
        if "vre" in names:
            shown[i, j] = False
            value[i, j] = np.nan
    fields["vre_pass"], fields["vre_value"] = shown, value


def _inverse(value: FloatArray, budget: float) -> FloatArray:
    """Δ*/value, +inf where the value is 0."""
    out: FloatArray = np.where(value > 0, budget / np.where(value > 0, value, 1.0), np.inf)
    return out


#: The tests a cell can be judged by, in the order ``disagrees`` names them.
TESTS = ("bounds", "rms", "worst")
#: The tests each criterion is decided by.
DECIDED_BY = {"bounds": ("bounds",), "rms": ("rms",), "worst": ("worst",),
              "both": ("bounds", "rms")}


def _disagreements(criterion: str, verdict: NDArray[np.bool_], saturated: NDArray[np.bool_],
                   tests: dict[str, NDArray[np.bool_]]) -> dict[tuple[int, int], tuple[str, ...]]:
    """Per (sensor, profile): the tests, other than the criterion's, that would decide
    otherwise than ``verdict`` (the verdict on the published figures). A saturated cell
    fails every test (docs/model.md section 9): none disagrees there."""
    others = [t for t in TESTS if t not in DECIDED_BY[criterion]]
    out: dict[tuple[int, int], tuple[str, ...]] = {}
    for i, j in np.argwhere(~saturated).tolist():
        names = tuple(t for t in others if bool(tests[t][i, j]) != bool(verdict[i, j]))
        if names:
            out[(int(i), int(j))] = names
    return out


def _unknowns(prepared: Prepared, spec: specs.SpecResults | None,
              own: spec_bounds.SpecChecks | None, method: str, criterion: str,
              passed: NDArray[np.bool_], budget: float, rms: FloatArray, total: FloatArray,
              unit: str) -> tuple[dict[tuple[int, int], tuple[str, ...]],
                                  dict[int, tuple[str, ...]]]:
    """The unknown figures per (sensor, profile), and per sensor the questions for its vendor.

    A question names the figure and the largest value of it that would still
    pass where the sensor passes on its published figures (``passed``, before
    the unknowns count), under the criterion: the allowable VRE of the spec
    bounds under ``bounds``; otherwise what is left of Δ* beside the worst
    case (|Δ_V| for ``worst``, in quadrature beside the RMS bound for
    ``rms``), over Σ⟨a_j²⟩ for the VRE or |C3i| for m3i (the other unknown
    figures taken as 0). ``budget``, ``rms``, ``total`` in deg/s.
    """
    unknown: dict[tuple[int, int], tuple[str, ...]] = {}
    questions: dict[int, tuple[str, ...]] = {}
    if spec is None or own is None:
        return unknown, questions
    figs = spec_bounds.unknown_figures(prepared, spec, method)
    s = units.scale(unit)
    # m31, m32 in the catalogue's rate unit, as coefficients are written in tables
    rate_unit = catalog_unit([e.unit for e in prepared.sensors]) or unit
    factors = bound_factors(rate_unit)
    for k, i in enumerate(spec.index.tolist()):
        limits: dict[str, tuple[float, int]] = {}
        for j in range(len(prepared.profiles)):
            names = figs.names(k, j)
            if not names:
                continue
            unknown[(i, j)] = names
            if not passed[i, j]:
                continue  # it fails there on its published figures alone
            left = _left(criterion, budget, float(rms[i, j]), float(total[i, j]))
            for name in names:
                if name == "vre":
                    value = left / float(figs.mean_square[j]) / s
                    if criterion in ("bounds", "both"):
                        value = min(value, float(own.vre_bound[k, j]) / s)
                else:
                    c = abs(float(getattr(figs, "c" + name[1:])[k, j]))
                    value = left / c * factors[name]
                if name not in limits or value < limits[name][0]:
                    limits[name] = (value, j)
        asks = _asks(limits, prepared, unit, rate_unit)
        if asks:
            questions[i] = asks
    return unknown, questions


def _left(criterion: str, budget: float, rms: float, total: float) -> float:
    """What is left of Δ* beside the worst case: |Δ_V| for ``worst`` (and ``bounds``),
    in quadrature beside the RMS bound for ``rms``; ``both``: the lesser."""
    left_worst = max(budget - total, 0.0)
    left_rms = float(np.sqrt(max(budget**2 - rms**2, 0.0)))
    return {"bounds": left_worst, "worst": left_worst, "rms": left_rms,
            "both": min(left_worst, left_rms)}[criterion]


def _asks(limits: dict[str, tuple[float, int]], prepared: Prepared, unit: str,
          rate_unit: str) -> tuple[str, ...]:
    """The questions for a vendor: per unknown figure, its largest value that passes."""
    asks = []
    for name in spec_bounds.UNKNOWN_FIGURES:
        if name not in limits:
            continue
        value, j = limits[name]
        profile = prepared.profiles[j].profile.id
        if name == "vre":
            asks.append(f"VRE (vibration rectification, {unit}/g²): at most {value:.4g} "
                        f"passes under {profile}")
        else:
            other = "m32" if name == "m31" else "m31"
            asks.append(f"{name} (multiplicative cross-axis coefficient, ({rate_unit})^-1): "
                        f"|{name}| at most {value:.4g} passes under {profile} "
                        f"(with {other} = 0)")
    return tuple(asks)


def _unknown_g2(prepared: Prepared, criterion: str, passed: NDArray[np.bool_], budget: float,
                rms: FloatArray, total: FloatArray, vre_bound: FloatArray, unit: str,
                unknown: dict[tuple[int, int], tuple[str, ...]],
                questions: dict[int, tuple[str, ...]]) -> None:
    """Add to ``unknown`` and ``questions`` the coefficient-form sensors without a g² figure.

    A coefficient-form sensor that gives neither ``g2_sensitivity`` nor ``vre``
    has no known g² sensitivity: under a profile with linear vibration
    (Σ⟨a_j²⟩ > 0) its g² term Δ0(6) = Σ G_jk⟨a_j a_k⟩ (docs/model.md section 8) is
    unknown, not zero, as a datasheet part's missing VRE is (``"vre"``). The
    question: the largest equal G11 = G22 = G33 that would still pass where it
    passes on its other figures: the ``vre`` bound under ``bounds``; what is
    left of Δ* beside |Δ_V| (``worst``) or in quadrature beside Δ_V(RMS)
    (``rms``; Δ0(6) is one term of eq. (16)), over Σ⟨a_j²⟩; ``both``: the lesser
    of the bound and the ``rms`` figure. ``budget``, ``rms``, ``total``,
    ``vre_bound`` in deg/s (per g²).
    """
    msq = [0.0 if v is None else float(mean_square(v.moments())) for v in prepared.linear] \
        if prepared.linear else [0.0] * len(prepared.profiles)
    s = units.scale(unit)
    for i, entry in enumerate(prepared.sensors):
        if not specs.g2_unknown(entry.sensor):
            continue
        best: tuple[float, int] | None = None
        for j, ms in enumerate(msq):
            if not ms > 0:
                continue
            unknown[(i, j)] = (*unknown.get((i, j), ()), "vre")
            if not passed[i, j]:
                continue  # it fails there on its other figures alone
            left_worst = max(budget - float(total[i, j]), 0.0) / ms
            left_rms = float(np.sqrt(max(budget**2 - float(rms[i, j]) ** 2, 0.0))) / ms
            bound = float(vre_bound[i, j])
            value = {"bounds": bound, "worst": left_worst, "rms": left_rms,
                     "both": min(bound, left_rms)}[criterion] / s
            if best is None or value < best[0]:
                best = (value, j)
        if best is not None:
            questions[i] = (*questions.get(i, ()),
                            f"g² sensitivity (G11 = G22 = G33, `vre`, {unit}/g²): at most "
                            f"{best[0]:.4g} passes under {prepared.profiles[best[1]].profile.id}")


def _effective_vre(prepared: Prepared) -> FloatArray:
    """|Δ0(6)|/Σ⟨a_j²⟩ of every sensor under every profile, deg/s per g² (docs/model.md section 8).

    0 where a profile has no linear vibration.
    """
    moments = np.array([np.zeros(6) if v is None else v.moments() for v in prepared.linear],
                       dtype=float).reshape(len(prepared.profiles), 6)
    return effective_vre(prepared.g2, moments)


def _worst_phase_totals(prepared: Prepared, group: Group, total: FloatArray) -> None:
    """|Δ_V| maximised over the phases of ``phase: worst`` orders (docs/model.md section 10).

    The synthesis multipliers take each moment at its largest magnitude, which
    fixes their signs; the direct test |Δ_V| ≤ Δ* needs, as ``analyze`` does,
    the maximum of |Δ_V| over the free phases per sensor (each form searches its
    own rows, :func:`~gyrovib.api.evaluation.evaluate.phase_worst`). Overwrites
    those profiles' columns of ``total`` (deg/s).
    """
    for j, idx, found in phase_worst(prepared, group):
        total[idx, j] = np.abs(found.error.total)
