"""Coefficients as distributions (docs/model.md section 14): a fitted unit's
``uncertainty`` and a production ``lot``.

``uncertainty``: u(Δ_V) = √(gᵀΣg) for ``analyze``; ``yields``: the probability that a
part drawn from a lot meets the budget, for ``select --yield`` (``LotYields``).
"""

from __future__ import annotations

from gyrovib.api.lots.uncertainty import uncertainty, with_uncertainty
from gyrovib.api.lots.yields import LotYields, lot_yields

__all__ = ["LotYields", "lot_yields", "uncertainty", "with_uncertainty"]
