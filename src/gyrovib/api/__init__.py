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
:mod:`gyrovib.api.linear`       linear vibration (g) and g²-sensitivities (docs/model.md 8)
:mod:`gyrovib.api.prepare`      the one pipeline and its overflow checks
:mod:`gyrovib.api.results`      the immutable result types
:mod:`gyrovib.api.commands`     one module per command
=============================  ===============================================

The names below are imported lazily, on first use; ``__init__.pyi`` gives
them to type checkers.

>>> from gyrovib.api import load, analyze
>>> result = analyze(load())          # the bundled catalogues  # doctest: +SKIP
"""

from __future__ import annotations

import importlib
from typing import Any

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
    "prepare": "study",
    "Study": "study",
    "Prepared": "prepare",
    "float_guard": "prepare",
    "quiet_float": "prepare",
    "check_finite": "prepare",
    "check_bounds": "prepare",
    "profile_vibration": "prepare",
    "response_table": "prepare",
    "response_groups": "prepare",
    "vibration_peak": "prepare",
    "vibration_swing": "prepare",
    "profile_locked": "prepare",
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
    "fit": "commands.fit",
    "FitResult": "fit_results",
    "RateTable": "ratetable",
    "read_rate_table": "ratetable",
    "REQUIREMENTS": "commands.select",
    "PASS_RTOL": "commands.select",
    "mission": "noise.mission",
    "MissionResult": "mission_results",
    "LotYields": "yields",
    "place_profile": "placement",
    "place_catalog": "placement",
    # catalogue types, for annotations
    "Catalog": "gyrovib.catalog.loader",
    "ProfileEntry": "gyrovib.catalog.loader",
    "SensorEntry": "gyrovib.catalog.loader",
    "Allocation": "gyrovib.models",
}

__all__ = [*_WHERE]  # the names with their types: __init__.pyi


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
