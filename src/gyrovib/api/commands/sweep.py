"""``sweep``: eq. (13) and (16) over a range of Ω_K3, exact and paper side by side."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from gyrovib import units
from gyrovib.api import specs
from gyrovib.api.convert import error_arrays, sensor_ranges, to_unit
from gyrovib.api.entries import select_entries
from gyrovib.api.other_results import SweepResult
from gyrovib.api.prepare import check_finite, float_guard, prepare
from gyrovib.catalog.loader import Catalog
from gyrovib.core.analysis import EXTRA_TERMS, METHODS, VibrationError, vibration_error
from gyrovib.core.saturation import DEFAULT_PEAK_FACTOR
from gyrovib.core.saturation import saturated as saturated_at
from gyrovib.core.transmissibility import FloatArray
from gyrovib.errors import OptionError

#: Most rates in one sweep: several tones cost about 10^4 kernel values per rate.
MAX_SWEEP_POINTS = 20_000
#: Most sensor × profile × rate cells of one sweep: each holds ~16 values per
#: method in the result (~260 MB at this many), so a long sweep stays under 400 MB.
MAX_SWEEP_CELLS = 1_000_000
#: Most datasheet-sensor × profile × rate × method worst cases of one sweep: each
#: is a linear programme polished from its neighbour's, 0.1-0.2 ms (5-10 s at this many;
#: the default 401-rate sweep of the bundled catalogue is 45,000).
MAX_SWEEP_PROGRAMMES = 50_000


def check_sweep_size(n_sensors: int, n_spec: int, n_profiles: int, n_rates: int) -> None:
    """Refuse, before any computation, a sweep whose result or whose datasheet worst
    cases would exceed :data:`MAX_SWEEP_CELLS` or :data:`MAX_SWEEP_PROGRAMMES`."""
    cells = n_sensors * n_profiles * n_rates
    if cells > MAX_SWEEP_CELLS:
        most = max(1, MAX_SWEEP_CELLS // max(1, n_sensors * n_profiles))
        raise OptionError(
            f"--rate-range: {n_rates:,} rates × {n_profiles} profiles × {n_sensors} sensors "
            f"are {cells:,} results, more than the {MAX_SWEEP_CELLS:,} one sweep holds "
            f"(~16 values each per method, to stay under 400 MB); sweep at most {most:,} "
            "rates here, or fewer profiles (--profile) or sensors (--sensor)")
    programmes = n_spec * n_profiles * n_rates * len(METHODS)
    if programmes > MAX_SWEEP_PROGRAMMES:
        most = max(1, MAX_SWEEP_PROGRAMMES // max(1, n_spec * n_profiles * len(METHODS)))
        raise OptionError(
            f"--rate-range: {n_rates:,} rates × {n_profiles} profiles × {n_spec} datasheet "
            f"sensors need {programmes:,} worst cases over their envelopes (a linear "
            f"programme each, both methods), more than the {MAX_SWEEP_PROGRAMMES:,} "
            f"(about 10 s) one sweep may take; sweep at most {most:,} rates here, or fewer "
            "profiles (--profile) or datasheet sensors (--sensor)")


def rate_range(start: float, stop: float, count: int) -> FloatArray:
    """``count`` evenly spaced rates from ``start`` to ``stop`` inclusive (deg/s)."""
    if count < 1:
        raise OptionError("a rate range needs a count of at least 1")
    if count > MAX_SWEEP_POINTS:
        raise OptionError(
            f"a rate range of {count} points is too many (at most {MAX_SWEEP_POINTS})"
        )
    if not (np.isfinite(start) and np.isfinite(stop) and np.isfinite(stop - start)):
        raise OptionError("a rate range needs finite start and stop, and a finite span")
    out: FloatArray = np.linspace(start, stop, count)
    return out


def sweep(
    catalog: Catalog,
    rates: Sequence[float] | FloatArray,
    *,
    sensors: Sequence[str] = (),
    profiles: Sequence[str] = (),
    unit: str = "deg/s",
    peak_factor: float = DEFAULT_PEAK_FACTOR,
) -> SweepResult:
    """Eq. (13) and (16) at every Ω_K3 of ``rates`` (deg/s), exact and paper.

    One vectorised evaluation per profile and sensor-response group: the
    multipliers are computed for the whole rate array at once. A value at a
    rate equals :func:`~gyrovib.api.analyze` with that ``rate``. Profiles the
    paper's formulas do not cover get NaN paper values and an entry in
    :attr:`SweepResult.paper_refused`; anything that overflows is refused.
    A spec-form sensor gives its worst case over the envelope at each rate (by
    either method's multipliers), and :attr:`SweepResult.worst_coefficients`
    the exact method's worst polynomial at each rate.
    :attr:`SweepResult.saturated` flags the rates where a sensor saturates
    (|Ω_K3| + the vibration's swing at its nonlinear element, κ =
    ``peak_factor``, above its range; docs/model.md section 9).
    """
    unit = units.canonical_unit(unit)
    omega = np.asarray(rates, dtype=float).reshape(-1)
    if omega.size == 0 or not np.all(np.isfinite(omega)):
        raise OptionError("the swept rates must be finite, and at least one")
    s_entries, p_entries = select_entries(catalog, sensors, profiles)
    check_sweep_size(len(s_entries), int(specs.spec_index(s_entries).size), len(p_entries),
                     omega.size)
    with float_guard():
        # only the paper's refusals leave empty cells; the exact method's is a
        # ModelError at the profile's place in its file, as in analyze
        prepared = prepare(catalog, sensors=sensors, profiles=profiles, omega=omega,
                           methods=METHODS, tolerate_refusals=("paper",), peak_factor=peak_factor)
        shape = (len(prepared.sensors), len(prepared.profiles), omega.size)
        tails = {"additive_terms": (5,), "multiplicative_coefficients": (3,), "additive": (),
                 "multiplicative": (), "total": (), "rms": (),
                 "extra_terms": (len(EXTRA_TERMS),)}
        # one group of every sensor in order (the usual case): its arrays are the results,
        # not copied into zeros, which would double the memory of a long sweep
        whole = (len(prepared.groups) == 1
                 and np.array_equal(prepared.groups[0].index, np.arange(shape[0])))
        results: dict[str, dict[str, FloatArray]] = {
            m: {} if whole else {name: np.zeros((*shape, *t)) for name, t in tails.items()}
            for m in METHODS}
        refused: dict[int, str] = {}
        saturated = np.zeros(shape, dtype=bool)
        ranges = sensor_ranges(prepared.sensors)
        for group in prepared.groups:
            reach = np.abs(omega)[None, :] + group.swing[:, None]  # (profiles, rates)
            saturated[group.index] = saturated_at(reach, ranges[group.index])
            refused.update(group.refused.get("paper", {}))
            for method in METHODS:
                err = vibration_error(prepared.coefficients[group.index],
                                      group.multipliers[method],
                                      g2_sensitivity=prepared.g2[group.index])
                for name, tail in tails.items():
                    if whole:
                        array = np.asarray(getattr(err, name))
                        if (array.shape != (*shape, *tail) or not array.flags.writeable
                                or any(np.may_share_memory(array, other)
                                       for other in results[method].values())):
                            array = np.array(np.broadcast_to(array, (*shape, *tail)))
                        results[method][name] = array
                    else:
                        results[method][name][group.index] = getattr(err, name)
        worst_x = None
        for method in METHODS:
            spec = specs.spec_results(prepared, method, omega=omega)
            if spec is not None:
                specs.place(results[method], spec)
                if method == "exact":
                    worst_x = specs.sweep_fields(len(prepared.sensors), spec, unit)
        exact = to_unit(VibrationError(**results["exact"]), unit, in_place=True)
        paper = to_unit(VibrationError(**results["paper"]), unit, in_place=True)
        check_finite(error_arrays(exact), prepared)
        check_finite(error_arrays(paper), prepared, exclude=sorted(refused))
    return SweepResult(
        unit=unit,
        sensors=tuple(e.sensor.id for e in prepared.sensors),
        profiles=tuple(p.profile.id for p in prepared.profiles),
        rates=omega / units.scale(unit),
        exact=exact,
        paper=paper,
        paper_refused={prepared.profiles[j].profile.id: refused[j] for j in sorted(refused)},
        **(worst_x or {}),
        saturated=saturated,
        peak_factor=peak_factor,
    )
