"""Numbers written for people: the one definition shared by the library's sentences
(:mod:`gyrovib.reasons`) and the renderers' tables (:mod:`gyrovib.render.common`)."""

from __future__ import annotations

import math

#: Tables write 0 for a value below this fraction of the budget (rounding residue).
NEGLIGIBLE = 1e-12


def fmt(value: float | None, digits: int = 4) -> str:
    """A number for a table or a sentence: ``digits`` significant figures, '∞' for
    unbounded."""
    if value is None:
        return "∞"
    v = float(value)
    if v - v == 0.0 and v != 0.0:  # finite and not zero: the usual case, first
        return format(v, _SPECS.get(digits) or f".{digits}g")
    if math.isinf(v):
        return "∞" if v > 0 else "-∞"
    if math.isnan(v):
        return "nan"
    return "0"


#: The format specs of the usual digit counts, built once.
_SPECS = {d: f".{d}g" for d in range(1, 18)}
