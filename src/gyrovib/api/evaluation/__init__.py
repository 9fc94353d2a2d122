"""The model evaluated on a prepared Study, and the immutable results of the views.

==========================================  =====================================
module                                      what it holds
==========================================  =====================================
:mod:`gyrovib.api.evaluation.evaluate`      the sensor forms, the error loop over
                                            the groups (``errors``), saturation
:mod:`gyrovib.api.evaluation.results`       the result types of analyze, sweep,
                                            bounds and select (``Result``)
==========================================  =====================================
"""

from __future__ import annotations

from gyrovib.api.evaluation.evaluate import ERROR_PARTS, errors, saturation, worst_case
from gyrovib.api.evaluation.results import (
    AnalysisResult,
    BoundsResult,
    Limit,
    Result,
    SelectionResult,
    SweepResult,
)

__all__ = ["ERROR_PARTS", "AnalysisResult", "BoundsResult", "Limit", "Result",
           "SelectionResult", "SweepResult", "errors", "saturation", "worst_case"]
