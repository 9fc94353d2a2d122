"""What a recording did not record is unknown, never 0 (docs/model.md section 13, first
paragraph): which of a sensor's results depend on it.

The parts a recording can leave out are its rate axes ``x1``, ``x2``, ``x3`` (the
profile's, or the recording's X, Y, Z) and its ``acceleration``. A sensor's
rectified error Δ_V,rec (and the closed form of a profile fitted without them)
depends on

* ``x3``, the sensitive axis: always (every term of eq. (2) that rectifies holds x3);
* ``x1``, ``x2``: through m31·x3·x1 and m32·x3·x2 (the linear m1·x1, m2·x2 cancel in
  Δ_V,rec), so where m31 (m32) is not zero, or not known (a datasheet part does not
  publish it);
* ``acceleration``: through the g² term, where the sensor states one that is not 0.

A result that depends on an unknown part is unknown: NaN in the library (``null`` in
JSON, empty in CSV, '?' in tables), and a verdict on it is ``unverified``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from gyrovib.api.datasheet.specs import is_spec
from gyrovib.api.study.convert import coefficient_matrix
from gyrovib.api.study.linear import g2_matrix
from gyrovib.core.analysis import EXTRA_TERMS

#: The parts of a recording, in order: its rate axes (as the profile's x1, x2, x3) and
#: its accelerations.
PARTS = ("x1", "x2", "x3", "acceleration")
#: Column of m31 and m32 in :func:`gyrovib.api.study.convert.coefficient_matrix`.
_M3 = {"x1": 9, "x2": 10}


def not_recorded(rate_axes: Sequence[bool], accel: bool | None = None) -> tuple[str, ...]:
    """The parts a recording lacks: the rate axes not recorded, and ``acceleration``
    when ``accel`` is False (None: not asked)."""
    out = [name for name, on in zip(PARTS[:3], rate_axes, strict=True) if not on]
    if accel is False:
        out.append("acceleration")
    return tuple(out)


def depends_on(entries: Sequence[Any], missing: Sequence[str], *,
               spec_cross: bool = True) -> list[tuple[str, ...]]:
    """Per sensor entry, the parts of ``missing`` its rectified error depends on (see the
    module docstring); empty where it does not depend on any. ``spec_cross`` False: a
    datasheet part's m31, m32 are taken as 0, as Δ_V,rec's worst case over its envelope
    takes them (docs/model.md section 13), so x1, x2 do not enter it."""
    if not missing or not entries:
        return [() for _ in entries]
    coeffs = coefficient_matrix(entries)
    g2 = g2_matrix(entries)
    out = []
    for i, e in enumerate(entries):
        spec = is_spec(e)
        needs = {"x3": True, "acceleration": _g2_matters(e, g2[i], spec)}
        for name, column in _M3.items():
            needs[name] = (spec and spec_cross) or bool(coeffs[i, column] != 0)
        out.append(tuple(name for name in missing if needs[name]))
    return out


def _g2_matters(entry: Any, g2: Any, spec: bool) -> bool:
    """Whether a sensor needs the accelerations: it states a g² term that is not 0 (a G,
    or a datasheet VRE). One that gives no g² figure at all is reported as such where
    the profile has linear vibration (``vre`` unknown), as for any profile."""
    if spec:
        vre = entry.sensor.specs.vre
        return vre is not None and vre != 0
    return bool(np.any(np.asarray(g2) != 0))


def any_missing(names: Sequence[str]) -> bool:
    """Whether ``names`` (a result's unknowns) hold a part a recording did not record: the
    verdict is then unverified whatever the computed one (no figure to assume 0)."""
    return any(n in PARTS for n in names)


def words(parts: Sequence[str]) -> str:
    """``axis x3 (sensitive) not recorded``-style words for ``parts``."""
    named = {"x1": "axis x1", "x2": "axis x2", "x3": "axis x3 (the sensitive axis)",
             "acceleration": "the accelerations"}
    return ", ".join(named[p] for p in parts) + " not recorded"


# ----------------------------------------------------------------- select's cells


def unrecorded_cells(prepared: Any, passed: Any,
                     unverified: Any,
                     unknown: dict[tuple[int, int], tuple[str, ...]]) -> None:
    """A profile fitted from a recording that lacks an axis (``not_recorded``): each sensor
    whose error depends on it is unverified there, whatever its computed verdict (the
    error is unknown, docs/model.md section 13; not a figure to assume 0)."""
    for j, p in enumerate(prepared.profiles):
        missing = tuple(p.profile.not_recorded)
        for i, parts in enumerate(depends_on(prepared.sensors, missing)):
            if parts:
                passed[i, j], unverified[i, j] = False, True
                unknown[(i, j)] = (*parts, *unknown.get((i, j), ()))


def unknown_errors(unknown: dict[tuple[int, int], tuple[str, ...]],
                   *arrays: Any) -> tuple[Any, ...]:
    """Each (sensors, profiles) array (Δ_V(RMS), Δ_V, the margin) with NaN in the cells
    that depend on a part a recording did not record: unknown (null in JSON, empty in
    CSV, '?' in tables), never the number computed with 0 there."""
    cells = [key for key, names in unknown.items() if any_missing(names)]
    if not cells:
        return arrays
    out = tuple(np.array(a, dtype=float, copy=True) for a in arrays)
    for i, j in cells:
        for a in out:
            a[i, j] = np.nan
    return out


def unknown_cells(prepared: Any, error: Any,
                  warnings: dict[tuple[int, int], tuple[str, ...]]) -> None:
    """``analyze`` on a profile fitted from a recording that lacks a part: each error of a
    sensor that depends on it is NaN in ``error`` (every array, at its sensor × profile),
    with a warning naming the part (docs/model.md section 13: unknown, never 0)."""
    arrays = [error.additive_terms, error.multiplicative_coefficients, error.additive,
              error.multiplicative, error.total, error.rms, error.extra_terms]
    for j, p in enumerate(prepared.profiles):
        for i, parts in enumerate(depends_on(prepared.sensors, tuple(p.profile.not_recorded))):
            if parts:
                for a in arrays:
                    a[i, j] = np.nan
                warnings[(i, j)] = (f"unknown: the profile was fitted from a recording "
                                    f"without {', '.join(parts)}, and this sensor's error "
                                    "depends on it (docs/model.md section 13)",
                                    *warnings.get((i, j), ()))


def unknown_g2(error: Any, rms_bound: Any, cells: Sequence[tuple[int, int]]) -> None:
    """``analyze`` and ``sweep`` where a sensor's g² figure is unknown (an unpublished VRE, a g²
    sensitivity not given) under linear vibration (``cells``): the g² term Δ0(6) and what
    sums it, Δ_VA, Δ_V and Δ_V(RMS) (a datasheet part's RMS bound too), are NaN in
    ``error``: unknown, never the numbers computed with the term left out
    (docs/model.md sections 8 and 11)."""
    g2 = EXTRA_TERMS.index("g2")
    for i, j in cells:  # a sweep's arrays carry a rate axis after the profile's: all NaN
        error.extra_terms[i, j, ..., g2] = np.nan
        for a in (error.additive, error.total, error.rms):
            a[i, j] = np.nan
        if rms_bound is not None:
            rms_bound[i, j] = np.nan


def _bound_needs(name: str, gone: set[str]) -> bool:
    """Whether the bound on ``name`` (a coefficient of :data:`BOUNDED`, or ``vre``) depends
    on a part in ``gone``: every coefficient's on x3, m31's also on x1, m32's also on x2,
    the VRE's on the accelerations."""
    if name == "vre":
        return "acceleration" in gone
    return ("x3" in gone or (name == "m31" and "x1" in gone)
            or (name == "m32" and "x2" in gone))


def unrecorded_limits(profiles: Sequence[Any], limits: Any, vre_bound: Any,
                      names: Sequence[str]) -> tuple[Any, Any]:
    """Each sensor's own bounds (sensors, profiles, ``names``) and VRE bounds (sensors,
    profiles) with NaN under a profile fitted from a recording that lacks what the bound
    depends on (as :func:`unknown_bounds`): unknown, not the bound computed with 0 there,
    which would read as looser than the truth or as 'nothing to bound'."""
    out, vre = limits, vre_bound
    for j, p in enumerate(profiles):
        gone = set(p.profile.not_recorded)
        if not gone:
            continue
        if out is limits:
            out, vre = np.array(limits, dtype=float), np.array(vre_bound, dtype=float)
        for b, name in enumerate(names):
            if _bound_needs(name, gone):
                out[:, j, b] = np.nan
        if _bound_needs("vre", gone):
            vre[:, j] = np.nan
    return out, vre


def unknown_bounds(profiles: Sequence[Any], bounds: Any) -> Any:
    """``bounds`` (per profile) with NaN where a profile fitted from a recording lacks what
    a bound depends on: every bound without x3, m31's without x1, m32's without x2, the
    VRE's without the accelerations (unknown, not 'unbounded')."""
    import dataclasses

    update: dict[str, Any] = {}
    for j, p in enumerate(profiles):
        gone = set(p.profile.not_recorded)
        if not gone:
            continue
        names = [f.name for f in dataclasses.fields(bounds)
                 if getattr(bounds, f.name) is not None and _bound_needs(f.name, gone)]
        for name in dict.fromkeys(names):
            array = update.setdefault(name, np.array(getattr(bounds, name), dtype=float))
            array[j] = np.nan
    return dataclasses.replace(bounds, **update) if update else bounds
