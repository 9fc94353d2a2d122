"""The notebook API: ``gyrovib.load``, ``analyze``, ``bounds``, ``select``, ``sweep``.

Thin wrappers over :mod:`gyrovib.api` for interactive use. They differ from
the library functions only in what they accept: a catalogue may be given as
nothing (the bundled catalogues), a path, a list of paths, a loaded
:class:`~gyrovib.catalog.loader.Catalog`, or catalogues built in Python
(:class:`gyrovib.models.Catalogue`, one or a list, e.g.
``Catalogue.model_validate({"gyrovib": 1, "sensors": [...]})``); rates and budgets are numbers in
``unit`` (the output unit) or strings carrying their own unit (``"10deg/h"``),
as on the command line. Every result has ``to_frame()`` (needs
``gyrovib[pandas]``).

``import gyrovib`` does not import this module: the package's ``__getattr__``
does on first use of one of these names.

Every argument is checked here, at the face, before any work: a wrong type
raises :class:`~gyrovib.errors.ArgumentTypeError` (a :class:`TypeError`), a
wrong value :class:`~gyrovib.errors.ArgumentError` (a :class:`ValueError`);
both are :class:`~gyrovib.errors.GyrovibError` and name the argument. The
command line's caps hold here too: samples (:data:`gyrovib.limits.MAX_SAMPLES`),
rates and sweep points (``gyrovib.api.MAX_SWEEP_POINTS``).
"""

from __future__ import annotations

import math
import operator
import os
import sys
from collections.abc import Iterable, Sequence
from numbers import Real
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from gyrovib import api, units
from gyrovib.api.commands.mission import angle_in_rad
from gyrovib.catalog.loader import Catalog, merge, model_source
from gyrovib.core.envelope import OF
from gyrovib.core.envelope_basis import FITS, MEASURES
from gyrovib.core.placement import parse
from gyrovib.errors import ArgumentError, ArgumentTypeError, OptionError
from gyrovib.limits import DEFAULT_PEAK_FACTOR, MAX_SAMPLES, MIN_SAMPLES
from gyrovib.models import Catalogue

if TYPE_CHECKING:
    from gyrovib.api import AnalysisResult, BoundsResult, SelectionResult, SweepResult

__all__ = ["analyze", "bounds", "load", "mission", "select", "sweep"]

#: The methods of bounds and select (analyze adds 'numeric').
METHODS = ("exact", "paper")

CatalogLike = Any  # None | str | Path | Sequence[str | Path] | Catalog | models.Catalogue(s)



# ----------------------------------------------------------------- argument checks


def _wrong_type(name: str, value: object, expected: str) -> NoReturn:
    raise ArgumentTypeError(f"argument {name!r}: expected {expected}, "
                            f"got {type(value).__name__} {_show(value)}")


def _show(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _text(name: str, value: object, choices: Sequence[str] = ()) -> str:
    if not isinstance(value, str):
        _wrong_type(name, value, "text")
    if choices and value not in choices:
        raise ArgumentError(f"argument {name!r}: {value!r} is not one of "
                            f"{', '.join(choices)}")
    return value


def _number(name: str, value: object, *, positive: bool = False,
            nonnegative: bool = False) -> float:
    """A real number (not a bool), finite, and > 0 or ≥ 0 when asked."""
    if isinstance(value, bool) or not isinstance(value, Real):
        _wrong_type(name, value, "a number")
    try:
        number = float(value)
    except (OverflowError, ValueError):
        number = math.inf
    if not math.isfinite(number):
        raise ArgumentError(f"argument {name!r}: {_show(value)} is not a finite number")
    if positive and not number > 0:
        raise ArgumentError(f"argument {name!r}: {number!r} must be positive")
    if nonnegative and number < 0:
        raise ArgumentError(f"argument {name!r}: {number!r} must not be negative")
    return number


def _integer(name: str, value: object, low: int, high: int | None = None) -> int:
    """A whole number (an int or numpy integer, not a bool or float) in [low, high]."""
    if isinstance(value, bool):
        _wrong_type(name, value, "a whole number")
    try:
        whole = operator.index(value)  # type: ignore[arg-type]
    except TypeError:
        _wrong_type(name, value, "a whole number")
    if whole < low or (high is not None and whole > high):
        # a huge int is not printed (nor turned into a float, which would overflow)
        magnitude = f"{'-' if whole < 0 else ''}10^{int(whole.bit_length() * math.log10(2))}"
        shown = f"{whole:,}" if abs(whole) < 10**15 else f"about {magnitude}"
        span = f"from {low:,} to {high:,}" if high is not None else f"at least {low:,}"
        raise ArgumentError(f"argument {name!r}: {shown} is out of range; give {span}")
    return whole


def _unit(name: str, value: object) -> str:
    try:
        return units.canonical_unit(_text(name, value))
    except OptionError as exc:
        if isinstance(exc, ArgumentError | ArgumentTypeError):
            raise
        raise ArgumentError(f"argument {name!r}: {exc.problems[0].message}") from None


def _quantity(name: str, value: object, unit: str, positive: bool = False) -> float:
    """A rate in deg/s: a number in ``unit`` or a string with its own unit; finite
    (:func:`gyrovib.units.quantity`, the command line's reading too)."""
    if not isinstance(value, str):
        value = _number(name, value, positive=positive)
    try:
        return units.quantity(value, unit, positive=positive)
    except units.NotPositive:
        raise ArgumentError(f"argument {name!r}: {value!r} must be positive") from None
    except OptionError as exc:
        if isinstance(value, str):
            raise ArgumentError(f"argument {name!r}: {exc.problems[0].message}") from None
        raise ArgumentError(f"argument {name!r}: {_show(value)} {unit} overflows") from None


def _sequence(name: str, value: object, what: str) -> list[Any]:
    """The items of a list, tuple, array…: not of a string, bytes or a mapping."""
    if isinstance(value, str | bytes | bytearray | dict) or not isinstance(value, Iterable):
        _wrong_type(name, value, what)
    return list(value)


def _rates(name: str, value: object, unit: str, counts: tuple[int, ...] = (1, 3)
           ) -> list[float] | None:
    if value is None:
        return None
    if isinstance(value, str | Real) and not isinstance(value, bool):
        items: list[Any] = [value]
    else:
        items = _sequence(name, value, "a rate, or a sequence of rates")
    if len(items) not in counts:
        raise ArgumentError(f"argument {name!r}: give one rate (Ω_K3) or three, "
                            f"not {len(items)}")
    return [_quantity(name, v, unit) for v in items]


def _ids(name: str, value: object) -> tuple[str, ...]:
    if isinstance(value, str):
        return (value,)
    items = _sequence(name, value, "an id or a sequence of ids")
    for item in items:
        if not isinstance(item, str):
            _wrong_type(name, item, "ids as text")
    return tuple(items)


def _paths(values: Iterable[object], name: str = "paths") -> list[str | Path]:
    """Paths as str or os.PathLike, or sequences of them (one level)."""
    flat: list[str | Path] = []
    for item in values:
        if isinstance(item, str | os.PathLike):
            flat.append(_path(name, item))
            continue
        for inner in _sequence(name, item, "a path or a sequence of paths"):
            if not isinstance(inner, str | os.PathLike):
                _wrong_type(name, inner, "a path (str or pathlib.Path)")
            flat.append(_path(name, inner))
    return flat


def _path(name: str, value: str | os.PathLike[Any]) -> str | Path:
    path = os.fspath(value)
    if not isinstance(path, str):  # os.PathLike of bytes
        _wrong_type(name, value, "a path as text (str or pathlib.Path)")
    if not path or "\0" in path:
        raise ArgumentError(f"argument {name!r}: {path!r} is not a file name")
    return value if isinstance(value, Path) else path


def _allocation(value: object) -> list[float] | None:
    if value is None:
        return None
    items = _sequence("allocation", value, "a sequence of numbers")
    numbers = [_number("allocation", v, positive=True) for v in items]
    if len(numbers) not in (1, 9, 10):
        raise ArgumentError("argument 'allocation': give r alone, 9 numbers r, w1..w5, "
                            f"v1..v3 or 10 numbers r, w1..w6, v1..v3 (got {len(numbers)})")
    return numbers


def _spec_weights(value: object) -> tuple[float, float]:
    items = _sequence("spec_weights", value, "two numbers (NL, VRE)")
    if len(items) != 2:
        raise ArgumentError(f"argument 'spec_weights': give two numbers (NL, VRE), "
                            f"not {len(items)}")
    return (_number("spec_weights", items[0], positive=True),
            _number("spec_weights", items[1], positive=True))


def load(*paths: str | Path | Sequence[str | Path], bundled: str | None = None) -> Catalog:
    """Load and merge catalogue files.

    Parameters
    ----------
    *paths : str or pathlib.Path, or sequences of them
        Catalogue files (YAML); several are merged, an id used twice is an
        error. None at all: the catalogues bundled with gyrovib.
    bundled : {'sensors', 'profiles', 'all'}, optional
        Add these bundled catalogues to ``paths`` (as ``--bundled``): e.g.
        ``gyrovib.load("my-profiles.yaml", bundled="sensors")``.

    Returns
    -------
    Catalog
        The merged sensors, profiles and allocation, with where each came from.

    Raises
    ------
    gyrovib.errors.CatalogError
        A file cannot be read or is not valid; the message names file, line
        and column.
    gyrovib.errors.ArgumentTypeError
        A path is not a str or os.PathLike (bytes, a number, a list in a list).

    Examples
    --------
    >>> import gyrovib
    >>> catalog = gyrovib.load()
    >>> [e.sensor.id for e in catalog.sensors][:2]
    ['adxrs645', 'adis16460']
    """
    if bundled is not None:
        bundled = _text("bundled", bundled, ("sensors", "profiles", "all"))
    return api.load(_paths(paths), bundled=bundled)


def _catalog(catalog: CatalogLike) -> Catalog:
    if isinstance(catalog, Catalog):
        return catalog
    if catalog is None:
        return load()
    models = _models(catalog)
    if models is not None:
        return merge([model_source(m, f"<gyrovib.models.Catalogue #{i + 1}>" if len(models) > 1
                                   else "<gyrovib.models.Catalogue>")
                      for i, m in enumerate(models)])
    return api.load(_paths([catalog], "catalog"))


def _models(catalog: Any) -> list[Any] | None:
    """``catalog`` as a list of :class:`gyrovib.models.Catalogue`, if it is one or a list
    of them (pydantic is imported only when the value may be one)."""
    if "gyrovib.models" not in sys.modules:  # no model was ever built
        return None
    if isinstance(catalog, Catalogue):
        return [catalog]
    if isinstance(catalog, (list, tuple)) and catalog \
            and all(isinstance(c, Catalogue) for c in catalog):
        return list(catalog)
    return None


def _budget_unit(unit: object, budget: object) -> str:
    """``unit`` as given, else the unit a budget string carries, else deg/s (as ``--unit``)."""
    if unit is not None:
        return _unit("unit", unit)
    return (units.quantity_unit(budget) if isinstance(budget, str) else None) or "deg/s"


def analyze(catalog: CatalogLike = None, *, sensors: str | Sequence[str] = (),
            profiles: str | Sequence[str] = (), method: str = "exact",
            rate: float | str | Sequence[float | str] | None = None, unit: str = "deg/s",
            samples: int | None = None, seed: int = 0,
            peak_factor: float = DEFAULT_PEAK_FACTOR) -> AnalysisResult:
    """The vibration error of every sensor under every profile, eq. (13)-(16).

    Parameters
    ----------
    catalog : Catalog, path, list of paths, gyrovib.models.Catalogue(s) or None
        What to analyse; None: the bundled catalogues.
    sensors, profiles : str or sequence of str
        Only these ids (all when empty).
    method : {'exact', 'paper', 'numeric'}
        Exact moments, the paper's printed formulas, or brute force (eq. 2
        averaged over sampled vibration).
    rate : number, str or sequence, optional
        Override Ω_K: one value for Ω_K3 or three; numbers in ``unit``.
    unit : str
        Unit of every output rate: deg/s, deg/h, rad/s or rpm.
    samples, seed : int
        ``method='numeric'`` only: evaluations per sensor × profile, seed.
    peak_factor : float
        κ of the saturation check (docs/model.md section 9), default 3.

    Returns
    -------
    gyrovib.api.AnalysisResult
        Arrays (sensors, profiles[, term]); ``to_frame()`` gives one row per
        sensor × profile with the JSON keys as columns.

    Examples
    --------
    >>> import gyrovib
    >>> r = gyrovib.analyze(sensors="adxrs645", profiles="flat-random-hover", unit="deg/h")
    >>> r.to_frame()[["sensor", "rms"]]  # doctest: +SKIP
    """
    unit = _unit("unit", unit)
    extra: dict[str, Any] = {"seed": _integer("seed", seed, 0),
                             "peak_factor": _number("peak_factor", peak_factor,
                                                    nonnegative=True)}
    if samples is not None:
        extra["samples"] = _integer("samples", samples, MIN_SAMPLES, MAX_SAMPLES)
    arguments: dict[str, Any] = {
        "sensors": _ids("sensors", sensors), "profiles": _ids("profiles", profiles),
        "method": _text("method", method, api.ANALYZE_METHODS),
        "rate": _rates("rate", rate, unit)}
    return api.analyze(_catalog(catalog), unit=unit, **arguments, **extra)


def bounds(catalog: CatalogLike = None, *, budget: float | str,
           profiles: str | Sequence[str] = (), method: str = "exact",
           rate: float | str | Sequence[float | str] | None = None, unit: str | None = None,
           allocation: Sequence[float] | None = None, range_: float | str | None = None,
           nl_fit: str = "least-squares", nl_measure: str = "max", nl_of: str = "range",
           spec_weights: tuple[float, float] = (1.0, 1.0)) -> BoundsResult:
    """Allowable coefficients per profile for a budget, eq. (23) and (25).

    Parameters
    ----------
    catalog : Catalog, path, list of paths, gyrovib.models.Catalogue(s) or None
        Profiles to bound; None: the bundled catalogues.
    budget : float or str
        Δ*_V: a number in ``unit`` or a string with a unit (``"10deg/h"``).
    profiles : str or sequence of str
        Only these profile ids.
    method : {'exact', 'paper'}
        Derived shares, or the paper's printed constants.
    rate : number, str or sequence, optional
        Override Ω_K as in :func:`analyze`.
    unit : str, optional
        Output unit; default the unit a budget string carries, else deg/s.
    allocation : sequence of float, optional
        r alone, or r, w1..w5, v1..v3, or r, w1..w6, v1..v3 with w6 the weight of
        the g² term (eq. 18, 21, 24; docs/model.md section 8).
    range_ : number or str, optional
        R of a datasheet part (in ``unit``, or with a unit): adds ``spec_bounds``,
        the allowable nonlinearity in %FS (read as ``nl_fit``, ``nl_measure``,
        of R or of the span 2R as ``nl_of``) and VRE (docs/model.md section 11).
    spec_weights : (float, float)
        Split of Δ* between the nonlinearity envelope and the VRE term.

    Returns
    -------
    gyrovib.api.BoundsResult
        ``to_frame()`` gives one row per profile; an unconstrained bound is inf.
    """
    unit = _budget_unit(unit, budget)
    arguments: dict[str, Any] = {
        "profiles": _ids("profiles", profiles), "method": _text("method", method, METHODS),
        "rate": _rates("rate", rate, unit), "budget": _quantity("budget", budget, unit, True),
        "allocation": _allocation(allocation),
        "range_": None if range_ is None else _quantity("range_", range_, unit, True),
        "nl_fit": _text("nl_fit", nl_fit, FITS),
        "nl_measure": _text("nl_measure", nl_measure, MEASURES),
        "nl_of": _text("nl_of", nl_of, OF), "spec_weights": _spec_weights(spec_weights)}
    return api.bounds(_catalog(catalog), unit=unit, **arguments)


def select(catalog: CatalogLike = None, *, budget: float | str,
           sensors: str | Sequence[str] = (), profiles: str | Sequence[str] = (),
           method: str = "exact", rate: float | str | Sequence[float | str] | None = None,
           unit: str | None = None, criterion: str = "bounds", require: str = "any",
           allocation: Sequence[float] | None = None,
           spec_weights: tuple[float, float] = (1.0, 1.0),
           peak_factor: float = DEFAULT_PEAK_FACTOR, assume_unknown: str = "none",
           yield_target: float | None = None, seed: int = 0,
           draws: int = 100_000) -> SelectionResult:
    """Which sensors meet the budget: bound checks and eq. (17), ranked by margin.

    Parameters
    ----------
    catalog : Catalog, path, list of paths, gyrovib.models.Catalogue(s) or None
        Sensors and profiles; None: the bundled catalogues.
    budget : float or str
        Δ*_V: a number in ``unit`` or a string with a unit (``"10deg/h"``).
    sensors, profiles : str or sequence of str
        Only these ids.
    method : {'exact', 'paper'}
        As in :func:`bounds`.
    rate : number, str or sequence, optional
        Override Ω_K as in :func:`analyze`.
    unit : str, optional
        Output unit; default the unit a budget string carries, else deg/s.
    criterion : {'bounds', 'rms', 'worst', 'both'}
        What a pass means (bounds: sufficient, not necessary; rms: the direct
        test; ``worst``: |Δ_V| ≤ Δ*, for a datasheet sensor over its envelope).
        A saturating sensor fails whatever the criterion.
    require : {'any', 'all'}
        Decides ``requirement_met``.
    allocation : sequence of float, optional
        As in :func:`bounds`.
    spec_weights : (float, float)
        As in :func:`bounds`, for datasheet sensors under ``criterion='bounds'``.
    peak_factor : float
        κ of the saturation check (docs/model.md section 9), default 3.
    assume_unknown : {'none', 'zero'}
        A figure a datasheet does not publish (the VRE, m31, m32) is unknown:
        where it can decide a part's verdict the part is ``unverified``
        (``status``), not passing, with ``questions`` for its vendor.
        ``'zero'`` takes such figures as 0 instead.
    yield_target : float, optional
        Y, 0 < Y < 1: a production lot (``lot:``) passes a profile when the
        probability that a part drawn from it passes is at least Y (docs/model.md
        section 14; ``select --yield``); ``seed`` and ``draws`` of its Monte Carlo.

    Returns
    -------
    gyrovib.api.SelectionResult
        ``ranking`` orders sensors best first; ``to_frame()`` gives one row per
        sensor × profile.

    Examples
    --------
    >>> import gyrovib
    >>> s = gyrovib.select(budget="10deg/h")
    >>> [s.sensors[i] for i in s.ranking][:1]  # doctest: +SKIP
    """
    unit = _budget_unit(unit, budget)
    arguments: dict[str, Any] = {
        "sensors": _ids("sensors", sensors), "profiles": _ids("profiles", profiles),
        "method": _text("method", method, METHODS), "rate": _rates("rate", rate, unit),
        "budget": _quantity("budget", budget, unit, True),
        "criterion": _text("criterion", criterion, api.CRITERIA),
        "require": _text("require", require, api.REQUIREMENTS),
        "allocation": _allocation(allocation), "spec_weights": _spec_weights(spec_weights),
        "peak_factor": _number("peak_factor", peak_factor, nonnegative=True),
        "assume_unknown": _text("assume_unknown", assume_unknown, ("none", "zero")),
        "yield_target": None if yield_target is None else _number("yield_target", yield_target),
        "seed": _integer("seed", seed, 0), "draws": _integer("draws", draws, 1)}
    return api.select(_catalog(catalog), unit=unit, **arguments)


def sweep(catalog: CatalogLike = None, rates: Sequence[float | str] | Any = (-200, 200),
          *, points: int = 401, sensors: str | Sequence[str] = (),
          profiles: str | Sequence[str] = (), unit: str = "deg/s") -> SweepResult:
    """Δ_V and Δ_V(RMS) over a range of Ω_K3, exact and paper.

    Parameters
    ----------
    catalog : Catalog, path, list of paths, gyrovib.models.Catalogue(s) or None
        Sensors and profiles; None: the bundled catalogues.
    rates : (start, stop) or array_like
        Two values: ``points`` evenly spaced rates from start to stop
        inclusive; more (or fewer): exactly these rates. Numbers in ``unit``.
    points : int
        Number of rates when ``rates`` is (start, stop).
    sensors, profiles : str or sequence of str
        Only these ids.
    unit : str
        Unit of the rates given and of the output.

    Returns
    -------
    gyrovib.api.SweepResult
        ``to_frame()`` gives one row per sensor × profile × rate.
    """
    unit = _unit("unit", unit)
    items = _sequence("rates", rates, "(start, stop) or a sequence of rates")
    if not 1 <= len(items) <= api.MAX_SWEEP_POINTS:
        raise ArgumentError(f"argument 'rates': give (start, stop) or from 1 to "
                            f"{api.MAX_SWEEP_POINTS:,} rates, not {len(items):,}")
    values = [_quantity("rates", v, unit) for v in items]
    if len(values) == 2:
        count = _integer("points", points, 1, api.MAX_SWEEP_POINTS)
        if not math.isfinite(values[1] - values[0]):
            raise ArgumentError("argument 'rates': the span from start to stop overflows")
        omega: Any = api.rate_range(values[0], values[1], count)
    else:
        omega = values
    return api.sweep(_catalog(catalog), omega, sensors=_ids("sensors", sensors),
                     profiles=_ids("profiles", profiles), unit=unit)


def mission(catalog: CatalogLike = None, *, missions: str | Sequence[str] = (),
            sensors: str | Sequence[str] = (), budget: float | str | None = None,
            angle_budget: str | None = None, unit: str | None = None,
            require: str = "any", placement: str | None = None,
            peak_factor: float = DEFAULT_PEAK_FACTOR, assume_unknown: str = "none",
            coverage: float = 1.0) -> Any:
    """Every sensor over every mission (docs/model.md section 12): mean error, angle θ_V,
    mean RMS, worst segment, and the whole angle budget (section 15).

    Parameters
    ----------
    catalog : Catalog, path, list of paths, gyrovib.models.Catalogue(s) or None
        Sensors, profiles and missions; None: the bundled catalogues.
    missions, sensors : str or sequence of str
        Only these ids.
    budget : float or str, optional
        Δ* on the mean RMS Δ̄_RMS: a number in ``unit`` or with a unit.
    angle_budget : str, optional
        θ* on each row's budget total |θ_V| + k·RSS(noise) with an angle unit:
        ``"0.5deg"``, ``"2 mrad"``.
    unit : str, optional
        Output rate unit; default the unit a budget string carries, else deg/s.
    require : {'any', 'all'}
        Decides ``requirement_met``.
    placement : str, optional
        ``"triad"`` or ``"x1=+Y,x2=+Z,x3=+X"``: replaces the missions' own.
    peak_factor : float
        κ of the saturation check (docs/model.md section 9), default 3.
    assume_unknown : {'none', 'zero'}
        'none': a datasheet part that passes on its published figures while an
        unpublished one (VRE, m31, m32, a noise figure) can decide it is
        'unverified' (row ``status``); 'zero' takes them as 0.
    coverage : float
        k of the noise terms in the budget's total (default 1).

    Returns
    -------
    gyrovib.api.MissionResult
        ``to_frame()`` gives one row per sensor × mission × axis.
    """
    unit = _budget_unit(unit, budget)
    theta = None
    if angle_budget is not None:
        try:
            theta = angle_in_rad(_text("angle_budget", angle_budget))
        except ValueError as exc:
            raise ArgumentError(f"argument 'angle_budget': {exc}") from None
    where = None
    if placement is not None:
        try:
            where = parse(_text("placement", placement))
        except ValueError as exc:
            raise ArgumentError(f"argument 'placement': {exc}") from None
    return api.mission(
        _catalog(catalog), missions=_ids("missions", missions), sensors=_ids("sensors", sensors),
        budget=None if budget is None else _quantity("budget", budget, unit, True),
        angle_budget=theta, unit=unit, require=_text("require", require, ("any", "all")),
        placement=where, peak_factor=_number("peak_factor", peak_factor, nonnegative=True),
        assume_unknown=_text("assume_unknown", assume_unknown, ("none", "zero")),
        coverage=_number("coverage", coverage, nonnegative=True))
