"""A trade study: everything ``gyrovib report`` shows, views of one Study.

One selection (:func:`gyrovib.api.select`) together with what explains it:
the error of every sensor × profile broken down by term
(:func:`gyrovib.api.analyze`, same method), the error over the rate envelope
(:func:`gyrovib.api.sweep`), each profile's spectrum in the output unit, and
the inputs that make the study reproducible (each catalogue file with its
SHA-256, the gyrovib version, the time). This module sits beside
:mod:`gyrovib.api` and uses only its public functions.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from gyrovib import api, units
from gyrovib._version import __version__
from gyrovib.api.commands.analyze import analysis_of
from gyrovib.api.commands.select import selection_of
from gyrovib.api.commands.sweep import sweep_of
from gyrovib.api.lots.yields import DEFAULT_DRAWS, DEFAULT_SEED
from gyrovib.api.study.linear import profile_linear
from gyrovib.api.study.prepare import cost_problems, float_guard
from gyrovib.api.study.study import Study
from gyrovib.catalog.loader import Catalog, ProfileEntry, bundled_paths
from gyrovib.core._types import FloatArray
from gyrovib.frozen import Frozen
from gyrovib.limits import DEFAULT_PEAK_FACTOR
from gyrovib.models import Allocation

#: Points of the default rate sweep (odd: Ω_K3 = 0 is one of them).
SWEEP_POINTS = 241
#: Most sensors drawn in the report's rate-envelope charts (the best-ranked of the selection).
SWEEP_SENSORS = 12
#: The default sweep reaches this multiple of the largest |Ω_K3| + vibration peak.
ENVELOPE_FACTOR = 1.5


@dataclass(frozen=True, eq=False, repr=False)
class InputFile(Frozen):
    """A catalogue file as read: its name as given, SHA-256 of its bytes, size."""

    name: str
    sha256: str
    size: int


@dataclass(frozen=True, eq=False, repr=False)
class Spectrum(Frozen):
    """A profile's vibration as the catalogue gives it, in the study's unit.

    ``psd``: (axis, frequencies Hz, PSD unit²/Hz) per axis given; ``tones``:
    (frequency Hz, amplitudes about x1, x2, x3); ``rms``: the random part given
    as σ per axis instead of a PSD; ``mount``: the isolation mount's ν(f);
    ``linear_rms``: the RMS per axis of the linear vibration at the sensor, in g
    (through its mount; docs/model.md section 8), or None without one.
    """

    profile: str
    name: str | None
    notes: str | None
    psd: tuple[tuple[str, tuple[float, ...], tuple[float, ...]], ...]
    tones: tuple[tuple[float, tuple[float, float, float]], ...]
    rms: tuple[float, float, float] | None
    mount: tuple[tuple[float, ...], tuple[float, ...]] | None
    linear_rms: tuple[float, float, float] | None = None
    #: Phase-locked harmonic groups (docs/model.md section 10): (f0 Hz, ((order n,
    #: amplitudes about x1, x2, x3 in the study's rate unit), ...)) per group.
    locked: tuple[tuple[float, tuple[tuple[int, tuple[float, float, float]], ...]], ...] = ()
    #: The linear vibration's PSD as the catalogue gives it, per axis (axis,
    #: frequencies Hz, PSD in ``linear_unit``²/Hz), and its tones (frequency,
    #: amplitudes about x1, x2, x3 in ``linear_unit``).
    linear_psd: tuple[tuple[str, tuple[float, ...], tuple[float, ...]], ...] = ()
    linear_tones: tuple[tuple[float, tuple[float, float, float]], ...] = ()
    linear_unit: str = "g"


@dataclass(frozen=True, eq=False, repr=False)
class TradeStudy(Frozen):
    """A selection with its explanation and its inputs (see the module docstring)."""

    selection: api.SelectionResult
    analysis: api.AnalysisResult
    sweep: api.SweepResult
    spectra: tuple[Spectrum, ...]
    files: tuple[InputFile, ...]
    sensor_names: tuple[str | None, ...]
    #: How each sensor is given: "coefficients", "output coefficients" or
    #: "datasheet" (the spec form, whose results are worst-case bounds).
    sensor_forms: tuple[str, ...]
    version: str
    created: str
    #: The unit of the vehicle's rates, tones and PSDs in :attr:`spectra` and the
    #: report (the profiles' own; the errors stay in the selection's unit).
    rate_unit: str = ""


def file_digest(name: str, text: str) -> InputFile:
    """SHA-256 of the file's bytes on disk (of its text as UTF-8 when it cannot be read)."""
    try:
        data = Path(name).read_bytes()
    except OSError:
        data = text.encode("utf-8")
    return InputFile(name=_shown_name(name), sha256=hashlib.sha256(data).hexdigest(),
                     size=len(data))


def _shown_name(name: str) -> str:
    """A bundled catalogue as ``gyrovib/catalogs/NAME (bundled)``, not the install path."""
    path = Path(name)
    for bundled in bundled_paths():
        if path.name == bundled.name and path.resolve() == bundled.resolve():
            return f"gyrovib/catalogs/{bundled.name} (bundled)"
    return name


#: A PSD per axis: (axis, frequencies, levels).
_Psd = list[tuple[str, tuple[float, ...], tuple[float, ...]]]
#: Tones: (frequency, amplitude per axis).
_Tones = tuple[tuple[float, tuple[float, float, float]], ...]


def spectrum(entry: ProfileEntry, unit: str) -> Spectrum:
    """The profile's PSD, tones and mount with rates converted to ``unit``."""
    p = entry.profile
    f = units.scale(entry.unit) / units.scale(unit)
    psd: _Psd = []
    rms = None
    if p.random is not None and p.random.psd is not None:
        psd = _psd_tables(p.random.psd, f * f)
    elif p.random is not None and p.random.rms is not None:
        rms = _triple(p.random.rms, f)
    mount = None
    if p.mount is not None:
        mount = (tuple(float(a) for a, _ in p.mount), tuple(float(b) for _, b in p.mount))
    linear = profile_linear(entry)
    linear_rms = None
    if linear is not None:
        x, y, z = (math.sqrt(max(float(v), 0.0)) for v in linear.moments()[:3])
        linear_rms = (x, y, z)
    locked = tuple(
        (float(group.fundamental),
         tuple((int(o.order), _triple(o.amplitude, f)) for o in group.orders))
        for group in (getattr(p, "harmonics", None) or ()))
    linear_psd, linear_tones = _acceleration(getattr(p, "acceleration", None))
    return Spectrum(profile=p.id, name=p.name, notes=p.notes, psd=tuple(psd),
                    tones=_tones(p.harmonic, f), rms=rms, mount=mount,
                    linear_rms=linear_rms, locked=locked, linear_psd=tuple(linear_psd),
                    linear_tones=linear_tones, linear_unit=str(entry.acceleration_unit))


def _triple(values: Sequence[float], scale: float) -> tuple[float, float, float]:
    return float(values[0]) * scale, float(values[1]) * scale, float(values[2]) * scale


def _tones(tones: Sequence[Any] | None, scale: float) -> _Tones:
    return tuple((float(t.frequency), _triple(t.amplitude, scale)) for t in (tones or ()))


def _psd_tables(tables: Any, scale: float) -> _Psd:
    """Each axis's PSD table present in ``tables``, levels times ``scale``."""
    out: _Psd = []
    for axis in ("x1", "x2", "x3"):
        table = None if tables is None else getattr(tables, axis, None)
        if table is not None:
            out.append((axis, tuple(float(a) for a, _ in table),
                        tuple(float(b) * scale for _, b in table)))
    return out


def _acceleration(block: Any) -> tuple[_Psd, _Tones]:
    """A profile's linear vibration (``acceleration:``): its PSD per axis and tones, in the
    file's acceleration unit."""
    if block is None:
        return [], ()
    random = getattr(block, "random", None)
    tables = getattr(random, "psd", None) if random is not None else None
    return _psd_tables(tables, 1.0), _tones(getattr(block, "harmonic", None), 1.0)


def sensor_form(sensor: object) -> str:
    """``"datasheet"`` for a sensor given by its specs, else which coefficients it gives."""
    if getattr(sensor, "specs", None) is not None:
        return "datasheet"
    if getattr(sensor, "output_coefficients", None) is not None:
        return "output coefficients"
    if getattr(sensor, "lot", None) is not None:
        return "lot"  # a production lot (docs/model.md section 14), analysed at its mean
    return "coefficients"


def envelope(catalog: Catalog | Study, profiles: Sequence[str] = (),
             rate: Sequence[float] | None = None) -> float:
    """Half-width of the default sweep in deg/s: ENVELOPE_FACTOR × max(|Ω_K3| + peak).

    The peak is Σ tone amplitudes + the locked groups' peaks + 3σ of x3 (the
    saturation check's, κ = 3); 1 deg/s when every profile is still and
    without vibration. Given a :class:`~gyrovib.api.study.study.Study`, its profiles
    as they reach a sensor without input-side response (computed once).
    """
    study = catalog if isinstance(catalog, Study) else Study.of(
        catalog, profiles=profiles, need=("profiles",), rate=rate)
    with float_guard():
        seen = study.seen(None, None)
    reach = [abs(float(study.rates[j, 2])) + float(seen.swing[j])
             for j in range(len(study.profiles))]
    widest = max(reach, default=0.0)
    return ENVELOPE_FACTOR * widest if widest > 0 else 1.0


def _affordable(study: Study, rates: FloatArray) -> FloatArray:
    """The sweep's rates, thinned (same range, fewer points) until a ``phase: worst``
    search at every rate costs what one search may (a profile the tool wrote from a
    recording must chart, not refuse the report): at worst the range's middle alone."""
    count = rates.size
    while count > 1 and cost_problems(study.profiles, count, 1, True):
        count = count // 2
    if count == rates.size:
        return rates
    if count <= 1:
        return np.array([0.5 * (float(rates[0]) + float(rates[-1]))])
    out: FloatArray = np.linspace(float(rates[0]), float(rates[-1]), count)
    return out


def trade_study(
    catalog: Catalog,
    *,
    budget: float,
    sensors: Sequence[str] = (),
    profiles: Sequence[str] = (),
    method: str = "exact",
    rate: Sequence[float] | None = None,
    unit: str = "deg/s",
    criterion: str = "bounds",
    require: str = "any",
    allocation: Allocation | Sequence[float] | None = None,
    sweep_rates: Sequence[float] | FloatArray | None = None,
    created: _dt.datetime | None = None,
    peak_factor: float = DEFAULT_PEAK_FACTOR,
    assume_unknown: str = "none",
    yield_target: float | None = None,
    seed: int = DEFAULT_SEED,
    draws: int = DEFAULT_DRAWS,
) -> TradeStudy:
    """Select, analyse and sweep one selection; ``budget``, ``rate``, ``sweep_rates`` in deg/s.

    Three views of one :class:`~gyrovib.api.study.study.Study`: each profile's
    vibration is computed once and shared. ``sweep_rates`` default:
    :data:`SWEEP_POINTS` rates over ±:func:`envelope`. The sweep evaluates
    ``method`` only (the one the report draws); the other method's arrays are
    NaN. ``created`` (default: now, UTC) is stamped on the study.
    ``peak_factor``: κ of the saturation check (docs/model.md section 9) of the
    selection and analysis; ``assume_unknown``: as :func:`gyrovib.api.select`;
    ``yield_target``, ``seed``, ``draws``: production lots judged by their yield
    (:func:`gyrovib.api.select`, docs/model.md section 14). Past
    :data:`SWEEP_SENSORS` sensors, only the best-ranked are swept.
    """
    unit = units.canonical_unit(unit)
    study = Study.of(catalog, sensors=sensors, profiles=profiles, rate=rate)
    selection = selection_of(study, method=method, budget=budget, unit=unit,
                             criterion=criterion, require=require, allocation=allocation,
                             peak_factor=peak_factor, assume_unknown=assume_unknown,
                             yield_target=yield_target, seed=seed, draws=draws)
    analysis = analysis_of(study, method=method, unit=unit, peak_factor=peak_factor)
    if sweep_rates is None:
        half = envelope(study)
        sweep_rates = api.rate_range(-half, half, SWEEP_POINTS)
    # a line per sensor of 3,000 is no chart, and their sweep held more than a sweep may
    charted = study
    if len(study.sensors) > SWEEP_SENSORS:
        charted = study.narrowed(sorted(selection.ranking[:SWEEP_SENSORS]))
    swept = sweep_of(charted, _affordable(charted, np.asarray(sweep_rates, dtype=float)),
                     unit=unit, methods=(method,), rms_only=True)
    when = (created or _dt.datetime.now(_dt.UTC)).astimezone(_dt.UTC)
    return TradeStudy(
        selection=selection,
        analysis=analysis,
        sweep=swept,
        spectra=tuple(spectrum(p, analysis.rate_unit or unit) for p in study.profiles),
        files=tuple(file_digest(s.name, s.text) for s in catalog.sources),
        # a sensor without a name is called by its part number, when it has one
        sensor_names=tuple(e.sensor.name or getattr(e.sensor, "part", None)
                           for e in study.sensors),
        sensor_forms=tuple(sensor_form(e.sensor) for e in study.sensors),
        version=__version__,
        created=when.strftime("%Y-%m-%d %H:%M:%S UTC"),
        rate_unit=analysis.rate_unit or unit,
    )
