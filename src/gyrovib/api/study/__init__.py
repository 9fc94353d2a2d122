"""The Study: a catalogue's chosen sensors and profiles in deg/s, prepared once.

Its modules are listed in docs/architecture.md. ``gyrovib.api.prepare`` is
``Study.of(...).prepare(...)``. Every view of the library (analyze, sweep, bounds,
select, report, mission) asks a ``Study`` for what it needs; nothing here evaluates
the model's error.
"""

from __future__ import annotations

from gyrovib.api.study.convert import coefficient_matrix, resolve_rate, sensor_ranges, to_unit
from gyrovib.api.study.entries import load, select_entries
from gyrovib.api.study.prepare import Prepared, check_finite, float_guard
from gyrovib.api.study.study import Study, check_peak_factor

__all__ = ["Prepared", "Study", "check_finite", "check_peak_factor", "coefficient_matrix",
           "float_guard", "load", "resolve_rate", "select_entries",
           "sensor_ranges", "to_unit"]
