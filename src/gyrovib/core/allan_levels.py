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
#: 68 % and for 95 %: a calibration set by simulation, not derived. On the coverage
#: study's 2,400 records (benchmarks/bench_allan_coverage.py, twelve ranges of 200 run
#: with ``--save``; benchmarks/allan_coverage_levels.py ``--solve``) these are the least
#: levels, on a grid of 0.005, at which each term's interval held its truth in 68 % and
#: in 95 % of the records that resolve it. They hold for that study's design (records of
#: 2¹⁵ samples, its five cases and truths); docs/error-budget.md section 5 lists the
#: ranges and says what the levels may not carry to.
READ_LEVELS = ((0.695, 0.975), (0.69, 0.955), (0.655, 0.97), (0.635, 0.945), (0.505, 0.925))


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
