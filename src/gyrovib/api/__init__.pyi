"""The names of :mod:`gyrovib.api`, for type checkers: the one listing of the
package face (``__init__.py`` imports each on first use, from ``_WHERE``, which
``tests/test_layers.py`` holds equal to this stub)."""

from gyrovib.api.commands.analyze import (
    ANALYZE_METHODS as ANALYZE_METHODS,
)
from gyrovib.api.commands.analyze import (
    DEFAULT_SAMPLES as DEFAULT_SAMPLES,
)
from gyrovib.api.commands.analyze import (
    DEFAULT_SEED as DEFAULT_SEED,
)
from gyrovib.api.commands.analyze import (
    ProgressCallback as ProgressCallback,
)
from gyrovib.api.commands.analyze import (
    analyze as analyze,
)
from gyrovib.api.commands.analyze import (
    profile_generator as profile_generator,
)
from gyrovib.api.commands.bounds import (
    bounds as bounds,
)
from gyrovib.api.commands.bounds import (
    resolve_allocation as resolve_allocation,
)
from gyrovib.api.commands.fit import (
    fit as fit,
)
from gyrovib.api.commands.select import (
    CRITERIA as CRITERIA,
)
from gyrovib.api.commands.select import (
    PASS_RTOL as PASS_RTOL,
)
from gyrovib.api.commands.select import (
    REQUIREMENTS as REQUIREMENTS,
)
from gyrovib.api.commands.select import (
    select as select,
)
from gyrovib.api.commands.sweep import (
    MAX_SWEEP_POINTS as MAX_SWEEP_POINTS,
)
from gyrovib.api.commands.sweep import (
    rate_range as rate_range,
)
from gyrovib.api.commands.sweep import (
    sweep as sweep,
)
from gyrovib.api.evaluation.results import (
    AnalysisResult as AnalysisResult,
)
from gyrovib.api.evaluation.results import (
    BoundsResult as BoundsResult,
)
from gyrovib.api.evaluation.results import (
    Limit as Limit,
)
from gyrovib.api.evaluation.results import (
    SelectionResult as SelectionResult,
)
from gyrovib.api.evaluation.results import (
    SweepResult as SweepResult,
)
from gyrovib.api.lots.yields import (
    LotYields as LotYields,
)
from gyrovib.api.missions.results import (
    MissionResult as MissionResult,
)
from gyrovib.api.noise.mission import (
    mission as mission,
)
from gyrovib.api.placement.placement import (
    place_catalog as place_catalog,
)
from gyrovib.api.placement.placement import (
    place_profile as place_profile,
)
from gyrovib.api.ratetable.reading import (
    RateTable as RateTable,
)
from gyrovib.api.ratetable.reading import (
    read_rate_table as read_rate_table,
)
from gyrovib.api.ratetable.results import (
    FitResult as FitResult,
)
from gyrovib.api.study.convert import (
    coefficient_matrix as coefficient_matrix,
)
from gyrovib.api.study.convert import (
    profile_rate as profile_rate,
)
from gyrovib.api.study.convert import (
    resolve_rate as resolve_rate,
)
from gyrovib.api.study.convert import (
    sensor_ranges as sensor_ranges,
)
from gyrovib.api.study.convert import (
    to_unit as to_unit,
)
from gyrovib.api.study.entries import (
    load as load,
)
from gyrovib.api.study.entries import (
    profile_location as profile_location,
)
from gyrovib.api.study.entries import (
    profile_locations as profile_locations,
)
from gyrovib.api.study.entries import (
    select_entries as select_entries,
)
from gyrovib.api.study.entries import (
    sensor_location as sensor_location,
)
from gyrovib.api.study.entries import (
    sensor_locations as sensor_locations,
)
from gyrovib.api.study.prepare import (
    Prepared as Prepared,
)
from gyrovib.api.study.prepare import (
    check_bounds as check_bounds,
)
from gyrovib.api.study.prepare import (
    check_finite as check_finite,
)
from gyrovib.api.study.prepare import (
    float_guard as float_guard,
)
from gyrovib.api.study.prepare import (
    profile_locked as profile_locked,
)
from gyrovib.api.study.prepare import (
    profile_vibration as profile_vibration,
)
from gyrovib.api.study.prepare import (
    quiet_float as quiet_float,
)
from gyrovib.api.study.prepare import (
    response_groups as response_groups,
)
from gyrovib.api.study.prepare import (
    response_table as response_table,
)
from gyrovib.api.study.prepare import (
    vibration_peak as vibration_peak,
)
from gyrovib.api.study.prepare import (
    vibration_swing as vibration_swing,
)
from gyrovib.api.study.study import (
    Study as Study,
)
from gyrovib.api.study.study import (
    prepare as prepare,
)
from gyrovib.catalog.loader import (
    Catalog as Catalog,
)
from gyrovib.catalog.loader import (
    ProfileEntry as ProfileEntry,
)
from gyrovib.catalog.loader import (
    SensorEntry as SensorEntry,
)
from gyrovib.models import (
    Allocation as Allocation,
)

__all__ = [
    "ANALYZE_METHODS",
    "CRITERIA",
    "DEFAULT_SAMPLES",
    "DEFAULT_SEED",
    "MAX_SWEEP_POINTS",
    "PASS_RTOL",
    "REQUIREMENTS",
    "Allocation",
    "AnalysisResult",
    "BoundsResult",
    "Catalog",
    "FitResult",
    "Limit",
    "LotYields",
    "MissionResult",
    "Prepared",
    "ProfileEntry",
    "ProgressCallback",
    "RateTable",
    "SelectionResult",
    "SensorEntry",
    "Study",
    "SweepResult",
    "analyze",
    "bounds",
    "check_bounds",
    "check_finite",
    "coefficient_matrix",
    "fit",
    "float_guard",
    "load",
    "mission",
    "place_catalog",
    "place_profile",
    "prepare",
    "profile_generator",
    "profile_location",
    "profile_locations",
    "profile_locked",
    "profile_rate",
    "profile_vibration",
    "quiet_float",
    "rate_range",
    "read_rate_table",
    "resolve_allocation",
    "resolve_rate",
    "response_groups",
    "response_table",
    "select",
    "select_entries",
    "sensor_location",
    "sensor_locations",
    "sensor_ranges",
    "sweep",
    "to_unit",
    "vibration_peak",
    "vibration_swing",
]
