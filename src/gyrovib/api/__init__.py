"""Library entry points: a catalogue in, immutable results out.

This layer joins the catalogue (:mod:`gyrovib.catalog`) to the numpy engines
(:mod:`gyrovib.core`) and does all unit handling: catalogue values are
converted to deg/s on the way in, results to the requested output unit on the
way out.

=============================  ===============================================
module                          what it holds
=============================  ===============================================
:mod:`gyrovib.api.entries`      ``load``, choosing entries, their file lines
:mod:`gyrovib.api.convert`      unit conversions (deg/s in, output unit out)
:mod:`gyrovib.api.prepare`      the one pipeline and its overflow checks
:mod:`gyrovib.api.results`      the immutable result types
:mod:`gyrovib.api.commands`     one module per command
=============================  ===============================================

The names below are imported lazily, on first use.

>>> from gyrovib.api import load, analyze
>>> result = analyze(load())          # the bundled catalogues  # doctest: +SKIP
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

_WHERE: dict[str, str] = {
    # entries
    "load": "entries",
    "select_entries": "entries",
    "sensor_location": "entries",
    "sensor_locations": "entries",
    "profile_location": "entries",
    "profile_locations": "entries",
    # conversion
    "coefficient_matrix": "convert",
    "sensor_ranges": "convert",
    "profile_rate": "convert",
    "resolve_rate": "convert",
    "to_unit": "convert",
    # the pipeline
    "prepare": "prepare",
    "Prepared": "prepare",
    "float_guard": "prepare",
    "quiet_float": "prepare",
    "check_finite": "prepare",
    "check_bounds": "prepare",
    "profile_vibration": "prepare",
    "response_table": "prepare",
    "response_groups": "prepare",
    "vibration_peak": "prepare",
    # results
    "AnalysisResult": "results",
    "SweepResult": "results",
    "BoundsResult": "results",
    "SelectionResult": "results",
    "Limit": "results",
    # commands
    "analyze": "commands.analyze",
    "ANALYZE_METHODS": "commands.analyze",
    "DEFAULT_SAMPLES": "commands.analyze",
    "DEFAULT_SEED": "commands.analyze",
    "ProgressCallback": "commands.analyze",
    "profile_generator": "commands.analyze",
    "sweep": "commands.sweep",
    "rate_range": "commands.sweep",
    "MAX_SWEEP_POINTS": "commands.sweep",
    "bounds": "commands.bounds",
    "resolve_allocation": "commands.bounds",
    "select": "commands.select",
    "CRITERIA": "commands.select",
    "REQUIREMENTS": "commands.select",
    "PASS_RTOL": "commands.select",
    # catalogue types, for annotations
    "Catalog": "gyrovib.catalog.loader",
    "ProfileEntry": "gyrovib.catalog.loader",
    "SensorEntry": "gyrovib.catalog.loader",
    "Allocation": "gyrovib.catalog.records",
}

__all__ = sorted(_WHERE)


def __getattr__(name: str) -> Any:
    where = _WHERE.get(name)
    if where is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    module = importlib.import_module(where if where.startswith("gyrovib.")
                                     else f"{__name__}.{where}")
    value = getattr(module, name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_WHERE})


if TYPE_CHECKING:
    from gyrovib.api.commands.analyze import (
        ANALYZE_METHODS,
        DEFAULT_SAMPLES,
        DEFAULT_SEED,
        ProgressCallback,
        analyze,
        profile_generator,
    )
    from gyrovib.api.commands.bounds import bounds, resolve_allocation
    from gyrovib.api.commands.select import CRITERIA, PASS_RTOL, REQUIREMENTS, select
    from gyrovib.api.commands.sweep import MAX_SWEEP_POINTS, rate_range, sweep
    from gyrovib.api.convert import (
        coefficient_matrix,
        profile_rate,
        resolve_rate,
        sensor_ranges,
        to_unit,
    )
    from gyrovib.api.entries import (
        load,
        profile_location,
        profile_locations,
        select_entries,
        sensor_location,
        sensor_locations,
    )
    from gyrovib.api.prepare import (
        Prepared,
        check_bounds,
        check_finite,
        float_guard,
        prepare,
        profile_vibration,
        quiet_float,
        response_groups,
        response_table,
        vibration_peak,
    )
    from gyrovib.api.results import (
        AnalysisResult,
        BoundsResult,
        Limit,
        SelectionResult,
        SweepResult,
    )
    from gyrovib.catalog.loader import Catalog, ProfileEntry, SensorEntry
    from gyrovib.catalog.records import Allocation
