"""``phase: worst``: the worst case over the unknown phases of locked harmonics (docs/model.md 10).

An order whose phase is unknown gets a common offset ψ_n on every axis
(its per-axis phases keep their differences). The overall time origin is
free — shifting t by τ advances order n by n·2πf0τ — so in a group with no
order of known phase the first unknown order keeps ψ = 0. The remaining
offsets (D of them, over all groups of a profile) are searched on a coarse
uniform grid of the D-torus (a Kronecker lattice of as many nodes past 4
offsets), and the best node of each objective is refined by a compass
(pattern) search down to a step of 0.3 rad, then by Newton's method with
central differences until its step is below 1e-6 rad (|Δ_V| is flat to
second order at a maximum, so that is ~1e-12 relative); where Newton's
method does not apply (an indefinite Hessian), the compass search goes on to
1e-6 rad. Four orders of unknown phase took 6,000 evaluations of the
objective with the compass search alone, 700 so.

* analysis (:func:`worst_phase_errors`): maximise |Δ_V| per sensor;
* synthesis (:func:`worst_phase_multipliers`): per term, the largest |moment|
  over the phases — g_A = ½E(Ω), M4, |M3|, |M5| each on its own (M2 and C3i
  do not depend on the relative phases).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Generator, Sequence
from dataclasses import dataclass
from functools import partial, wraps
from typing import Any, ParamSpec, TypeVar, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import (
    Multipliers,
    VibrationError,
    profile_multipliers,
    stack_multipliers,
    vibration_error,
)
from gyrovib.core.harmonics import LockedGroup
from gyrovib.core.phase_batch import batched
from gyrovib.core.statistics import Vibration
from gyrovib.frozen import Frozen
from gyrovib.progress import advance

#: Most nodes of the coarse grid over the free offsets.
COARSE_NODES = 256
#: Fewest nodes per free offset on the coarse grid (when the grid allows).
MIN_PER_AXIS = 4
#: Step at which the compass search stops (rad).
FINE_STEP = 1e-6
#: Compass step below which Newton's method takes over (rad), and its difference step.
NEWTON_FROM = 0.3
NEWTON_H = 1e-4
#: Step (rad) along a direction of positive curvature off a saddle.
SADDLE_STEP = 0.25
#: Hessian eigenvalues within this fraction of the largest are a flat direction.
FLAT = 1e-6


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


#: Most distinct values the snapped offsets of :func:`_coarse` take together.
SNAPPED_VALUES = 16


def _coarse(dims: int, snap: Sequence[int] = ()) -> FloatArray:
    """The coarse nodes: a uniform grid of at most :data:`COARSE_NODES` with at least
    :data:`MIN_PER_AXIS` per offset; past that (5 or more offsets), the first
    COARSE_NODES points of the R_d Kronecker sequence (fractional parts of i·α_j,
    α_j = φ_d^−(j+1), φ_d the root of x^(d+1) = x + 1), which fill the torus evenly
    in any dimension (a full grid of 4 per axis would have 4^d nodes).

    ``snap``: offsets whose every distinct value costs a table (the folded groups' of
    :mod:`gyrovib.core.phase_batch`): on the Kronecker nodes they are rounded to a
    uniform grid, so that together they take at most :data:`SNAPPED_VALUES` values."""
    if MIN_PER_AXIS**dims > COARSE_NODES:
        phi = 2.0
        for _ in range(60):
            phi = (1.0 + phi) ** (1.0 / (dims + 1))
        alpha = phi ** -np.arange(1.0, dims + 1.0)
        i = np.arange(1, COARSE_NODES + 1)[:, None]
        lattice: FloatArray = 2.0 * math.pi * np.mod(0.5 + i * alpha[None, :], 1.0)
        if snap:
            q = max(2, math.floor(SNAPPED_VALUES ** (1.0 / len(snap)) + 1e-9))
            cols = list(snap)
            unit = 2.0 * math.pi / q
            lattice[:, cols] = np.mod(np.round(lattice[:, cols] / unit), q) * unit
        return lattice
    per = max(MIN_PER_AXIS, math.floor(COARSE_NODES ** (1.0 / dims) + 1e-9))
    while per**dims > COARSE_NODES and per > MIN_PER_AXIS:
        per -= 1
    axis = 2.0 * math.pi * np.arange(per) / per
    mesh = np.meshgrid(*([axis] * dims), indexing="ij")
    out: FloatArray = np.stack([m.ravel() for m in mesh], axis=1)
    return out


#: A request of a refinement: trial offsets (T, D); it is sent back their values (T,).
Refinement = Generator[FloatArray, FloatArray, tuple[FloatArray, float]]


def _compass(best: FloatArray, value: float, step: float, stop: float
             ) -> Generator[FloatArray, FloatArray, tuple[FloatArray, float]]:
    """Compass search on one objective from ``best`` until the step is below ``stop``
    (a coroutine: it yields its trial points and is sent their values)."""
    dims = best.size
    moves = np.concatenate([np.eye(dims), -np.eye(dims)])
    while step > stop:
        trial = np.mod(best[None, :] + step * moves, 2.0 * math.pi)
        got = yield trial
        i = int(np.argmax(got))
        # (an improvement within rounding is none: on a flat ridge it would walk
        # the search at a fixed step for hundreds of evaluations)
        if got[i] > value + 1e-14 * abs(value):
            best, value = trial[i], float(got[i])
        else:
            step *= 0.5
    return best, value


def _stencil(dims: int) -> FloatArray:
    """Offsets (in units of h) of the central-difference gradient and Hessian."""
    eye = np.eye(dims)
    rows = [np.zeros(dims)]
    rows += [eye[i] for i in range(dims)] + [-eye[i] for i in range(dims)]
    for i in range(dims):
        for j in range(i + 1, dims):
            rows += [eye[i] + eye[j], eye[i] - eye[j], -eye[i] + eye[j], -eye[i] - eye[j]]
    return np.asarray(rows)


def _hessian(f: FloatArray, dims: int, h: float) -> tuple[FloatArray, FloatArray]:
    """Gradient and Hessian from the values ``f`` on :func:`_stencil` (step ``h``)."""
    f0 = f[0]
    grad = (f[1:1 + dims] - f[1 + dims:1 + 2 * dims]) / (2.0 * h)
    hess = np.diag((f[1:1 + dims] + f[1 + dims:1 + 2 * dims] - 2.0 * f0) / (h * h))
    at = 1 + 2 * dims
    for i in range(dims):
        for j in range(i + 1, dims):
            pp, pm, mp, mm = f[at:at + 4]
            hess[i, j] = hess[j, i] = (pp - pm - mp + mm) / (4.0 * h * h)
            at += 4
    return grad, hess


def _newton(best: FloatArray, value: float
            ) -> Generator[FloatArray, FloatArray, tuple[FloatArray, float, bool]]:
    """Newton's method on one objective with central differences (step :data:`NEWTON_H`).

    Near a smooth maximum it converges quadratically (a handful of steps of
    1 + 2D² evaluations where the compass search took hundreds of steps of 2D).
    Each step is tried whole first; only when that does not improve are its halves
    (down to 1/128) tried, and the best taken. Returns the point, its value and
    whether it converged (False: a step did not improve). A direction of no curvature
    (:data:`FLAT`) is one the objective does not depend on: the step leaves it alone.
    At a saddle (an eigenvalue of the Hessian > 0) it steps along the eigenvectors of
    positive curvature instead, and goes on from the best of them if one improves. A coroutine, as
    :func:`_compass`.
    """
    dims = best.size
    stencil = _stencil(dims)
    h = NEWTON_H
    for _ in range(12):
        f = yield np.mod(best[None, :] + h * stencil, 2.0 * math.pi)
        grad, hess = _hessian(f, dims, h)
        if not np.all(np.isfinite(hess)):
            return best, value, False
        lam, vec = np.linalg.eigh(hess)
        # a curvature within FLAT of the largest is none: a direction the objective does
        # not depend on (a moment of one group along another group's offset); the step
        # leaves it alone
        flat = np.abs(lam) <= FLAT * float(np.max(np.abs(lam)))
        if np.any(lam[~flat] > 0):
            # a saddle: f rises both ways along an eigenvector of curvature > 0, whatever
            # the gradient there; try steps of SADDLE_STEP along each, both signs
            up = vec[:, (lam > 0) & ~flat].T
            trials = np.mod(best[None, :] + SADDLE_STEP * np.concatenate([up, -up]),
                            2.0 * math.pi)
            got = yield trials
            i = int(np.argmax(got))
            if not got[i] > value + 1e-14 * abs(value):
                return best, value, False
            best, value = trials[i], float(got[i])
            continue
        bent = vec[:, ~flat]
        move = -bent @ ((bent.T @ grad) / lam[~flat])
        size = float(np.max(np.abs(move)))
        if size > 1.0:
            move *= 1.0 / size
        if size < FINE_STEP:
            return best, max(value, float(f[0])), True
        trials = np.mod(best[None, :] + np.exp2(-np.arange(8.0))[:, None] * move[None, :],
                        2.0 * math.pi)
        whole = yield trials[:1]
        if whole[0] >= value:
            best, value = trials[0], float(whole[0])
            continue
        got = yield trials[1:]
        i = int(np.argmax(got))
        if not got[i] >= value:
            return best, value, False
        best, value = trials[1 + i], float(got[i])
    return best, value, False


#: Newton's method tried this many times, with compass moves between (off a saddle).
NEWTON_TRIES = 3


def _refine(best: FloatArray, value: float, start: float) -> Refinement:
    """One objective from its best coarse node: the compass search down to
    :data:`NEWTON_FROM`, then Newton's method. Where Newton's method fails (a saddle
    or a ridge: the Hessian is not negative definite), compass moves of 2·NEWTON_FROM
    down to NEWTON_FROM/4 leave it and Newton's method is tried again (at most
    :data:`NEWTON_TRIES` times); past that, the compass search goes on down to
    :data:`FINE_STEP`."""
    point, value = yield from _compass(best, value, start, NEWTON_FROM)
    for attempt in range(NEWTON_TRIES):
        point, value, done = yield from _newton(point, value)
        if done:
            return point, value
        if attempt + 1 < NEWTON_TRIES:
            point, value = yield from _compass(point, value, 2.0 * NEWTON_FROM,
                                               0.25 * NEWTON_FROM)
    point, value = yield from _compass(point, value, NEWTON_FROM, FINE_STEP)
    return point, value


#: Rows' values of their own objective: (offsets (T, D), objective of each row (T,)) → (T,).
RowObjective = Callable[[FloatArray, NDArray[np.intp]], FloatArray]


def _lockstep(rows_objective: RowObjective, starts: FloatArray, values: FloatArray,
              step: float) -> tuple[FloatArray, FloatArray]:
    """Every objective's refinement (:func:`_refine`) in step: at each round the trial
    points all objectives ask for are evaluated in one call. Each objective takes the
    same path as it would alone."""
    best, best_value = starts.copy(), values.copy()
    running: dict[int, Refinement] = {}
    asks: dict[int, FloatArray] = {}
    for k in range(starts.shape[0]):
        gen = _refine(starts[k].copy(), float(values[k]), step)
        running[k] = gen
        try:
            asks[k] = next(gen)
        except StopIteration as stop:
            best[k], best_value[k] = stop.value
            del running[k]
    total = starts.shape[0]
    while running:
        advance("phase: worst search", total - len(running), total)
        ks = list(running)
        psi = np.concatenate([asks[k] for k in ks])
        which = np.concatenate([np.full(asks[k].shape[0], k, dtype=np.intp) for k in ks])
        got = rows_objective(psi, which)
        at = 0
        for k in ks:
            n = asks[k].shape[0]
            part, at = got[at:at + n], at + n
            try:
                asks[k] = running[k].send(part)
            except StopIteration as stop:
                best[k], best_value[k] = stop.value
                del running[k], asks[k]
    advance("phase: worst search", total, total)
    return best, best_value


def _searched(coarse: FloatArray, values: FloatArray, rows_objective: RowObjective
              ) -> tuple[FloatArray, FloatArray]:
    """Each objective's best coarse node (``values``: (nodes, K)), refined in step."""
    dims = coarse.shape[1]
    best_index = np.argmax(values, axis=0)
    best = coarse[best_index].copy()
    best_value = values[best_index, np.arange(values.shape[1])].copy()
    per_axis = max(2, round(coarse.shape[0] ** (1.0 / dims)))
    return _lockstep(rows_objective, best, best_value, 2.0 * math.pi / per_axis)


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


def _search_key(*parts: object) -> bytes:
    """Bytes that identify a search's inputs (arrays by shape, dtype and content)."""
    out = []
    for part in parts:
        if part is None:
            out.append(b"-")
        elif isinstance(part, LockedGroup):
            out.append(_search_key(part.orders, part.phasors, part.worst))
        elif isinstance(part, Vibration):
            out.append(_search_key(part.phasors, part.sigma, part.coherence,
                                   np.asarray(part.has_random)))
        elif isinstance(part, (list, tuple)):
            out.append(_search_key(*part))
        else:
            a = np.ascontiguousarray(part)
            out.append(f"{a.dtype.str}{a.shape}".encode() + a.tobytes())
    return b"|".join(out)


#: The last searches made, by their inputs: a report asks ``analyze`` and ``select`` the
#: same profile's worst phases, and ``bounds`` and ``sweep`` its worst multipliers.
_SEARCHES: dict[bytes, Any] = {}
_KEPT_SEARCHES = 32
_P = ParamSpec("_P")
_R = TypeVar("_R")


def _remembered(kind: str) -> Callable[[Callable[_P, _R]], Callable[_P, _R]]:
    """A search not made again for the same inputs as one of the last few: a copy of
    what it gave then, so that a caller's changes never reach the next one."""

    def wrap(compute: Callable[_P, _R]) -> Callable[_P, _R]:
        @wraps(compute)
        def search(*args: _P.args, **kwargs: _P.kwargs) -> _R:
            key = _search_key(kind, *args, *sorted(kwargs.items()))
            if key not in _SEARCHES:
                if len(_SEARCHES) >= _KEPT_SEARCHES:
                    _SEARCHES.pop(next(iter(_SEARCHES)))
                _SEARCHES[key] = compute(*args, **kwargs)
            return cast(_R, copy.deepcopy(_SEARCHES[key]))

        return search

    return wrap


@_remembered("errors")
def worst_phase_errors(
    coefficients: ArrayLike,
    vibration: Vibration,
    groups: Sequence[LockedGroup],
    omegas: ArrayLike,
    *,
    acceleration: ArrayLike | None = None,
    g2_sensitivity: ArrayLike | None = None,
) -> list[WorstPhases]:
    """Maximise |Δ_V(Ω)| over the unknown phases, per sensor (exact method), at each rate
    of ``omegas`` (Ω_K3, R,), one search for all. ``coefficients``: (sensors, 11); the rest
    as in :func:`gyrovib.core.analysis.profile_multipliers` and
    :func:`~gyrovib.core.analysis.vibration_error`.

    The objectives are |Δ_V| of every (rate, sensor): the coarse nodes are
    evaluated once for all of them and their refinements run in step
    (:func:`_lockstep`), each trial point on the batched form of the profile
    (:mod:`gyrovib.core.phase_batch`) where it has one. The error reported is
    recomputed at the phases found by
    :func:`~gyrovib.core.analysis.profile_multipliers`, the one-point path. A search
    with the same inputs as one of the last few is not made again.
    """
    c = np.asarray(coefficients, dtype=float)
    rates = np.asarray(omegas, dtype=float).reshape(-1)
    free = free_offsets(groups)
    g2 = None if g2_sensitivity is None else np.asarray(g2_sensitivity, dtype=float)
    sensors = c.shape[0]
    fast = batched(vibration, groups, free, acceleration)

    def one_point(row: FloatArray, omega: float) -> Multipliers:
        return profile_multipliers(vibration, np.asarray(float(omega)), "exact",
                                   locked=apply_offsets(groups, free, row),
                                   acceleration=acceleration)

    def errors_at(psi: FloatArray, omega: FloatArray) -> FloatArray:
        if fast is not None:
            mu = fast.multipliers(psi, omega)
        else:
            mu = stack_multipliers([one_point(row, float(w))
                                    for row, w in zip(psi, omega, strict=True)])
        out: FloatArray = np.abs(vibration_error(c, mu, g2).total).T  # (C, sensors)
        return out

    def rows_objective(psi: FloatArray, which: NDArray[np.intp]) -> FloatArray:
        got = errors_at(psi, rates[which // sensors])
        out: FloatArray = got[np.arange(psi.shape[0]), which % sensors]
        return out

    dims = len(free)
    if dims == 0:
        best = np.zeros((rates.size * sensors, 0))
    else:
        nodes = _coarse(dims, () if fast is None else fast.folded_offsets())
        n = nodes.shape[0]
        values = errors_at(np.tile(nodes, (rates.size, 1)), np.repeat(rates, n))
        values = values.reshape(rates.size, n, sensors).transpose(1, 0, 2).reshape(n, -1)
        best, _ = _searched(nodes, values, rows_objective)
    return [_found(c, g2, free, best[r * sensors:(r + 1) * sensors],
                   partial(one_point, omega=w))
            for r, w in enumerate(rates.tolist())]


def _found(c: FloatArray, g2: FloatArray | None, free: Sequence[tuple[int, int]],
           best: FloatArray, one_point: Callable[[FloatArray], Multipliers]) -> WorstPhases:
    """The error of each sensor at its phases ``best`` (sensors, D), on the one-point path."""
    per_sensor = [one_point(best[k]) for k in range(c.shape[0])]
    errors = [vibration_error(c[k : k + 1], stack_multipliers([mu]),
                              None if g2 is None else g2[k : k + 1])
              for k, mu in enumerate(per_sensor)]
    error = VibrationError(**{
        name: np.concatenate([getattr(e, name)[:, 0] for e in errors])
        for name in VibrationError.__dataclass_fields__})
    stacked = stack_multipliers(per_sensor)
    return WorstPhases(offsets=best, free=tuple(free), error=error, multipliers=stacked)


@_remembered("multipliers")
def worst_phase_multipliers(vibration: Vibration, groups: Sequence[LockedGroup],
                            omega: ArrayLike, *, acceleration: ArrayLike | None = None
                            ) -> Multipliers:
    """Per term, the largest |multiplier| over the unknown phases (synthesis, exact).

    g_A = ½E(Ω), M4, |M3| and |M5| are each maximised on their own: M3, M4 and
    M5 once (they do not depend on the rate), g_A at every rate in ``omega``
    (any shape), all in one search (:func:`_lockstep`; the trial points on the
    batched form of the profile, :mod:`gyrovib.core.phase_batch`, where it has
    one); M2, C31, C32 and the acceleration moments do not depend on the phases.
    The result bounds every phase's share. A search with the same inputs as one of the
    last few is not made again.
    """
    w = np.asarray(omega, dtype=float)
    free = free_offsets(groups)
    flat = w.ravel()
    base = profile_multipliers(vibration, w, "exact", locked=list(groups),
                               acceleration=acceleration)
    fast = batched(vibration, groups, free, None)

    def values(psi: FloatArray, rates: FloatArray) -> FloatArray:
        """(C, 4): |g_A| at each row's rate, |M3|, M4, |M5|."""
        if fast is not None:
            mu = fast.multipliers(psi, rates)
        else:
            mu = stack_multipliers([
                profile_multipliers(vibration, np.asarray(float(rate)), "exact",
                                    locked=apply_offsets(groups, free, row))
                for row, rate in zip(psi, rates, strict=True)])
        assert mu.m3 is not None and mu.m5 is not None
        out: FloatArray = np.stack([np.abs(mu.asymmetry), np.abs(mu.m3), mu.m4,
                                    np.abs(mu.m5)], axis=1)
        return out

    dims = len(free)
    if dims == 0:
        got = values(np.zeros((flat.size, 0)), flat)
        best = np.concatenate([got[0, 1:], got[:, 0]])
    else:
        nodes = _coarse(dims, () if fast is None else fast.folded_offsets())
        n = nodes.shape[0]
        v = values(np.tile(nodes, (flat.size, 1)), np.repeat(flat, n))
        v = v.reshape(flat.size, n, 4)
        # objectives: |M3|, M4, |M5| (any rate), then g_A at each rate
        table = np.concatenate([v[0, :, 1:], v[:, :, 0].T], axis=1)

        def rows_objective(psi: FloatArray, which: NDArray[np.intp]) -> FloatArray:
            moment = which < 3
            got = values(psi, flat[np.where(moment, 0, which - 3)])
            out: FloatArray = got[np.arange(psi.shape[0]), np.where(moment, which + 1, 0)]
            return out

        _, best = _searched(nodes, table, rows_objective)
    m3, m4, m5 = (np.full(w.shape, float(best[i])) for i in range(3))
    return Multipliers(
        asymmetry=best[3:].reshape(w.shape), m2=base.m2, m4=m4, c31=base.c31,
        c32=base.c32, omega=w.copy(), m3=m3, m5=m5, acceleration=base.acceleration,
    )


#: Most objective-evaluation units one ``phase: worst`` search may cost
#: (:func:`search_cost`): 3-4 s on a quiet 2-core machine, under 10 s on a shared one.
MAX_SEARCH_COST = 3000.0


def search_cost(dims: int, objectives: int, n_max: int) -> float:
    """Estimated cost of :func:`_searched` over ``dims`` offsets, in
    evaluations of a profile's multipliers at one rate with small orders (~1.3 ms).

    The coarse nodes, then per objective a few compass rounds of 2D moves and
    about five Newton steps of 1 + 2D² differences (measured: four orders,
    four objectives 722 evaluations; eight orders 2,916); an evaluation of
    orders up to n_max solves an eigenvalue problem of degree 2·n_max, which
    costs like (n_max/16)³ more.
    """
    if dims == 0:
        return 0.0
    per_objective = 8 * dims + 5 * (1 + 2 * dims * dims) + 40
    evaluations = COARSE_NODES + objectives * per_objective
    return float(evaluations) * (1.0 + (max(n_max, 1) / 16.0) ** 3)
