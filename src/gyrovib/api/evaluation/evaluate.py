"""The model evaluated on a prepared study: each sensor form's error, and saturation.

Every view (``analyze``, ``sweep``, ``select``, the report, the notebook)
takes its numbers from here, so the error loop over the sensor groups and the
saturation rule are written once.

A sensor is given in one of a few *forms*; each form is one small object with
the same interface (:class:`SensorForm`):

* :class:`CoefficientForm` — a conversion function's coefficients (written as
  ``coefficients:``, or ``output_coefficients:`` divided by K1 when loaded):
  its error terms are eq. (13)-(16) of its own polynomial;
* :class:`DatasheetForm` — a datasheet (``specs:``): its error terms are those
  of the worst polynomial its envelope allows (docs/model.md section 11,
  :mod:`gyrovib.api.datasheet.specs`), its bound checks the datasheet figures against
  their spec bounds.

A form answers for its own rows only; no form writes placeholder rows another
overwrites. A new form (a lot of parts, say) is a new class here and an entry
in :data:`FORMS`.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from gyrovib.api.datasheet import specs
from gyrovib.api.datasheet.spec_bounds import SpecChecks
from gyrovib.api.evaluation.checks import (
    BoundVerdict,
    CoefficientChecks,
    CoefficientVerdict,
    DatasheetVerdict,
)
from gyrovib.api.study.convert import sensor_ranges
from gyrovib.api.study.prepare import Group, Prepared
from gyrovib.api.study.study import Study, omega_key
from gyrovib.catalog.loader import SensorEntry
from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import EXTRA_TERMS, vibration_error
from gyrovib.core.phases import WorstPhases, worst_phase_errors
from gyrovib.core.saturation import saturated as saturated_at
from gyrovib.frozen import Frozen
from gyrovib.progress import part_of

#: The arrays of a :class:`~gyrovib.core.analysis.VibrationError` and their trailing shapes.
ERROR_PARTS: dict[str, tuple[int, ...]] = {
    "additive_terms": (5,), "multiplicative_coefficients": (3,), "additive": (),
    "multiplicative": (), "total": (), "rms": (), "extra_terms": (len(EXTRA_TERMS),)}


class SensorForm(Protocol):
    """How one form of sensor enters the model.

    ``source``: its name in results (``"coefficients"``, ``"specs"``);
    :meth:`owns` picks its sensors; :meth:`error` writes their error terms
    (deg/s) into the (sensors, profiles[, rates]) arrays ``parts``.
    Saturation is the same rule for every form (:func:`saturation`), against
    each sensor's own range (:func:`~gyrovib.api.study.convert.sensor_ranges`).
    """

    source: str
    #: Whether its error is a bound over the unknown phases of ``phase: worst`` orders,
    #: taken on multipliers at their largest over them (not a search of the phases).
    bounds_phases: bool

    def owns(self, entry: SensorEntry) -> bool: ...

    def error(self, study: Study, prepared: Prepared, rows: NDArray[np.intp], method: str,
              omega: FloatArray | None, parts: dict[str, FloatArray],
              rms_only: bool = False) -> None: ...

    def phase_search(self, prepared: Prepared, group: Group,
                     rows: NDArray[np.intp]) -> Iterator[tuple[int, WorstPhases]]: ...

    def polynomials(self, block: FloatArray, at: NDArray[np.intp], sensors: NDArray[np.intp],
                    profile: int, spec: specs.SpecResults | None) -> None: ...

    def numeric_done(self, parts: dict[str, FloatArray],
                     spec: specs.SpecResults | None) -> None: ...

    def bound_checks(self, rows: NDArray[np.intp], checks: CoefficientChecks,
                     own: SpecChecks | None) -> BoundVerdict: ...


class CoefficientForm:
    """A sensor given by its conversion function's coefficients (eq. 2)."""

    source = "coefficients"
    bounds_phases = False

    def owns(self, entry: SensorEntry) -> bool:
        return entry.sensor.specs is None

    def error(self, study: Study, prepared: Prepared, rows: NDArray[np.intp], method: str,
              omega: FloatArray | None, parts: dict[str, FloatArray],
              rms_only: bool = False) -> None:
        """Eq. (13)-(16) for its rows, one vectorised call per sensor group.

        ``parts`` empty: its rows are every sensor, in one group; the arrays of
        that one call become the results (a long sweep's are large: copied into
        zeros they would double its memory).
        """
        shape = (len(prepared.sensors), len(prepared.profiles),
                 *(() if omega is None else (np.asarray(omega).size,)))
        whole = not parts
        mine = np.zeros(len(prepared.sensors), dtype=bool)
        mine[rows] = True
        for group in prepared.groups:
            idx = group.index[mine[group.index]]
            if idx.size == 0:
                continue
            err = vibration_error(prepared.coefficients[idx], group.multipliers[method],
                                  g2_sensitivity=prepared.g2[idx])
            if whole:
                _take_whole(err, shape, parts, group.multipliers[method])
                continue
            for name, array in parts.items():
                array[idx] = getattr(err, name)

    def phase_search(self, prepared: Prepared, group: Group,
                     rows: NDArray[np.intp]) -> Iterator[tuple[int, WorstPhases]]:
        """Per profile with ``phase: worst`` orders, the phases maximising |Δ_V| of each of
        ``rows`` (its sensors of ``group``) and the error there (docs/model.md section 10).

        Profiles that differ only in their rate Ω_K3 (a mission's segments flown on one
        profile at several rates, in one placement) are searched together
        (:func:`~gyrovib.core.phases.worst_phase_errors`): their coarse nodes and
        trial points are shared, and the search runs once, not once per rate."""
        searched = [j for j, locked in enumerate(group.locked)
                    if any(g.worst.any() for g in locked)]
        alike: dict[bytes, list[int]] = {}
        for j in searched:
            alike.setdefault(_search_key(prepared, group, j), []).append(j)
        for part, same in enumerate(alike.values()):
            j = same[0]
            linear = prepared.linear[j] if prepared.linear else None
            with part_of(part, len(alike)):  # one bar over every profile's search
                found = worst_phase_errors(
                    prepared.coefficients[rows], group.vibrations[j], group.locked[j],
                    [float(prepared.rates[i, 2]) for i in same],
                    acceleration=None if linear is None else linear.moments(),
                    g2_sensitivity=None if linear is None else prepared.g2[rows])
            yield from zip(same, found, strict=True)

    def polynomials(self, block: FloatArray, at: NDArray[np.intp], sensors: NDArray[np.intp],
                    profile: int, spec: specs.SpecResults | None) -> None:
        """Its rows of a brute-force block are its own polynomials already."""

    def numeric_done(self, parts: dict[str, FloatArray],
                     spec: specs.SpecResults | None) -> None:
        """Brute force gives its error terms as they are."""

    def bound_checks(self, rows: NDArray[np.intp], checks: CoefficientChecks,
                     own: SpecChecks | None) -> BoundVerdict:
        """Each coefficient against eq. (23)/(25), the effective VRE against its bound."""
        return CoefficientVerdict.of(rows, checks)


def _search_key(prepared: Prepared, group: Group, j: int) -> bytes:
    """What a ``phase: worst`` search of profile ``j`` depends on, but its rate: the
    vibration at the sensor, the locked groups and the linear vibration's moments."""
    v = group.vibrations[j]
    linear = prepared.linear[j] if prepared.linear else None
    parts = [v.phasors, v.sigma, v.coherence, np.asarray(v.has_random)]
    for g in group.locked[j]:
        parts += [g.orders, g.phasors, g.worst, np.asarray(len(g.orders))]
    parts.append(np.zeros(0) if linear is None else np.asarray(linear.moments(), float))
    return b"|".join(np.ascontiguousarray(p).tobytes() for p in parts)


def _take_whole(err: Any, shape: tuple[int, ...], parts: dict[str, FloatArray],
                kept: Any) -> None:
    """The arrays of ``err`` as the results: broadcast and copied only where they must be
    (a view shared with another result or with the multipliers the study keeps, a
    read-only one, a shape left to broadcasting)."""
    others = [a for a in vars(kept).values() if isinstance(a, np.ndarray)] if hasattr(
        kept, "__dict__") else [getattr(kept, f) for f in kept.__dataclass_fields__
                                if isinstance(getattr(kept, f), np.ndarray)]
    for name, tail in ERROR_PARTS.items():
        array = np.asarray(getattr(err, name))
        if (array.shape != (*shape, *tail) or not array.flags.writeable
                or any(np.may_share_memory(array, other)
                       for other in [*parts.values(), *others])):
            array = np.array(np.broadcast_to(array, (*shape, *tail)))
        parts[name] = array


class DatasheetForm:
    """A sensor given by its datasheet: the worst case over its envelope (section 11)."""

    source = "specs"
    bounds_phases = True

    def owns(self, entry: SensorEntry) -> bool:
        return entry.sensor.specs is not None

    def error(self, study: Study, prepared: Prepared, rows: NDArray[np.intp], method: str,
              omega: FloatArray | None, parts: dict[str, FloatArray],
              rms_only: bool = False) -> None:
        """The worst polynomial's terms; ``total`` the worst |Δ_V|, ``rms`` the per-term bound."""
        spec = worst_case(study, prepared, method, omega, rms_only=rms_only)
        if spec is not None:
            specs.place(parts, spec)

    def phase_search(self, prepared: Prepared, group: Group,
                     rows: NDArray[np.intp]) -> Iterator[tuple[int, WorstPhases]]:
        """None: its rows are the worst case over the envelope, not one polynomial's
        phases (the multipliers at their largest over the phases bound every one)."""
        return iter(())

    def polynomials(self, block: FloatArray, at: NDArray[np.intp], sensors: NDArray[np.intp],
                    profile: int, spec: specs.SpecResults | None) -> None:
        """Brute force averages the worst polynomial its envelope allows, per profile."""
        if spec is not None:
            block[at] = specs.numeric_rows(block[at], np.arange(at.size), profile, spec,
                                           sensors)

    def numeric_done(self, parts: dict[str, FloatArray],
                     spec: specs.SpecResults | None) -> None:
        """``total`` gets the g² part |v|·S; ``rms`` stays the per-term bound."""
        if spec is not None:
            specs.place_analysis(parts, spec, numeric=True)

    def bound_checks(self, rows: NDArray[np.intp], checks: CoefficientChecks,
                     own: SpecChecks | None) -> BoundVerdict:
        """Its nonlinearity and VRE against their spec bounds (``own``: its rows' checks)."""
        if own is None:
            raise ValueError("datasheet sensors judged without their spec checks")
        return DatasheetVerdict.of(rows, own)


#: The forms, in the order they are asked whether a sensor is theirs.
FORMS: tuple[SensorForm, ...] = (DatasheetForm(), CoefficientForm())


def form_rows(sensors: Sequence[SensorEntry]) -> list[tuple[SensorForm, NDArray[np.intp]]]:
    """Each form with the indices of its sensors (forms without sensors left out)."""
    taken = np.zeros(len(sensors), dtype=bool)
    out = []
    for form in FORMS:
        rows = np.array([i for i, e in enumerate(sensors) if not taken[i] and form.owns(e)],
                        dtype=np.intp)
        taken[rows] = True
        if rows.size:
            out.append((form, rows))
    return out


def phase_bound(study: Study, prepared: Prepared, method: str,
                peak_factor: float) -> Prepared:
    """The preparation a form that bounds the phases (:attr:`SensorForm.bounds_phases`)
    takes its error on (docs/model.md sections 10, 11): with ``phase: worst`` orders
    under ``exact``, each multiplier at its largest over the unknown phases, which bounds
    every phase's share, as ``bounds`` and ``select`` do; otherwise ``prepared`` itself."""
    worst = any(g.worst.any() for group in prepared.groups for gs in group.locked
                for g in gs)
    if method != "exact" or not worst or not any(
            form.bounds_phases for form, _ in form_rows(prepared.sensors)):
        return prepared
    return study.prepare(methods=("exact",), peak_factor=peak_factor, phase_search=True)


def phase_worst(prepared: Prepared, group: Group,
                ) -> Iterator[tuple[int, NDArray[np.intp], WorstPhases]]:
    """``phase: worst`` (docs/model.md section 10) in ``group``: per profile with such
    orders and each form that searches them, the profile, the sensors and what was found."""
    for form, rows in form_rows(prepared.sensors):
        idx = group.index[_mask(len(prepared.sensors), rows)[group.index]]
        if idx.size:
            for j, found in form.phase_search(prepared, group, idx):
                yield j, idx, found


def numeric_polynomials(prepared: Prepared, idx: NDArray[np.intp], profile: int,
                        spec: specs.SpecResults | None) -> FloatArray:
    """The polynomials brute force averages for sensors ``idx`` under one profile: each
    form writes its own rows (``spec``: the datasheet sensors' worst case)."""
    block = np.array(prepared.coefficients[idx], dtype=float)
    for form, rows in form_rows(prepared.sensors):
        at = np.flatnonzero(_mask(len(prepared.sensors), rows)[idx])
        if at.size:
            form.polynomials(block, at, idx[at], profile, spec)
    return block


def numeric_done(prepared: Prepared, parts: dict[str, FloatArray],
                 spec: specs.SpecResults | None) -> None:
    """After brute force: each form completes its rows of ``parts``."""
    for form, _ in form_rows(prepared.sensors):
        form.numeric_done(parts, spec)


def bound_verdicts(prepared: Prepared, checks: CoefficientChecks,
                   own: SpecChecks | None) -> list[BoundVerdict]:
    """The bound checks of ``select``: each form's verdict on its own rows."""
    return [form.bound_checks(rows, checks, own) for form, rows in form_rows(prepared.sensors)]


def _mask(n: int, rows: NDArray[np.intp]) -> NDArray[np.bool_]:
    out = np.zeros(n, dtype=bool)
    out[rows] = True
    return out


def sources(sensors: Sequence[SensorEntry]) -> tuple[str, ...]:
    """Each sensor's form, as results name it; empty when every sensor has coefficients."""
    named = ["coefficients"] * len(sensors)
    for form, rows in form_rows(sensors):
        for i in rows.tolist():
            named[i] = form.source
    return () if all(n == "coefficients" for n in named) else tuple(named)


def worst_case(study: Study, prepared: Prepared, method: str,
               omega: FloatArray | None = None, *,
               rms_only: bool = False) -> specs.SpecResults | None:
    """The datasheet sensors' worst case under ``method`` (kept by the study).

    Kept per method, rates and the multipliers prepared (which the study keeps
    too, so one preparation asked twice gives the same objects). ``rms_only``:
    the per-term RMS bound alone, the rest NaN (a chart of Δ_V(RMS)).
    """
    multipliers = tuple(id(g.multipliers.get(method)) for g in prepared.groups)
    return study.remember(("worst case", method, omega_key(omega), multipliers, rms_only),
                          lambda: specs.spec_results(prepared, method, omega=omega,
                                                     total=not rms_only))


def errors(study: Study, prepared: Prepared, method: str, omega: FloatArray | None = None,
           *, datasheet: Prepared | None = None,
           rms_only: bool = False) -> dict[str, FloatArray]:
    """Every sensor's error terms under ``method`` in deg/s, (sensors, profiles[, rates], ...).

    ``datasheet``: the preparation the datasheet worst case is taken on when
    it differs (``analyze`` with ``phase: worst``: each multiplier at its
    largest over the phases); default ``prepared``. ``rms_only``: a form may
    give Δ_V(RMS) alone where the rest costs much more (the datasheet form's
    whole-error programme), leaving the rest NaN.
    """
    tail = () if omega is None else (np.asarray(omega).size,)
    shape = (len(prepared.sensors), len(prepared.profiles), *tail)
    forms = form_rows(prepared.sensors)
    parts: dict[str, FloatArray] = {}
    whole = (len(forms) == 1 and forms[0][0].source == "coefficients"
             and len(prepared.groups) == 1
             and np.array_equal(prepared.groups[0].index, np.arange(shape[0])))
    if not whole:  # each form fills its own rows of zeros
        parts = {name: np.zeros((*shape, *t)) for name, t in ERROR_PARTS.items()}
    for form, rows in forms:
        form.error(study, datasheet if datasheet is not None and form.bounds_phases
                   else prepared, rows, method, omega, parts, rms_only)
    if not parts:  # no profile (no group): nothing was computed
        parts = {name: np.zeros((*shape, *t)) for name, t in ERROR_PARTS.items()}
    return parts


@dataclass(frozen=True, eq=False, repr=False)
class Saturation(Frozen):
    """The saturation rule (docs/model.md section 9), (sensors, profiles[, rates]), deg/s.

    ``reach``: |Ω_K3| + the vibration's swing at the sensor's nonlinear element;
    ``ranges``: each sensor's range (inf: none given; a datasheet's own range);
    ``saturated``: reach > range.
    """

    reach: FloatArray
    ranges: FloatArray
    saturated: NDArray[np.bool_]


def saturation(prepared: Prepared, omega: FloatArray | None = None) -> Saturation:
    """Where each sensor saturates, at the profiles' Ω_K3 or at every rate of ``omega``."""
    n_s, n_p = len(prepared.sensors), len(prepared.profiles)
    rates = prepared.rates[:, 2] if omega is None else np.asarray(omega, dtype=float)
    tail = () if omega is None else (rates.size,)
    reach = np.zeros((n_s, n_p, *tail))
    for group in prepared.groups:
        swing = group.swing if omega is None else group.swing[:, None]
        reach[group.index] = (np.abs(rates) + swing)[None]
    ranges = sensor_ranges(prepared.sensors)
    return Saturation(reach, ranges, saturated_at(reach, ranges))
