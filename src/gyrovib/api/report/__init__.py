"""``gyrovib report``: the trade study, three views of one Study
(:mod:`gyrovib.api.report.views`: the selection, the analysis, and the sweep of the
best-ranked sensors)."""

from __future__ import annotations

from gyrovib.api.report.views import SWEEP_SENSORS, TradeStudy, envelope, trade_study

__all__ = ["SWEEP_SENSORS", "TradeStudy", "envelope", "trade_study"]
