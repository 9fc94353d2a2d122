"""``gyrovib runup``: a run-up test turned into the installed sensor's own rectification
(docs/model.md section 16; the kernels are core/runup.py).

:func:`runup` measures the steps (:mod:`gyrovib.api.runup.measure`), fits (16.1) by
weighted least squares, and with a catalogue sensor sets each step's measured shift
beside its prediction, Δ_V,rec of section 13 on the step's samples less the baseline's.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from gyrovib.api.datasheet.specs import figures, g2_unknown, is_spec
from gyrovib.api.ratetable.results import coefficient_unit
from gyrovib.api.recordings.analysis import recorded_totals
from gyrovib.api.recordings.reading import Recording
from gyrovib.api.runup.measure import Measured, baseline, measure, need_scipy
from gyrovib.api.runup.results import (
    OUTSIDE,
    UNVERIFIED,
    WITHIN,
    Estimate,
    RunupResult,
    Step,
)
from gyrovib.api.study.convert import coefficient_matrix
from gyrovib.api.study.entries import select_entries
from gyrovib.api.study.linear import g2_matrix
from gyrovib.api.study.prepare import input_response
from gyrovib.core import runup as kernel
from gyrovib.core._types import FloatArray
from gyrovib.core.linear import G2_TERMS
from gyrovib.core.transmissibility import as_table
from gyrovib.errors import OptionError
from gyrovib.limits import DEFAULT_CROSSOVER as DEFAULT_CROSSOVER

#: A measured shift is within its prediction's interval when it lies within this many
#: standard uncertainties of it (about 95 %).
COVERAGE = 2.0
#: An estimate is ``found`` when its value is at least this many uncertainties from 0.
FOUND_T = 2.0
#: Where each rate-form term sits in a row of the coefficient matrix (core.analysis).
_COLUMN = {"A1": 2, "k2": 3, "k4": 5, "m31": 9, "m32": 10}
#: The least variance of a step's mean, (deg/s)²: a record without noise (synthetic, or
#: quantised flat) would otherwise weigh infinitely.
TINY = 1e-30
_RATE_UNIT = "deg/s"


def estimate_units(name: str) -> str:
    """The unit of an in-situ term: eq. (2)'s in deg/s, the g² terms in deg/s/g^2."""
    if name in _COLUMN:
        return coefficient_unit(name, _RATE_UNIT)
    return f"{_RATE_UNIT}/g^2"


def default_terms(recording: Recording) -> tuple[str, ...]:
    """``vre`` where the recording holds accelerations, else ``k2``."""
    return ("vre",) if recording.store.has_accel else ("k2",)


def check_terms(terms: Sequence[str], recording: Recording) -> tuple[str, ...]:
    """The terms to estimate, each known and measurable on this recording, given once."""
    if not recording.rate_axes[2]:
        raise OptionError("the run-up test measures the rate about x3 (Z), which the "
                          "recording does not hold")
    out: list[str] = []
    for t in terms:
        if t not in kernel.TERMS:
            raise OptionError(f"cannot estimate {t!r}: choose among {', '.join(kernel.TERMS)}")
        if t in out:
            raise OptionError(f"{t!r} is asked for twice")
        need = kernel.RATE_NEEDS.get(t, ())
        missing = [("X", "Y", "Z")[j] for j in need if not recording.rate_axes[j]]
        if missing:
            raise OptionError(f"{t} needs the rate about {', '.join(missing)}, which the "
                              "recording does not hold")
        if t not in kernel.RATE_NEEDS and not recording.store.has_accel:
            raise OptionError(f"{t} is a g² term: it needs the recording's accelerations")
        out.append(t)
    if "vre" in out and {"G11", "G22", "G33"} & set(out):
        raise OptionError("vre is G11 = G22 = G33: estimate it or the G_jj, not both")
    if not out:
        raise OptionError("no term to estimate")
    return tuple(out)


def runup(recording: Recording, catalog: Any = None, *, sensor: str | None = None,
          steps: Sequence[tuple[float, float]] | None = None,
          estimate: Sequence[str] | None = None,
          crossover: float = DEFAULT_CROSSOVER) -> RunupResult:
    """A run-up test on ``recording`` (docs/model.md section 16).

    ``steps``: (start, end) in s from the first sample; None finds them from the running
    variance of x3 and of a. ``estimate``: the terms of :data:`gyrovib.core.runup.TERMS`
    (default :func:`default_terms`). ``sensor``: a sensor of ``catalog`` whose prediction
    is set beside each step's measured shift, and whose figures beside the estimates.
    """
    need_scipy(recording)
    if not (math.isfinite(crossover) and crossover > 0):
        raise OptionError(f"the crossover {crossover:g} Hz must be a positive frequency")
    terms = check_terms(estimate if estimate else default_terms(recording), recording)
    entry = _entry(catalog, sensor)
    response = None if entry is None else input_response(entry)
    responses = None if entry is None else () if response is None else (as_table(response),)
    measured = measure(recording, crossover, steps, responses)
    if len(measured) < len(terms) + 1:
        raise OptionError(
            f"{len(measured)} step(s) found for {len(terms)} term(s) and the constant: the "
            f"test needs at least {len(terms) + 1} steps at distinct vibration levels (give "
            "the steps, or record longer steps)")
    return _result(recording, crossover, measured, terms, entry, steps is not None)


def _entry(catalog: Any, sensor: str | None) -> Any:
    if sensor is None:
        return None
    if catalog is None:
        raise OptionError(f"sensor {sensor!r}: no catalogue to find it in")
    entries, _ = select_entries(catalog, (sensor,), (), need=("sensors",))
    return entries[0]


def _result(recording: Recording, crossover: float, measured: list[Measured],
            terms: tuple[str, ...], entry: Any, given: bool) -> RunupResult:
    idx = [kernel.TERMS.index(t) for t in terms]
    y = np.array([m.mean for m in measured])
    t = np.array([(m.start + m.end) / 2 for m in measured])
    var = np.maximum([m.variance for m in measured], TINY)
    phi = np.array([m.phi[idx] for m in measured]).reshape(len(measured), len(idx))
    fit = kernel.fit_steps(y, t, phi, var)
    base = baseline(measured)
    predicted, bound = _predictions(measured, base, entry, var)
    steps = _steps(measured, base, terms, fit, phi, var, predicted, bound, entry is not None,
                   recording.rate_axes)
    catalogue, cat_bound = _catalogue(entry, terms)
    estimates = tuple(_estimate(k, name, fit, len(measured), terms, catalogue[k], cat_bound[k])
                      for k, name in enumerate(terms))
    sd = np.sqrt(np.diag(fit.covariance))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = fit.covariance / np.outer(sd, sd)
    notes = _notes(recording, steps, estimates, fit, entry)
    return RunupResult(
        file=recording.file, sha256=recording.sha256, fs=recording.fs,
        samples=recording.samples, crossover=crossover, steps=steps, estimates=estimates,
        constant=fit.constant, drift=fit.drift, drift_uncertainty=fit.drift_sigma,
        drift_vif=fit.drift_vif, chi2=fit.chi2, dof=fit.dof, inflation=fit.inflation,
        correlation=tuple(tuple(float(v) for v in row) for row in corr),
        sensor=None if entry is None else entry.sensor.id, steps_given=given,
        limits=_limits(recording), notes=notes, warnings=recording.warnings,
        topic=recording.topic, instance=recording.instance)


def _weighted(values: FloatArray, var: FloatArray, base: np.ndarray) -> float:
    w = 1.0 / var[base]
    return float(np.sum(w * values[base]) / np.sum(w))


def _steps(measured: list[Measured], base: np.ndarray, terms: tuple[str, ...],
           fit: kernel.StepFit, phi: FloatArray, var: FloatArray, predicted: FloatArray,
           bound: bool, compared: bool,
           rate_axes: tuple[bool, bool, bool]) -> tuple[Step, ...]:
    y = np.array([m.mean for m in measured])
    t = np.array([(m.start + m.end) / 2 for m in measured])
    d = fit.drift if math.isfinite(fit.drift) else 0.0
    ud = fit.drift_sigma if math.isfinite(fit.drift_sigma) else 0.0
    y_b, t_b = _weighted(y, var, base), _weighted(t, var, base)
    var_b = 1.0 / float(np.sum(1.0 / var[base]))
    phi_b = np.array([_weighted(phi[:, k], var, base) for k in range(phi.shape[1])])
    theta = np.nan_to_num(fit.values)
    outliers = kernel.flagged_residuals(fit.residuals, var)
    moved = _moved(measured, base, rate_axes)
    out = []
    for s, m in enumerate(measured):
        shift = float(y[s] - y_b - d * (t[s] - t_b))
        u2 = var[s] + var_b - (2 * var_b if base[s] else 0.0) + (t[s] - t_b) ** 2 * ud ** 2
        u = math.sqrt(max(u2, 0.0))
        out.append(Step(
            index=s, start=m.start, end=m.end, baseline=bool(base[s]), mean=m.mean,
            variance=float(var[s]), x3_rms=m.x3_rms, accel_rms=m.accel_rms,
            regressors=tuple((name, float(phi[s, k])) for k, name in enumerate(terms)),
            shift=shift, uncertainty=u, fitted=float((phi[s] - phi_b) @ theta),
            residual=float(fit.residuals[s]), predicted=float(predicted[s]), bound=bound,
            status=_status(shift, u, float(predicted[s]), bound, base[s]) if compared else None,
            outlier=bool(outliers[s]), moved=bool(moved[s])))
    return tuple(out)


def _status(shift: float, u: float, predicted: float, bound: bool, base: bool) -> str:
    """The measured shift against the prediction's interval (unverified: unknown)."""
    if math.isnan(predicted):
        return UNVERIFIED
    if base:
        return WITHIN
    gap = abs(shift) - abs(predicted) if bound else abs(shift - predicted)
    return WITHIN if gap <= COVERAGE * u else OUTSIDE


def _moved(measured: list[Measured], base: np.ndarray,
           recorded: tuple[bool, bool, bool]) -> np.ndarray:
    """Steps where the vehicle moved: on some recorded axis the carrier's angle excursion
    (:func:`gyrovib.core.runup.angle_excursion`: it turned and came back) exceeds
    :data:`~gyrovib.core.runup.MOVED_FACTOR` times the median step's, both per √T (the
    vibration's own low-frequency shaking raises every vibrating step a little; a turn
    stands out). A steady rectified offset leaves the excursion alone; about x3 a step
    off the fit is also the residual's flag."""
    axes = [j for j in range(3) if recorded[j]]
    excursion = np.array([m.excursion for m in measured])[:, axes]
    root = np.sqrt([m.end - m.start for m in measured])[:, None]
    per_root = excursion / root
    reference = np.maximum(np.median(per_root, axis=0), 1e-12)
    out: np.ndarray = np.any(per_root > kernel.MOVED_FACTOR * reference, axis=1)
    return out


def _predictions(measured: list[Measured], base: np.ndarray, entry: Any,
                 var: FloatArray) -> tuple[FloatArray, bool]:
    """Each step's predicted shift (deg/s): Δ_V,rec on its samples less the baseline's
    (weighted like the means; Δ_V,rec is linear in the moments, so it is Δ_V,rec of the
    moments' difference). A spec-form sensor's is the envelope's worst |Δ_s − Δ_b|, a
    bound (its g² part taken on |⟨a_j a_k⟩_s − ⟨a_j a_k⟩_b| per term, which can only
    raise it).
    NaN where a term the prediction needs is unknown (a g² sensitivity the datasheet does
    not publish, or accelerations the recording does not hold)."""
    n = len(measured)
    if entry is None:
        return np.full(n, np.nan), False
    spec = is_spec(entry)
    row = 1 if input_response(entry) is not None else 0
    moments = np.array([m.moments[row] for m in measured])
    g2 = None if measured[0].g2_moments is None else np.array([m.g2_moments
                                                                for m in measured])
    m_b = np.sum(moments[base] / var[base, None], axis=0) / np.sum(1.0 / var[base])
    g_b = None if g2 is None else np.sum(g2[base] / var[base, None], axis=0) / np.sum(
        1.0 / var[base])
    out = np.empty(n)
    for s in range(n):
        d = (moments[s] - m_b).reshape(1, -1)
        g = None if g2 is None or g_b is None else g2[s] - g_b
        if spec:  # the envelope's worst |Δ_s − Δ_b|, both signs of the difference
            g = None if g is None else np.abs(g)
            out[s] = max(recorded_totals([entry], d, g)[0], recorded_totals([entry], -d, g)[0])
        else:
            out[s] = recorded_totals([entry], d, g)[0]
    if _g2_unknown(entry, measured, spec):
        out = np.full(n, np.nan)
    return out, spec


def _g2_unknown(entry: Any, measured: list[Measured], spec: bool) -> bool:
    """Whether the prediction's g² part is unknown: a datasheet without a VRE figure or a
    sensor that gives no g² figure (:func:`~gyrovib.api.datasheet.specs.g2_unknown`) on a
    recording with accelerations, or a sensor with a g² sensitivity (or a datasheet) on a
    recording without them."""
    has_accel = measured[0].g2_moments is not None
    if spec:
        return not has_accel or not bool(figures([entry]).has_vre[0])
    if has_accel:
        return g2_unknown(entry.sensor)
    return bool(np.any(g2_matrix([entry]) != 0))


def _catalogue(entry: Any, terms: tuple[str, ...]) -> tuple[list[float], list[bool]]:
    """The sensor's own figure of each term in its unit (NaN unknown), and whether it is a
    datasheet bound on |value|."""
    n = len(terms)
    if entry is None:
        return [math.nan] * n, [False] * n
    if is_spec(entry):
        figs = figures([entry])
        known = {"vre": float(figs.vre[0]) if figs.has_vre[0] else math.nan,
                 "A1": float(figs.asymmetry[0]) if np.isfinite(figs.asymmetry[0]) else math.nan}
        figures_ = [known.get(t, math.nan) for t in terms]
        return figures_, [math.isfinite(v) for v in figures_]
    row = coefficient_matrix([entry])[0]
    g = g2_matrix([entry])[0]
    values = {name: float(row[col]) for name, col in _COLUMN.items()}
    values |= dict(zip(G2_TERMS, map(float, g), strict=True))
    values["vre"] = float(g[0]) if g[0] == g[1] == g[2] and not np.any(g[3:]) else math.nan
    return [values[t] for t in terms], [False] * n


def _estimate(k: int, name: str, fit: kernel.StepFit, steps: int, terms: tuple[str, ...],
              catalogue: float, bound: bool) -> Estimate:
    value, sigma = float(fit.values[k]), float(fit.sigma[k])
    separable = bool(fit.separable[k])
    if not separable:
        status, separate = "not identifiable", _separation(k, fit, steps, terms)
    elif not sigma < abs(value):
        status = "not identifiable"
        separate = ("longer steps or a stronger top step: its effect is below the noise of "
                    "these steps")
    elif abs(value) < FOUND_T * sigma:
        status, separate = "not significant", None
    else:
        status, separate = "found", None
    return Estimate(name=name, value=value, uncertainty=sigma, unit=estimate_units(name),
                    identifiable=bool(fit.identifiable[k]), status=status, separate=separate,
                    catalogue=catalogue, catalogue_bound=bound, vif=float(fit.vif[k]))


_LEVELS = {"A1", "k2", "k4"}


def _separation(k: int, fit: kernel.StepFit, steps: int, terms: tuple[str, ...]) -> str:
    """What step would separate term k from what it is collinear with."""
    partner = int(fit.partner[k])
    name = terms[k]
    if partner == -2:
        return (f"more steps, each at a vibration level of its own: {steps} steps for "
                f"{len(terms)} term(s), the constant and the drift")
    if partner == -3:
        return (f"a step where the {name} regressor changes: it is the same on every one of "
                "these steps (no vibration where the term needs it)")
    if partner == -1:
        return ("a step at a lower vibration level after the highest (down again): it "
                "separates the drift from the vibration")
    if partner >= len(terms):
        return "a step at another vibration level"
    other = terms[partner]
    if {name, other} <= _LEVELS:
        return (f"a step at another vibration level: {name} and {other} grow as different "
                "powers of the vibration (A1 as its rms, k2 as its square, k4 as the fourth "
                "power), which these steps do not tell apart")
    return (f"a step where the regressors of {name} and {other} change in another ratio, e.g. "
            "angular and linear vibration stepped apart (another speed, another mount, or a "
            "shaker along one axis)")


def _notes(recording: Recording, steps: tuple[Step, ...], estimates: tuple[Estimate, ...],
           fit: kernel.StepFit, entry: Any) -> tuple[str, ...]:
    notes = []
    if not math.isfinite(fit.drift):
        notes.append(f"no drift term: the steps' order does not separate it from the "
                     f"vibration (VIF of time {fit.drift_vif:.3g} > "
                     f"{kernel.DRIFT_VIF_LIMIT:g}); step down again to separate it")
    if fit.inflation > 1.0:
        notes.append(f"reduced χ² = {fit.inflation:.3g} > 1: the uncertainties are inflated "
                     "by its square root")
    for s in steps:
        if s.outlier:
            notes.append(f"step {s.index} ({s.start:.6g}–{s.end:.6g} s) is "
                         f"{abs(s.residual) / s.sigma:.2g} σ off the fit: vibration the log "
                         "does not see (above its Nyquist frequency, or aliased) or a step "
                         "that was not static")
        if s.moved:
            notes.append(f"step {s.index} ({s.start:.6g}–{s.end:.6g} s): the carrier rate "
                         "shows the vehicle moving; the rest assumption does not hold there")
    notes += _against_catalogue(recording, estimates, entry)
    return tuple(notes)


def _against_catalogue(recording: Recording, estimates: tuple[Estimate, ...],
                       entry: Any) -> list[str]:
    out = []
    for e in estimates:
        if e.status != "found" or not math.isfinite(e.catalogue):
            continue
        far = (abs(e.value) - COVERAGE * e.uncertainty > e.catalogue if e.catalogue_bound
               else abs(e.value - e.catalogue) > COVERAGE * e.uncertainty)
        if far:
            word = "the datasheet's bound" if e.catalogue_bound else "the catalogue's"
            out.append(
                f"in-situ {e.name} {e.value:.3g} ± {e.uncertainty:.2g} {e.unit}, {word} "
                f"{e.catalogue:.3g} ({entry.sensor.id}): what the model lacks — a resonance "
                "of the mount or of the sensor, a tone above the log's Nyquist frequency "
                f"({recording.fs / 2:.6g} Hz), aliasing — is a possibility, as is a sensor "
                "off its datasheet")
    return out


def _limits(recording: Recording) -> tuple[str, ...]:
    return (f"the log sees vibration only below fs/2 = {recording.fs / 2:.6g} Hz; the "
            "sensor's element may see more, and rectify it without it showing in the "
            "regressors",
            "the vehicle must stay at rest during each step: an attitude change breaks the "
            "test (steps where the carrier rate shows one are flagged 'moved')")


__all__ = ["COVERAGE", "DEFAULT_CROSSOVER", "check_terms", "default_terms", "estimate_units",
           "runup"]
