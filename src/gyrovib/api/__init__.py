"""Library entry points: a catalogue in, immutable results out.

This layer joins the catalogue (:mod:`gyrovib.catalog`) to the numpy engines
(:mod:`gyrovib.core`) and does all unit handling: catalogue values are
converted to deg/s on the way in, results to the requested output unit on the
way out.

=================================  ============================================
package                            what it holds
=================================  ============================================
:mod:`gyrovib.api.study`           the Study: entries chosen, values in deg/s,
                                   the one preparation and its overflow checks
:mod:`gyrovib.api.datasheet`       the datasheet form: figures, worst case, the
                                   spec checks and spec bounds
:mod:`gyrovib.api.evaluation`      the model evaluated per sensor form, and the
                                   immutable result types
:mod:`gyrovib.api.commands`        one view of a Study per command
:mod:`gyrovib.api.report`          ``gyrovib report``: three views of one Study
:mod:`gyrovib.api.placement`       placements and the triad
=================================  ============================================

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
    "load": "study.entries",
    "select_entries": "study.entries",
    "sensor_location": "study.entries",
    "sensor_locations": "study.entries",
    "profile_location": "study.entries",
    "profile_locations": "study.entries",
    # conversion
    "coefficient_matrix": "study.convert",
    "sensor_ranges": "study.convert",
    "profile_rate": "study.convert",
    "resolve_rate": "study.convert",
    "to_unit": "study.convert",
    # the pipeline
    "prepare": "study.study",
    "Study": "study.study",
    "Prepared": "study.prepare",
    "float_guard": "study.prepare",
    "quiet_float": "study.prepare",
    "check_finite": "study.prepare",
    "check_bounds": "study.prepare",
    "profile_vibration": "study.prepare",
    "response_table": "study.prepare",
    "response_groups": "study.prepare",
    "vibration_peak": "study.prepare",
    "vibration_swing": "study.prepare",
    "profile_locked": "study.prepare",
    # results
    "AnalysisResult": "evaluation.results",
    "SweepResult": "evaluation.results",
    "BoundsResult": "evaluation.results",
    "SelectionResult": "evaluation.results",
    "Limit": "evaluation.results",
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
    "FitResult": "ratetable.results",
    "RateTable": "ratetable.reading",
    "read_rate_table": "ratetable.reading",
    "REQUIREMENTS": "commands.select",
    "PASS_RTOL": "commands.select",
    "mission": "noise.mission",
    "MissionResult": "missions.results",
    "LotYields": "lots.yields",
    "place_profile": "placement.placement",
    "place_catalog": "placement.placement",
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
