"""The level at which each term's studentized interval (:mod:`gyrovib.core.allan_fit`) is
read for a confidence: a calibration set by simulation on the coverage study, not derived.
Read at the nominal level, the intervals covered some terms' truths too often or too
rarely; docs/error-budget.md section 5 gives why, the study's design these levels hold
for, and the coverage they achieve on records they were not set on (docs/model.md
section 15).
"""

from __future__ import annotations

import numpy as np

#: The level at which each term's studentized interval is read (:data:`TERMS` order) for
#: 68 % and for 95 %: the least levels, on a grid of 0.005, at which each term's interval
#: held its truth in 68 % and 95 % of the study's 800 records that resolve it
#: (benchmarks/bench_allan_coverage.py ``--save``, then benchmarks/allan_coverage_levels.py
#: ``--solve``; the seeds are in docs/error-budget.md section 5).
READ_LEVELS = ((0.66, 0.975), (0.695, 0.965), (0.695, 0.975), (0.63, 0.95), (0.51, 0.925))


def read_level(j: int, confidence: float) -> float:
    """The level at which term j's studentized interval is read for ``confidence``:
    :data:`READ_LEVELS` at 68 % and 95 %, linear between them and from (0, 0) and to
    (1, 1) elsewhere; the Gauss–Markov σ (j = 5), which the study does not simulate, at
    ``confidence`` itself."""
    if j >= len(READ_LEVELS):
        return confidence
    r68, r95 = READ_LEVELS[j]
    return float(np.interp(confidence, (0.0, 0.68, 0.95, 1.0), (0.0, r68, r95, 1.0)))


__all__ = ["READ_LEVELS", "read_level"]
