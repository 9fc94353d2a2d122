"""``phase: worst``: the worst case over the unknown phases of locked harmonics (docs/model.md 10).

An order whose phase is unknown gets a common offset ψ_n on every axis
(its per-axis phases keep their differences). The overall time origin is
free — shifting t by τ advances order n by n·2πf0τ — so in a group with no
order of known phase the first unknown order keeps ψ = 0. The remaining
offsets (D of them, over all groups of a profile) are searched on a coarse
uniform grid of the D-torus, and the best node of each objective is refined
by a compass (pattern) search whose step halves down to 1e-6 rad (|Δ_V| is
flat to second order at a maximum, so that is ~1e-12 relative).

* analysis (:func:`worst_phase_error`): maximise |Δ_V| per sensor;
* synthesis (:func:`worst_phase_multipliers`): per term, the largest |moment|
  over the phases — g_A = ½E(Ω), M4, |M3|, |M5| each on its own (M2 and C3i
  do not depend on the relative phases).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from gyrovib.core.analysis import (
    Multipliers,
    VibrationError,
    profile_multipliers,
    stack_multipliers,
    vibration_error,
)
from gyrovib.core.harmonics import LockedGroup
from gyrovib.core.statistics import Vibration
from gyrovib.core.transmissibility import FloatArray
from gyrovib.frozen import Frozen

#: Most nodes of the coarse grid over the free offsets.
COARSE_NODES = 256
#: Fewest nodes per free offset on the coarse grid (when the grid allows).
MIN_PER_AXIS = 4
#: Step at which the compass search stops (rad).
FINE_STEP = 1e-6


def free_offsets(groups: Sequence[LockedGroup]) -> list[tuple[int, int]]:
    """(group, order index) of each offset searched, after fixing the time origin."""
    free: list[tuple[int, int]] = []
    for g_index, g in enumerate(groups):
        worst = np.flatnonzero(g.worst)
        if worst.size and not np.any(~g.worst):
            worst = worst[1:]  # no order of known phase: the time origin fixes one
        free.extend((g_index, int(i)) for i in worst)
    return free


def apply_offsets(groups: Sequence[LockedGroup], free: Sequence[tuple[int, int]],
                  psi: ArrayLike) -> list[LockedGroup]:
    """The groups with offsets ``psi`` (D,) rad added to the orders in ``free``."""
    values = np.asarray(psi, dtype=float).reshape(-1)
    out = []
    for g_index, g in enumerate(groups):
        offsets = np.zeros(g.orders.size)
        for (gi, oi), v in zip(free, values, strict=True):
            if gi == g_index:
                offsets[oi] = v
        out.append(g.shifted(offsets))
    return out


def _coarse(dims: int) -> FloatArray:
    per = max(MIN_PER_AXIS, math.floor(COARSE_NODES ** (1.0 / dims) + 1e-9))
    while per**dims > COARSE_NODES and per > MIN_PER_AXIS:
        per -= 1
    axis = 2.0 * math.pi * np.arange(per) / per
    mesh = np.meshgrid(*([axis] * dims), indexing="ij")
    out: FloatArray = np.stack([m.ravel() for m in mesh], axis=1)
    return out


def maximise_on_torus(objective: Callable[[FloatArray], FloatArray], dims: int
                      ) -> tuple[FloatArray, FloatArray]:
    """Maximise K objectives over ψ ∈ [0, 2π)^dims, each on its own.

    ``objective``: (C, dims) offsets → (C, K) values. Returns the best
    offsets (K, dims) and values (K,).
    """
    if dims == 0:
        values = objective(np.zeros((1, 0)))[0]
        return np.zeros((values.size, 0)), values
    nodes = _coarse(dims)
    values = objective(nodes)
    best_index = np.argmax(values, axis=0)
    best = nodes[best_index].copy()
    best_value = values[best_index, np.arange(values.shape[1])].copy()
    start = 2.0 * math.pi / round(nodes.shape[0] ** (1.0 / dims))
    moves = np.concatenate([np.eye(dims), -np.eye(dims)])
    for k in range(best.shape[0]):
        step = start
        while step > FINE_STEP:
            trial = np.mod(best[k][None, :] + step * moves, 2.0 * math.pi)
            got = objective(trial)[:, k]
            i = int(np.argmax(got))
            if got[i] > best_value[k]:
                best[k], best_value[k] = trial[i], got[i]
            else:
                step *= 0.5
    return best, best_value


@dataclass(frozen=True, eq=False, repr=False)
class WorstPhases(Frozen):
    """The worst case of a profile over its unknown phases, per sensor.

    ``offsets``: (sensors, D) ψ found (rad), for the orders ``free``
    ((group, order index) pairs); ``error``: the :class:`VibrationError` at
    those phases, shape (sensors,); ``multipliers``: per sensor, stacked
    along a leading (sensors,) axis.
    """

    offsets: FloatArray
    free: tuple[tuple[int, int], ...]
    error: VibrationError
    multipliers: Multipliers


def worst_phase_error(
    coefficients: ArrayLike,
    vibration: Vibration,
    groups: Sequence[LockedGroup],
    omega: float,
    *,
    acceleration: ArrayLike | None = None,
    g2_sensitivity: ArrayLike | None = None,
) -> WorstPhases:
    """Maximise |Δ_V(Ω)| over the unknown phases, per sensor (exact method).

    ``coefficients``: (sensors, 11); ``omega``: Ω_K3 (rate); the rest as in
    :func:`gyrovib.core.analysis.profile_multipliers` and
    :func:`~gyrovib.core.analysis.vibration_error`.
    """
    c = np.asarray(coefficients, dtype=float)
    free = free_offsets(groups)
    g2 = None if g2_sensitivity is None else np.asarray(g2_sensitivity, dtype=float)

    def multipliers_at(psi: FloatArray) -> Multipliers:
        return stack_multipliers([
            profile_multipliers(vibration, np.asarray(float(omega)), "exact",
                                locked=apply_offsets(groups, free, row),
                                acceleration=acceleration)
            for row in psi])

    def objective(psi: FloatArray) -> FloatArray:
        err = vibration_error(c, multipliers_at(psi), g2)
        out: FloatArray = np.abs(err.total).T  # (C, sensors)
        return out

    best, _ = maximise_on_torus(objective, len(free))
    per_sensor = [multipliers_at(best[k : k + 1]) for k in range(c.shape[0])]
    errors = [vibration_error(c[k : k + 1], mu,
                              None if g2 is None else g2[k : k + 1])
              for k, mu in enumerate(per_sensor)]
    error = VibrationError(**{
        name: np.concatenate([getattr(e, name)[:, 0] for e in errors])
        for name in VibrationError.__dataclass_fields__})
    rows: list[Multipliers] = []
    for m in per_sensor:
        row: dict[str, Any] = {f: None if getattr(m, f) is None else getattr(m, f)[0]
                               for f in Multipliers.__dataclass_fields__}
        rows.append(Multipliers(**row))
    stacked = stack_multipliers(rows)
    return WorstPhases(offsets=best, free=tuple(free), error=error, multipliers=stacked)


def worst_phase_multipliers(
    vibration: Vibration,
    groups: Sequence[LockedGroup],
    omega: ArrayLike,
    *,
    acceleration: ArrayLike | None = None,
) -> Multipliers:
    """Per term, the largest |multiplier| over the unknown phases (synthesis, exact).

    g_A = ½E(Ω), M4, |M3| and |M5| are each maximised on their own at every
    rate in ``omega`` (any shape); M2, C31, C32 and the acceleration moments
    do not depend on the phases. The result bounds every phase's share.
    """
    w = np.asarray(omega, dtype=float)
    free = free_offsets(groups)
    flat = w.ravel()
    fields: dict[str, list[float]] = {"asymmetry": [], "m3": [], "m4": [], "m5": []}
    base = profile_multipliers(vibration, w, "exact", locked=list(groups),
                               acceleration=acceleration)
    for rate in flat:
        def objective(psi: FloatArray, rate: float = float(rate)) -> FloatArray:
            mu = stack_multipliers([
                profile_multipliers(vibration, np.asarray(rate), "exact",
                                    locked=apply_offsets(groups, free, row))
                for row in psi])
            assert mu.m3 is not None and mu.m5 is not None
            out: FloatArray = np.stack([np.abs(mu.asymmetry), np.abs(mu.m3), mu.m4,
                                        np.abs(mu.m5)], axis=1)
            return out

        _, values = maximise_on_torus(objective, len(free))
        for name, v in zip(("asymmetry", "m3", "m4", "m5"), values, strict=True):
            fields[name].append(float(v))
    shaped = {k: np.asarray(v).reshape(w.shape) for k, v in fields.items()}
    return Multipliers(
        asymmetry=shaped["asymmetry"], m2=base.m2, m4=shaped["m4"], c31=base.c31,
        c32=base.c32, omega=w.copy(), m3=shaped["m3"], m5=shaped["m5"],
        acceleration=base.acceleration,
    )
