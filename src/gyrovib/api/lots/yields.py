"""The yield of a production lot under ``select --yield`` (docs/model.md section 14).

A part drawn from a lot has c ~ N(μ, Σ) (:mod:`gyrovib.api.lots.uncertainty`: μ
the lot's mean, Σ from its sigma and correlations, the diagonal only for a lot
of n ≤ p units). Its yield under a profile is the probability that it passes
the criterion of ``select``:

* ``worst`` (the direct test |Δ_V| ≤ Δ*): exactly, Δ_V ~ N(m, s²) with
  m = Δ_V at the mean and s = u(Δ_V) (:func:`gyrovib.core.lot.direct_yield`);
* ``rms`` (Δ_V(RMS) ≤ Δ*, eq. 17), ``bounds`` (every |coefficient| within its
  bound, and the VRE check, which no coefficient of eq. 2 moves) and ``both``:
  by Monte Carlo (:func:`gyrovib.core.lot.monte_carlo_yield`), ``draws`` draws
  from a generator seeded by the seed and the lot's id (so a lot's yield does
  not change when other sensors are chosen), with the 95 % Wilson interval.

The parts of Δ_V and of the RMS terms that no uncertain coefficient moves (the
fixed coefficients, the g² term of docs/model.md section 8) enter as one more
coordinate of c fixed at 1 (its column is that part, its variance 0), so every
test is a function of the draws alone.

A lot passes a profile when its yield is at least the target Y (and it does not
saturate there, docs/model.md section 9).
"""

from __future__ import annotations

import zlib
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gyrovib.api.datasheet.spec_bounds import is_unverified
from gyrovib.api.evaluation.results import Limit, Result
from gyrovib.api.lots.uncertainty import (
    Distribution,
    at_k1,
    distributions,
    group_multipliers,
    has_worst_phases,
    lot_warnings,
    sensor_sensitivity,
)
from gyrovib.api.study.prepare import Prepared, profile_problem
from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import COEFFICIENTS, Multipliers
from gyrovib.core.lot import DEFAULT_DRAWS as DEFAULT_DRAWS
from gyrovib.core.lot import (
    bounds_test,
    direct_yield,
    monte_carlo_yield,
    rms_test,
    term_matrix,
)
from gyrovib.core.synthesis import BOUNDED
from gyrovib.errors import ModelError, Note, OptionError, literal
from gyrovib.reasons import Yield

#: Seed of the Monte-Carlo yields unless told otherwise.
DEFAULT_SEED = 0
#: Most draws per lot (memory and time: 10⁷ draws × profiles tests).
MAX_DRAWS = 10_000_000


@dataclass(frozen=True, eq=False, repr=False)
class LotYields(Result):
    """The yields of the lots among the chosen sensors, (sensors, profiles).

    ``value``: the yield (NaN on a sensor that is not a lot); ``low``/``high``:
    its 95 % Wilson interval (NaN for the exact yield and off lots);
    ``method``: ``"exact"`` (criterion ``worst``) or ``"monte-carlo"``;
    ``draws``: Monte-Carlo draws per lot (0 for exact); ``target``: Y;
    ``seed``; ``lots``: per sensor, whether it is a lot; ``unmeasured``: per
    sensor, why its yield is not a measurement (a lot without a measured spread,
    :func:`gyrovib.core.lot.spread_problem`), else None.
    """

    value: FloatArray
    low: FloatArray
    high: FloatArray
    method: str
    draws: int
    target: float
    seed: int
    lots: tuple[bool, ...]
    unmeasured: tuple[str | None, ...] = ()

    def _shape(self) -> tuple[int, ...]:
        return tuple(self.value.shape)

    def is_lot(self, i: int) -> bool:
        """Whether sensor ``i`` is a lot (judged by its yield)."""
        return self.lots[i]

    def at(self, i: int, j: int) -> Yield:
        """Sensor ``i``'s yield under profile ``j``, as :mod:`gyrovib.reasons` words it."""
        return Yield(float(self.value[i, j]), float(self.low[i, j]), float(self.high[i, j]),
                     self.method, self.draws)

    def shortfall(self, i: int, j: int) -> float:
        """(1 − yield)/(1 − Y): the fraction failing over the fraction allowed (> 1 fails)."""
        return float((1.0 - self.value[i, j]) / (1.0 - self.target))


def check_yield_options(target: float, draws: int, seed: int) -> None:
    """0 < Y < 1, 1 ≤ draws ≤ :data:`MAX_DRAWS`, seed ≥ 0."""
    if not (0.0 < target < 1.0):
        raise OptionError(argument="yield_target", value=f"{target:g}",
                          reason="give a probability between 0 and 1 (exclusive), e.g. 0.99 "
                                 "or 0.9973 for 3σ")
    if isinstance(draws, bool) or not (1 <= draws <= MAX_DRAWS):
        raise OptionError(argument="draws", value=str(draws), reason=f"give 1 to {MAX_DRAWS:,}")
    if seed < 0:
        raise OptionError(argument="seed", value=str(seed),
                          reason="the seed must be a non-negative integer")


def lot_generator(seed: int, sensor_id: str) -> np.random.Generator:
    """The random stream of one lot: a function of the seed and the lot's id only."""
    return np.random.default_rng([seed, zlib.crc32(sensor_id.encode("utf-8"))])


def _augmented(dist: Distribution) -> tuple[FloatArray, FloatArray]:
    """μ and Σ with one more coordinate fixed at 1 (variance 0): the fixed part."""
    p = len(dist.names)
    mean = np.append(dist.mean, 1.0)
    cov = np.zeros((p + 1, p + 1))
    cov[:p, :p] = dist.covariance
    return mean, cov


def _direct(multipliers: Multipliers, dist: Distribution,
            parts: Mapping[str, FloatArray], i: int) -> FloatArray:
    """(profiles, p + 1): g of Δ_V over the lot's coefficients and, last, the fixed part
    Δ_V(μ) − gᵀμ (deg/s); Δ_V(μ) is the view's own error of the lot's row ``i``
    (``parts``, :func:`gyrovib.api.evaluation.evaluate.errors`: the lot at its mean)."""
    g = sensor_sensitivity(multipliers, dist)
    total = parts["total"][i]
    out: FloatArray = np.concatenate([g, (total - g @ dist.mean)[..., None]], axis=-1)
    return out


def _terms(multipliers: Multipliers, dist: Distribution,
           parts: Mapping[str, FloatArray], i: int) -> FloatArray:
    """(profiles, terms, p + 1): the terms of eq. (16) as G·c over the lot's coefficients
    and, last, the fixed part (deg/s); the terms at the mean are the view's own
    (``parts`` of row ``i``, as :func:`_direct`)."""
    g = at_k1(term_matrix(multipliers, dist.names), dist)
    powers = np.stack([multipliers.omega ** q for q in (1, 2, 3)], axis=-1)
    terms = np.concatenate([parts["additive_terms"][i], parts["extra_terms"][i],
                            parts["multiplicative_coefficients"][i] * powers], axis=-1)
    fixed = terms - np.einsum("...tp,p->...t", g, dist.mean)
    out: FloatArray = np.concatenate([g, fixed[..., None]], axis=-1)
    return out


def _bounds(dist: Distribution, row: FloatArray, limits: FloatArray,
            vre_pass: NDArray[np.bool_], rtol: float
            ) -> tuple[FloatArray, NDArray[np.bool_]]:
    """The bound of each lot coefficient per profile (profiles, p + 1; +inf where none,
    and for the fixed coordinate), and per profile whether the fixed coefficients and
    the VRE pass their checks."""
    n_p = limits.shape[0]
    out = np.full((n_p, len(dist.names) + 1), np.inf)
    fixed_ok = np.asarray(vre_pass, dtype=bool).copy()
    for b, name in enumerate(BOUNDED):
        bound = limits[:, b] * (1.0 + rtol)
        if name in dist.names:
            out[:, dist.names.index(name)] = bound
        else:
            fixed_ok &= abs(float(row[COEFFICIENTS.index(name)])) <= bound
    return out, fixed_ok


def _and_fixed(test: Callable[[FloatArray], NDArray[np.bool_]], fixed_ok: NDArray[np.bool_]
               ) -> Callable[[FloatArray], NDArray[np.bool_]]:
    """``test`` and, per profile, the checks no drawn coefficient moves."""

    def both(c: FloatArray) -> NDArray[np.bool_]:
        out: NDArray[np.bool_] = test(c) & fixed_ok[None, :]
        return out

    return both


def _refuse_searched_phases(prepared: Prepared, lots: Sequence[bool]) -> None:
    """A profile with ``phase: worst`` orders has Δ_V maximised over phases per part (docs/model.md
    section 10): no linear form, no yield computed here. Refused, located at the profile."""
    searched = sorted({j for group in prepared.groups if any(lots[int(i)] for i in group.index)
                       for j in range(len(prepared.profiles)) if has_worst_phases(group, j)})
    if searched:
        raise ModelError([profile_problem(
            prepared.profiles[j],
            f"profile {literal(repr(prepared.profiles[j].profile.id))}: {{yield_target}} "
            "cannot judge a lot under 'phase: worst' orders (the error is maximised over "
            "the phases part by part, which no distribution of Δ_V gives here); write the "
            "phases, or choose other profiles with {profiles}", ("yield_target", "profiles"))
            for j in searched],
            reason="a yield with phase: worst")


def lot_yields(prepared: Prepared, parts: Mapping[str, FloatArray], method: str,
               criterion: str, budget: float,
               limits_deg: FloatArray, vre_pass: NDArray[np.bool_], target: float, *,
               seed: int = DEFAULT_SEED, draws: int = DEFAULT_DRAWS, rtol: float = 0.0,
               found: Sequence[Distribution | None] | None = None) -> LotYields | None:
    """The yield of every lot under every profile for ``criterion`` (module docstring);
    None when no chosen sensor is a lot.

    ``parts``: the view's error terms of every sensor in deg/s
    (:func:`gyrovib.api.evaluation.evaluate.errors` on ``prepared`` under ``method``; a lot's
    row is the lot at its mean). ``budget`` Δ* in deg/s; ``limits_deg`` (sensors,
    profiles, :data:`BOUNDED`) each sensor's coefficient bounds in deg/s powers;
    ``vre_pass`` (sensors, profiles) the VRE check; ``rtol`` the slack of every ≤
    (``select``'s).
    """
    check_yield_options(target, draws, seed)
    found = distributions(prepared) if found is None else found
    lots = tuple(d is not None and d.is_lot for d in found)
    if not any(lots):
        return None
    n_s, n_p = len(prepared.sensors), len(prepared.profiles)
    value = np.full((n_s, n_p), np.nan)
    low, high = value.copy(), value.copy()
    exact = criterion == "worst"
    limit = budget * (1.0 + rtol)
    _refuse_searched_phases(prepared, lots)
    for group in prepared.groups:
        multipliers = group_multipliers(prepared, group, method)
        for i in (int(k) for k in group.index if lots[int(k)]):
            dist = found[i]
            assert dist is not None
            row = prepared.coefficients[i]
            mean, cov = _augmented(dist)
            if exact:
                value[i] = direct_yield(_direct(multipliers, dist, parts, i), mean, cov, limit)
                continue
            tests: list[Callable[[FloatArray], NDArray[np.bool_]]] = []
            if criterion in ("bounds", "both"):
                bounds, fixed_ok = _bounds(dist, row, limits_deg[i], vre_pass[i], rtol)
                tests.append(_and_fixed(bounds_test(bounds), fixed_ok))
            if criterion in ("rms", "both"):
                tests.append(rms_test(_terms(multipliers, dist, parts, i), limit))

            def passes(c: FloatArray,
                       tests: list[Callable[[FloatArray], NDArray[np.bool_]]] = tests
                       ) -> NDArray[np.bool_]:
                out = tests[0](c)
                for more in tests[1:]:
                    out = out & more(c)
                return out

            estimate = monte_carlo_yield(passes, mean, cov,
                                         lot_generator(seed, prepared.sensors[i].sensor.id),
                                         draws=draws)
            value[i], low[i], high[i] = estimate.value, estimate.low, estimate.high
    return LotYields(value=value, low=low, high=high,
                     method="exact" if exact else "monte-carlo",
                     draws=0 if exact else draws, target=target, seed=seed, lots=lots,
                     unmeasured=_unmeasured(found))


def _unmeasured(found: Sequence[Distribution | None]) -> tuple[str | None, ...]:
    """Per sensor, why its lot's yield is not a measurement (None: measured, or no lot)."""
    return tuple(d.unmeasured if d is not None and d.is_lot else None for d in found)


def judge(yields: LotYields, passed: NDArray[np.bool_],
          saturated: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """``passed`` with each lot's cells replaced by yield ≥ Y (and not saturated)."""
    out = passed.copy()
    rows = np.array(yields.lots, dtype=bool)
    out[rows] = (yields.value[rows] >= yields.target) & ~saturated[rows]
    return out


def open_lots(yields: LotYields, passed: NDArray[np.bool_], unverified: NDArray[np.bool_],
              unknown: dict[tuple[int, int], tuple[str, ...]],
              questions: dict[int, tuple[str, ...]], assume_unknown: str) -> None:
    """In place, after :func:`judge`: a lot whose spread is not measured (``unmeasured``)
    has the unknown ``"spread"`` under every profile, and where its yield passes it is
    ``unverified``, not passing (:func:`gyrovib.api.datasheet.spec_bounds.is_unverified`, the one
    rule of unknowns), with what would settle it among ``questions``;
    ``assume_unknown="zero"`` takes the lot as given (no unknown). A cell an unknown
    figure already left open stays open, whatever the yield."""
    passed &= ~unverified
    if assume_unknown == "zero":
        return
    for i, why in enumerate(yields.unmeasured):
        if why is None:
            continue
        for j in range(passed.shape[1]):
            unknown[(i, j)] = (*unknown.get((i, j), ()), "spread")
            if is_unverified(bool(passed[i, j]), unknown[(i, j)], assume_unknown):
                unverified[i, j] = True
                passed[i, j] = False
        questions[i] = (*questions.get(i, ()), "the lot's spread, not measured (too few "
                        "units, or units without spread): measure more units")


def yield_limits(yields: LotYields, limits: Mapping[int, Limit],
                 sensor_pass: NDArray[np.bool_], saturated: NDArray[np.bool_]
                 ) -> dict[int, Limit]:
    """``limits`` with each failing lot (not saturating) limited by its lowest yield:
    ``Limit("yield", profile, (1 − yield)/(1 − Y))``."""
    out = dict(limits)
    for i, lot in enumerate(yields.lots):
        if not lot or sensor_pass[i] or saturated[i].any():
            continue
        j = int(np.nanargmin(yields.value[i]))
        out[i] = Limit("yield", j, yields.shortfall(i, j))
    return out


#: The note of a yield target without a lot among the chosen sensors.
NO_LOTS = Note("{yield_target}: no production lot ('lot:') among the chosen sensors; every "
               "sensor is judged as without it", ("yield_target", None))


def notes(prepared: Prepared, target: float | None = None,
          yields: LotYields | None = None) -> tuple[str, ...]:
    """The warnings of lots too small for their correlations; and, when a yield
    ``target`` was given but no sensor is a lot, that it changed nothing."""
    out = lot_warnings(distributions(prepared))
    return out + ((NO_LOTS,) if target is not None and yields is None else ())
