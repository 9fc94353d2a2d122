"""Spec-form (datasheet) sensors: their worst case over the envelope (docs/model.md section 11).

A sensor written with ``specs:`` (range, nonlinearity, optional asymmetry and
VRE) has no single conversion function. The commands route it here: its
datasheet figures are converted to deg/s (the nonlinearity limit b from %FS
of the range or span, or from an absolute rate in any rate unit; the
asymmetry from ppm or %, A1 = 1e-6 per ppm; the VRE from rate per the file's
acceleration unit² to deg/s per g²), and the profile multipliers of each
sensor group feed :func:`gyrovib.core.envelope.worst_case`.

What a spec-form sensor reports (JSON ``"source": "specs"``, docs/output.md): ``total``
the worst |Δ_V(Ω_K3)| over the polynomials the datasheet permits (the worst one's cᵀx plus
|v|·Σ⟨a_j²⟩ under linear vibration), ``rms`` the bound √(Σ per-term maxima²), and the worst
polynomial's terms and coefficients (m31 = m32 = 0). How each method uses the
programme: docs/datasheets.md.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from gyrovib import units
from gyrovib.api.study.convert import g2_value
from gyrovib.api.study.prepare import Group, Prepared
from gyrovib.catalog.loader import SensorEntry
from gyrovib.coefficients import POLYNOMIAL
from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import (
    COLUMN,
    Multipliers,
    VibrationError,
    profile_multipliers,
    stack_multipliers,
)
from gyrovib.core.linear import mean_square
from gyrovib.frozen import Frozen

#: Rate powers of (A1, k2…k5): a coefficient in U is q[deg/s]·s**(-p).
_POWERS = np.array([0.0, -1.0, -2.0, -3.0, -4.0])
#: The words the nonlinearity's ``of`` may take when the value is %FS.
PERCENT_FS = "%FS"


def is_spec(entry: SensorEntry) -> bool:
    """Whether the sensor is given by its datasheet (``specs:``)."""
    return entry.sensor.specs is not None


def spec_index(entries: Sequence[SensorEntry]) -> NDArray[np.intp]:
    """Indices of the spec-form sensors among ``entries``."""
    return np.array([i for i, e in enumerate(entries) if is_spec(e)], dtype=np.intp)


@dataclass(frozen=True, eq=False, repr=False)
class SpecFigures(Frozen):
    """The datasheet figures of N spec-form sensors, in deg/s (and g).

    ``range`` R and ``limit`` b (deg/s); ``value``, ``unit`` the nonlinearity
    as written; ``percent`` the nonlinearity in %FS of the sensor's own
    ``of`` (range or span; for an absolute-rate figure: of the range);
    ``fit``, ``measure``, ``of``: the definition; ``asymmetry`` max |A1|
    (inf: no spec); ``vre`` |v| in deg/s per g² (0: no spec); ``has_vre``.
    """

    range: FloatArray
    limit: FloatArray
    percent: FloatArray
    fit: tuple[str, ...]
    measure: tuple[str, ...]
    of: tuple[str, ...]
    asymmetry: FloatArray
    vre: FloatArray
    has_vre: NDArray[np.bool_]


def figures(entries: Sequence[SensorEntry]) -> SpecFigures:
    """Convert every spec-form entry's datasheet to deg/s (see :class:`SpecFigures`)."""
    rng, lim, pct, asym, vre, has = [], [], [], [], [], []
    fits, measures, ofs = [], [], []
    for e in entries:
        spec = e.sensor.specs
        assert spec is not None
        s = units.scale(e.unit)
        r = spec.range * s
        nl = spec.nonlinearity
        if nl.unit == PERCENT_FS:
            of = nl.of
            b = nl.value / 100.0 * r * (2.0 if of == "span" else 1.0)
            percent = nl.value
        else:
            of = "range"
            b = nl.value * units.scale(nl.unit)
            percent = 100.0 * b / r
        a = np.inf
        if spec.asymmetry is not None:
            a = spec.asymmetry.value * (1e-6 if spec.asymmetry.unit == "ppm" else 1e-2)
        rng.append(r)
        lim.append(b)
        pct.append(percent)
        fits.append(nl.fit)
        measures.append(nl.measure)
        ofs.append(of)
        asym.append(abs(a))
        vre.append(0.0 if spec.vre is None else abs(g2_value(spec.vre, e.unit)))
        has.append(spec.vre is not None)
    return SpecFigures(np.array(rng, dtype=float), np.array(lim, dtype=float),
                       np.array(pct, dtype=float), tuple(fits), tuple(measures), tuple(ofs),
                       np.array(asym, dtype=float), np.array(vre, dtype=float),
                       np.array(has, dtype=bool))


def mean_square_acceleration(m: Multipliers) -> FloatArray:
    """S = Σ_j ⟨a_j²⟩ (g²) at each profile (× rate); 0 without a linear vibration."""
    if m.acceleration is None:
        return np.zeros(m.omega.shape)
    return np.asarray(mean_square(m.acceleration), dtype=float)


def terms_of(m: Multipliers) -> FloatArray:
    """The eight term functionals (shape + (8, 5)) of :func:`core.envelope.term_functionals`."""
    # lazy: the datasheet envelope (and HiGHS) only for datasheet sensors
    from gyrovib.core.envelope import term_functionals

    zero = np.zeros(m.omega.shape)
    return term_functionals(m.asymmetry, m.m2, zero if m.m3 is None else m.m3, m.m4,
                            zero if m.m5 is None else m.m5, m.omega)


@dataclass(frozen=True, eq=False, repr=False)
class SpecWorst(Frozen):
    """The worst case of N spec sensors over one group's profiles (× rates), in deg/s.

    ``error``: the :class:`VibrationError` of the worst polynomial (total =
    worst |Δ_V|, rms = the per-term RMS bound); ``coefficients`` x* (..., 5)
    in deg/s powers; ``rms_bound``; ``nonlinearity`` (cᵀx*) and ``g2`` (|v|·S).
    """

    error: VibrationError
    coefficients: FloatArray
    rms_bound: FloatArray
    nonlinearity: FloatArray
    g2: FloatArray


def worst(figs: SpecFigures, m: Multipliers, *, total: bool = True) -> SpecWorst:
    """Worst |Δ_V| of every sensor of ``figs`` under the multipliers ``m`` (any shape).

    One call to :func:`gyrovib.core.envelope.worst_case` over all profiles
    (× rates), flattened; the result has shape (N,) + m.omega.shape. A
    profile (× rate) whose multipliers are NaN (a method's refusal) gets NaN.
    ``total`` False: the per-term RMS bound only (``error.rms``); the rest is
    NaN, unknown (:func:`gyrovib.core.envelope.worst_case`).
    """
    # lazy: the datasheet envelope (and HiGHS) only for datasheet sensors
    from gyrovib.core.envelope import worst_case

    shape = m.omega.shape
    t = terms_of(m).reshape(-1, 8, 5)
    s = mean_square_acceleration(m).reshape(-1)
    n = figs.range.size
    ok = np.all(np.isfinite(t), axis=(1, 2)) & np.isfinite(s)
    k_all = t.shape[0]
    wc = worst_case(t[ok], s[ok], figs.range, figs.limit, figs.fit, figs.measure,
                    asymmetry=figs.asymmetry, vre=figs.vre, total=total)

    def spread(a: FloatArray) -> FloatArray:
        out = np.full((n, k_all, *a.shape[2:]), np.nan)
        out[:, ok] = a
        return out

    x = spread(wc.coefficients)                                      # (N, K, 5)
    total_, nonlin_, g2_, bound_ = (spread(wc.total), spread(wc.nonlinearity),
                                    spread(wc.g2), spread(wc.rms_bound))
    per = np.einsum("ktj,nkj->nkt", t, x)                            # (N, K, 8)
    zero = np.zeros(per.shape[:2])
    additive_terms = np.stack([per[..., 0], per[..., 1], per[..., 3], zero, zero], axis=-1)
    extra = np.stack([g2_, per[..., 2], per[..., 4]], axis=-1)
    flat_m2 = np.broadcast_to(m.m2, shape).reshape(-1)[None]
    flat_m4 = np.broadcast_to(m.m4, shape).reshape(-1)[None]
    flat_m3 = (np.zeros_like(flat_m2) if m.m3 is None
               else np.broadcast_to(m.m3, shape).reshape(-1)[None])
    k3, k4, k5 = x[..., 2], x[..., 3], x[..., 4]
    q = np.stack([3 * k3 * flat_m2 + 4 * k4 * flat_m3 + 5 * k5 * flat_m4,
                  6 * k4 * flat_m2 + 10 * k5 * flat_m3, 10 * k5 * flat_m2], axis=-1)
    mult = per[..., 5:].sum(axis=-1)
    additive = additive_terms.sum(axis=-1) + extra.sum(axis=-1)
    full = (n, *shape)
    error = VibrationError(
        additive_terms=additive_terms.reshape(*full, 5),
        multiplicative_coefficients=q.reshape(*full, 3),
        additive=additive.reshape(full),
        multiplicative=mult.reshape(full),
        total=total_.reshape(full),
        rms=bound_.reshape(full),
        extra_terms=extra.reshape(*full, 3),
    )
    return SpecWorst(error=error, coefficients=x.reshape(*full, 5),
                     rms_bound=bound_.reshape(full),
                     nonlinearity=nonlin_.reshape(full), g2=g2_.reshape(full))


def coefficient_rows(worst_x: FloatArray) -> FloatArray:
    """The worst polynomials (..., 5) as eq. (2) coefficient rows (..., 11), k1 = 1."""
    x = np.asarray(worst_x, dtype=float)
    out = np.zeros((*x.shape[:-1], len(COLUMN)))
    out[..., COLUMN["k1"]] = 1.0
    for k, name in enumerate(POLYNOMIAL):
        out[..., COLUMN[name]] = x[..., k]
    return out


def coefficients_in(worst_x: FloatArray, unit: str) -> FloatArray:
    """(A1, k2…k5) from deg/s powers to ``unit`` powers."""
    s = units.scale(unit)
    out: FloatArray = np.asarray(worst_x, dtype=float) * s ** (-_POWERS)
    return out


def cross_axis_warning(m: Multipliers) -> NDArray[np.bool_]:
    """Where the profile (× rate) has cross-axis vibration correlated with x3 (C31, C32 ≠ 0).

    There a spec-form sensor's m31 = m32 = 0 is an assumption worth stating.
    """
    out: NDArray[np.bool_] = (np.asarray(m.c31) != 0) | (np.asarray(m.c32) != 0)
    return out


CROSS_AXIS_NOTE = ("spec-form sensor: the datasheet gives no multiplicative cross-axis "
                   "coefficients, so m31 = m32 = 0 is taken although this profile has "
                   "cross-axis vibration correlated with x3")


# ----------------------------------------------------------------- the commands' hooks


def multipliers_of(group: Group, prepared: Prepared, method: str,
                   omega: FloatArray | None = None) -> Multipliers:
    """The group's multipliers for ``method``: prepared ones, or computed from its vibrations."""
    found = group.multipliers.get(method)
    if found is not None:
        return found
    items = [profile_multipliers(v, prepared.rates[j, 2] if omega is None else omega, method)
             for j, v in enumerate(group.vibrations)]
    return stack_multipliers(items)


@dataclass(frozen=True, eq=False, repr=False)
class SpecResults(Frozen):
    """The spec-form rows of a command: which sensors, and their worst case (deg/s).

    ``index``: the spec sensors among the prepared ones (M,); ``error``: their
    :class:`VibrationError` (M, P[, R]); ``coefficients``: the worst polynomials
    (M, P[, R], 5) in deg/s powers; ``nonlinearity``, ``g2``: the two parts of
    ``error.total``; ``cross_axis``: (P[, R]) where m31 = m32 = 0 is assumed
    against cross-axis vibration; ``figures``: the converted datasheets.
    """

    index: NDArray[np.intp]
    figures: SpecFigures
    error: VibrationError
    coefficients: FloatArray
    nonlinearity: FloatArray
    g2: FloatArray
    cross_axis: NDArray[np.bool_]


def spec_groups(prepared: Prepared, index: NDArray[np.intp]) -> Iterator[tuple[Group, list[int]]]:
    """Each response group of ``prepared`` that holds spec sensors of ``index`` (rows of
    ``prepared.sensors``), with their positions in ``index``; none without profiles."""
    position = {int(i): k for k, i in enumerate(index.tolist())}
    for group in prepared.groups:
        rows = [position[int(i)] for i in group.index.tolist() if int(i) in position]
        if rows and prepared.profiles:
            yield group, rows


def spec_results(prepared: Prepared, method: str, omega: FloatArray | None = None,
                 *, total: bool = True) -> SpecResults | None:
    """The worst case of every spec-form sensor of ``prepared`` (None when there are none).

    Each sensor group (one response ν_sensor) is one call of the envelope
    programme over all its spec sensors × profiles (× rates ``omega``).
    """
    index = spec_index(prepared.sensors)
    if index.size == 0:
        return None
    figs = figures([prepared.sensors[i] for i in index.tolist()])
    n_p = len(prepared.profiles)
    tail = () if omega is None else (np.asarray(omega).size,)
    shape = (index.size, n_p, *tail)
    parts = {name: np.zeros((*shape, *t)) for name, t in
             (("additive_terms", (5,)), ("multiplicative_coefficients", (3,)),
              ("additive", ()), ("multiplicative", ()), ("total", ()), ("rms", ()),
              ("extra_terms", (3,)))}
    coefficients = np.zeros((*shape, 5))
    nonlinearity = np.zeros(shape)
    g2 = np.zeros(shape)
    cross = np.zeros((n_p, *tail), dtype=bool)
    for group, rows in spec_groups(prepared, index):
        m = multipliers_of(group, prepared, method, omega)
        _fill(parts, {"coefficients": coefficients, "nonlinearity": nonlinearity, "g2": g2},
              _subset(figs, rows), m, rows, omega is not None, total)
        cross |= cross_axis_warning(m)
    return SpecResults(index=index, figures=figs, error=VibrationError(**parts),
                       coefficients=coefficients, nonlinearity=nonlinearity, g2=g2,
                       cross_axis=cross)


#: Rates per call of the envelope programme in a sweep.
_RATE_BLOCK = 500


def _fill(parts: dict[str, FloatArray], worst_parts: dict[str, FloatArray], figs: SpecFigures,
          m: Multipliers, rows: list[int], sweep: bool, total: bool) -> None:
    """One group's worst case into ``rows`` of ``parts`` (its error) and ``worst_parts``
    (its polynomial, nonlinearity and g² part). A sweep (``sweep``) in blocks of rates:
    the envelope programmes of all its rates at once held 4 GB at 20,000 rates; a
    block's neighbours still polish each other."""
    n_rates = m.omega.shape[-1]
    width = _RATE_BLOCK if sweep else n_rates
    for lo in range(0, n_rates if sweep else 1, width):
        at: tuple[Any, ...] = (rows, slice(None), slice(lo, lo + width)) if sweep else (rows,)
        result = worst(figs, _rate_block(m, lo, width) if sweep else m, total=total)
        for name, array in parts.items():
            array[at] = getattr(result.error, name)
        for name, array in worst_parts.items():
            array[at] = getattr(result, name)


def _rate_block(m: Multipliers, lo: int, width: int) -> Multipliers:
    """The multipliers at rates ``lo : lo + width`` of a (profiles, rates) sweep."""
    fields: dict[str, Any] = {}
    for name in Multipliers.__dataclass_fields__:
        value = getattr(m, name)
        if value is None:
            fields[name] = None
        elif name == "acceleration":
            fields[name] = value[..., lo:lo + width, :]
        else:
            fields[name] = value[..., lo:lo + width]
    return Multipliers(**fields)


def _subset(figs: SpecFigures, rows: Sequence[int]) -> SpecFigures:
    r = list(rows)
    return SpecFigures(figs.range[r], figs.limit[r], figs.percent[r],
                       tuple(figs.fit[k] for k in r), tuple(figs.measure[k] for k in r),
                       tuple(figs.of[k] for k in r), figs.asymmetry[r], figs.vre[r],
                       figs.has_vre[r])


def place(parts: dict[str, FloatArray], spec: SpecResults) -> None:
    """Write the spec rows' worst-case error into a command's (sensors, ...) arrays."""
    for name, array in parts.items():
        array[spec.index] = getattr(spec.error, name)


def numeric_rows(coefficients: FloatArray, index: NDArray[np.intp], profile: int,
                 spec: SpecResults, sensors: NDArray[np.intp] | None = None) -> FloatArray:
    """A group's coefficient rows for brute force under one profile (specs: worst polynomial).

    ``sensors``: the sensors of the rows ``index`` of ``coefficients`` (default ``index``
    itself: ``coefficients`` has a row per sensor)."""
    out = np.array(coefficients[index], dtype=float)
    where = {int(i): k for k, i in enumerate(spec.index.tolist())}
    for r, i in enumerate((index if sensors is None else sensors).tolist()):
        k = where.get(int(i))
        if k is not None:
            out[r] = coefficient_rows(spec.coefficients[k, profile])
    return out


def place_analysis(parts: dict[str, FloatArray], spec: SpecResults, *, numeric: bool) -> None:
    """Spec rows of ``analyze``: the worst case (closed forms) or its brute force (numeric).

    Under brute force ``total`` is the simulated Δ_V of the worst polynomial
    plus the g² part |v|·S (the averaging of eq. (2) covers the rate terms
    only); ``rms`` is the per-term bound.
    """
    if numeric:
        parts["total"][spec.index] = parts["total"][spec.index] + spec.g2
        parts["rms"][spec.index] = spec.error.rms
        return
    for name, array in parts.items():
        array[spec.index] = getattr(spec.error, name)


NO_VRE_NOTE = ("spec-form sensor: the datasheet publishes no VRE, so the g² term of this "
               "profile's linear vibration is unknown, and with it Δ_VA, Δ_V and Δ_V(RMS) "
               "(unknown, not zero: `select` calls such a part unverified)")
NO_G2_NOTE = ("the sensor gives no g² sensitivity (g2_sensitivity or vre), so the g² term of "
              "this profile's linear vibration is unknown, and with it Δ_VA, Δ_V and "
              "Δ_V(RMS) (unknown, not zero: `select` calls such a sensor unverified; write "
              "`vre: 0` for a known zero)")
#: The notes of a g² term whose figure is unknown (and every sum of it with it).
UNKNOWN_TERM_NOTES = (NO_VRE_NOTE, NO_G2_NOTE)


def g2_unknown(sensor: Any) -> bool:
    """Whether a coefficient-form sensor gives no g² figure at all (neither
    ``g2_sensitivity`` nor ``vre``): its g² sensitivity is unknown, not zero
    (docs/model.md section 8). Datasheet parts are judged by their VRE figure."""
    return sensor.specs is None and sensor.g2_sensitivity is None and sensor.vre is None


def with_unknown_g2(warnings: dict[tuple[int, int], tuple[str, ...]], sensors: Sequence[Any],
                    linear: Sequence[bool]) -> dict[tuple[int, int], tuple[str, ...]]:
    """``warnings`` plus :data:`NO_G2_NOTE` for each coefficient-form sensor without a g²
    figure (:func:`g2_unknown`) under each profile with linear vibration (``linear``)."""
    for i, entry in enumerate(sensors):
        if not g2_unknown(entry.sensor):
            continue
        for j, shaken in enumerate(linear):
            if shaken:
                warnings[(i, j)] = (*warnings.get((i, j), ()), NO_G2_NOTE)
    return warnings


def unknown_g2_cells(sensors: Sequence[Any], spec: SpecResults | None,
                     linear: Sequence[bool]) -> list[tuple[int, int]]:
    """The (sensor, profile) cells whose g² term is unknown: a coefficient-form sensor
    without a g² figure (:func:`g2_unknown`) or a datasheet part that publishes no VRE,
    under a profile with linear vibration (``linear``): the cells :data:`NO_G2_NOTE` and
    :data:`NO_VRE_NOTE` are said of."""
    unpublished = set() if spec is None else {
        int(i) for k, i in enumerate(spec.index.tolist()) if not spec.figures.has_vre[k]}
    rows = [i for i, entry in enumerate(sensors)
            if i in unpublished or g2_unknown(entry.sensor)]
    return [(i, j) for i in rows for j, shaken in enumerate(linear) if shaken]


def with_cross_axis(warnings: dict[tuple[int, int], tuple[str, ...]],
                    spec: SpecResults | None,
                    linear: Sequence[bool] = ()) -> dict[tuple[int, int], tuple[str, ...]]:
    """``warnings`` plus the m31 = m32 = 0 note for spec sensors under cross-axis profiles,
    and the no-VRE note for those without a VRE spec under the profiles with linear
    vibration (``linear``, per profile)."""
    if spec is None:
        return warnings
    cross = spec.cross_axis.reshape(spec.cross_axis.shape[0], -1).any(axis=1)
    for k, i in enumerate(spec.index.tolist()):
        for j in np.nonzero(cross)[0].tolist():
            warnings[(int(i), int(j))] = (*warnings.get((int(i), int(j)), ()), CROSS_AXIS_NOTE)
        if spec.figures.has_vre[k]:
            continue
        for j, shaken in enumerate(linear):
            if shaken:
                warnings[(int(i), j)] = (*warnings.get((int(i), j), ()), NO_VRE_NOTE)
    return warnings


def analysis_fields(n_s: int, n_p: int, spec: SpecResults | None,
                    unit: str) -> dict[str, Any]:
    """The spec-form fields of an :class:`~gyrovib.api.AnalysisResult` (empty without specs)."""
    if spec is None:
        return {}
    sources = ["coefficients"] * n_s
    for i in spec.index.tolist():
        sources[i] = "specs"
    worst_x = np.full((n_s, n_p, 5), np.nan)
    worst_x[spec.index] = coefficients_in(spec.coefficients, unit)
    bound = np.full((n_s, n_p), np.nan)
    bound[spec.index] = spec.error.rms / units.scale(unit)
    published: list[tuple[str, ...]] = [()] * n_s
    for k, i in enumerate(spec.index.tolist()):
        published[i] = ("nonlinearity",
                        *(("asymmetry",) if np.isfinite(spec.figures.asymmetry[k]) else ()),
                        *(("vre",) if spec.figures.has_vre[k] else ()))
    return {"sources": tuple(sources), "worst_coefficients": worst_x, "rms_bound": bound,
            "published": tuple(published)}


# ----------------------------------------------------------------- sweep


def sweep_fields(n_s: int, spec: SpecResults, unit: str) -> dict[str, Any]:
    """The spec-form fields of a :class:`~gyrovib.api.SweepResult` (exact method)."""
    sources = ["coefficients"] * n_s
    fit = [""] * n_s
    for k, i in enumerate(spec.index.tolist()):
        sources[i] = "specs"
        fit[i] = spec.figures.fit[k]
    s = units.scale(unit)
    shape = spec.coefficients.shape[1:]
    worst_x = np.full((n_s, *shape), np.nan)
    worst_x[spec.index] = coefficients_in(spec.coefficients, unit)
    limit = np.full(n_s, np.nan)
    limit[spec.index] = spec.figures.limit / s
    rng = np.full(n_s, np.nan)
    rng[spec.index] = spec.figures.range / s
    return {"sources": tuple(sources), "worst_coefficients": worst_x, "nl_limit": limit,
            "nl_range": rng, "nl_fit": tuple(fit)}


def worst_residual(result: Any, i: int, j: int, r: int,
                   points: int = 401) -> tuple[FloatArray, FloatArray, float]:
    """The worst polynomial's residual from its reference line over [−R, R] (plot units).

    For spec sensor ``i`` of a sweep result at profile ``j`` and rate index
    ``r``: (ω, r(ω), b). The line is the polynomial's own least-squares or
    endpoint line, or for minimax the line of least peak deviation on the grid
    (:func:`gyrovib.core.envelope.residual` with the line recomputed here, in
    the result's unit).
    """
    # lazy: the datasheet envelope (and HiGHS) only for datasheet sensors
    from gyrovib.core.envelope import residual
    from gyrovib.core.envelope_lp import minimax_line

    x = np.asarray(result.worst_coefficients[i, j, r], dtype=float)
    big_r = float(result.nl_range[i])
    w = np.linspace(-big_r, big_r, points)
    p = residual(x, np.zeros(2), w)
    fit = result.nl_fit[i]
    if fit == "endpoint":
        slope = (p[-1] - p[0]) / (2 * big_r)
        line = 0.5 * (p[-1] + p[0]) + slope * w
    elif fit == "minimax":
        line = minimax_line(w, p)
    else:
        slope, intercept = np.polyfit(w, p, 1)
        line = intercept + slope * w
    return w, p - line, float(result.nl_limit[i])
