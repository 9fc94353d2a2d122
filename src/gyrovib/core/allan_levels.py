"""The level at which each term's studentized interval is read for a confidence: a
calibration set by simulation on the coverage study, not derived (docs/error-budget.md
section 5; docs/model.md section 15).

The studentized interval of :mod:`gyrovib.core.allan_fit`, read at the nominal level,
covered its truth too often at 68 % for the rate ramp (83 % of the 160 records with a ramp)
and the rate random walk (73 %), and too rarely at 95 % for quantization (92 %). Scaled
by the spread of its replicates' roots, the record's root at the truth is spread
differently from the replicates' (for the ramp its 68 % point 0.80, theirs 0.98): the
replicates are drawn from the fitted model, and a little flicker or random walk that
the fit puts where the truth has none widens its neighbours' replicates, so their
spread follows the fitted nuisance terms from record to record more than the error
does. The study's roots, saved per record and term, give the coverage at any level;
each term is read at the level at which it covered as asked. Checked on ranges run after they
were frozen (docs/error-budget.md section 5).
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
