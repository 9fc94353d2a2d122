"""The notebook API: ``gyrovib.load``, ``analyze``, ``bounds``, ``select``, ``sweep``.

Thin wrappers over :mod:`gyrovib.api` for interactive use. They differ from
the library functions only in what they accept: a catalogue may be given as
nothing (the bundled catalogues), a path, a list of paths or a loaded
:class:`~gyrovib.catalog.loader.Catalog`; rates and budgets are numbers in
``unit`` (the output unit) or strings carrying their own unit (``"10deg/h"``),
as on the command line. Every result has ``to_frame()`` (needs
``gyrovib[pandas]``).

``import gyrovib`` does not import this module: the package's ``__getattr__``
does on first use of one of these names.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from gyrovib import units

if TYPE_CHECKING:
    from gyrovib.api import AnalysisResult, BoundsResult, SelectionResult, SweepResult
    from gyrovib.catalog.loader import Catalog

__all__ = ["analyze", "bounds", "load", "select", "sweep"]

CatalogLike = Any  # None | str | Path | Sequence[str | Path] | Catalog


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

    Examples
    --------
    >>> import gyrovib
    >>> catalog = gyrovib.load()
    >>> [e.sensor.id for e in catalog.sensors][:2]
    ['adxrs645', 'adis16460']
    """
    from gyrovib import api

    flat: list[str | Path] = []
    for item in paths:
        if isinstance(item, str | Path):
            flat.append(item)
        else:
            flat.extend(item)
    return api.load(flat, bundled=bundled)


def _catalog(catalog: CatalogLike) -> Catalog:
    from gyrovib.catalog.loader import Catalog

    if isinstance(catalog, Catalog):
        return catalog
    if catalog is None:
        return load()
    return load(catalog)


def _rate(value: float | str, unit: str) -> float:
    """A rate in deg/s from a number in ``unit`` or a string with its own unit."""
    if isinstance(value, str):
        return units.parse_rate(value, unit)
    return float(value) * units.scale(unit)


def _rates(value: float | str | Sequence[float | str] | None, unit: str) -> list[float] | None:
    if value is None:
        return None
    if isinstance(value, str | int | float):
        return [_rate(value, unit)]
    return [_rate(v, unit) for v in value]


def _budget_unit(unit: str | None, budget: float | str) -> str:
    """``unit`` as given, else the unit a budget string carries, else deg/s (as ``--unit``)."""
    if unit is not None:
        return unit
    return (units.quantity_unit(budget) if isinstance(budget, str) else None) or "deg/s"


def _ids(value: str | Sequence[str]) -> tuple[str, ...]:
    return (value,) if isinstance(value, str) else tuple(value)


def analyze(catalog: CatalogLike = None, *, sensors: str | Sequence[str] = (),
            profiles: str | Sequence[str] = (), method: str = "exact",
            rate: float | str | Sequence[float | str] | None = None, unit: str = "deg/s",
            samples: int | None = None, seed: int = 0,
            peak_factor: float = 3.0) -> AnalysisResult:
    """The vibration error of every sensor under every profile, eq. (13)-(16).

    Parameters
    ----------
    catalog : Catalog, path, list of paths or None
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
    from gyrovib import api

    extra: dict[str, Any] = {"seed": seed, "peak_factor": peak_factor}
    if samples is not None:
        extra["samples"] = samples
    return api.analyze(_catalog(catalog), sensors=_ids(sensors), profiles=_ids(profiles),
                       method=method, rate=_rates(rate, unit), unit=unit, **extra)


def bounds(catalog: CatalogLike = None, *, budget: float | str,
           profiles: str | Sequence[str] = (), method: str = "exact",
           rate: float | str | Sequence[float | str] | None = None, unit: str | None = None,
           allocation: Sequence[float] | None = None, range_: float | str | None = None,
           nl_fit: str = "least-squares", nl_measure: str = "max", nl_of: str = "range",
           spec_weights: tuple[float, float] = (1.0, 1.0)) -> BoundsResult:
    """Allowable coefficients per profile for a budget, eq. (23) and (25).

    Parameters
    ----------
    catalog : Catalog, path, list of paths or None
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
    from gyrovib import api

    unit = _budget_unit(unit, budget)
    return api.bounds(_catalog(catalog), profiles=_ids(profiles), method=method,
                      rate=_rates(rate, unit), budget=_rate(budget, unit), unit=unit,
                      allocation=allocation,
                      range_=None if range_ is None else _rate(range_, unit), nl_fit=nl_fit,
                      nl_measure=nl_measure, nl_of=nl_of, spec_weights=spec_weights)


def select(catalog: CatalogLike = None, *, budget: float | str,
           sensors: str | Sequence[str] = (), profiles: str | Sequence[str] = (),
           method: str = "exact", rate: float | str | Sequence[float | str] | None = None,
           unit: str | None = None, criterion: str = "bounds", require: str = "any",
           allocation: Sequence[float] | None = None,
           spec_weights: tuple[float, float] = (1.0, 1.0),
           peak_factor: float = 3.0, assume_unknown: str = "none") -> SelectionResult:
    """Which sensors meet the budget: bound checks and eq. (17), ranked by margin.

    Parameters
    ----------
    catalog : Catalog, path, list of paths or None
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
    from gyrovib import api

    unit = _budget_unit(unit, budget)
    return api.select(_catalog(catalog), sensors=_ids(sensors), profiles=_ids(profiles),
                      method=method, rate=_rates(rate, unit), budget=_rate(budget, unit),
                      unit=unit, criterion=criterion, require=require, allocation=allocation,
                      spec_weights=spec_weights, peak_factor=peak_factor,
                      assume_unknown=assume_unknown)


def sweep(catalog: CatalogLike = None, rates: Sequence[float | str] | Any = (-200, 200),
          *, points: int = 401, sensors: str | Sequence[str] = (),
          profiles: str | Sequence[str] = (), unit: str = "deg/s") -> SweepResult:
    """Δ_V and Δ_V(RMS) over a range of Ω_K3, exact and paper.

    Parameters
    ----------
    catalog : Catalog, path, list of paths or None
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
    from gyrovib import api

    values = [_rate(v, unit) for v in list(rates)]
    omega = api.rate_range(values[0], values[1], points) if len(values) == 2 else values
    return api.sweep(_catalog(catalog), omega, sensors=_ids(sensors),
                     profiles=_ids(profiles), unit=unit)
