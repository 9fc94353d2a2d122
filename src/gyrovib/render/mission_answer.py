"""The words of a mission result that the numbers alone do not say: the answer first
(which part to buy, by what margin, or the one figure that would change a failure),
and each row's allowance — the largest figure that still meets the angle budget
(:class:`gyrovib.api.noise.Allowance`) — as table cells."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from gyrovib.api.noise.results import ALLOWANCE_UNITS
from gyrovib.render.common import fmt
from gyrovib.render.formats import Cell

if TYPE_CHECKING:
    from gyrovib.api.missions.results import MissionResult, MissionRow

#: The allowance's terms, their symbol and the word for the term that limits them.
TERMS = {"vibration": ("|θ_V|", "θ_V"), "arw": ("N", "ARW"),
         "bias_instability": ("B", "B"), "rrw": ("K", "RRW"), "repeatability": ("R", "R")}


def _allowed(name: str) -> Callable[[MissionRow], str]:
    """A term's cell: '≤ value' (with '*' where it is only an upper limit), 'none
    (<term>)': no value passes, that term alone uses the allowance, or '?' where the
    allowance rests on an error that is unknown."""
    def text(row: MissionRow) -> str:
        if row.budget is None or row.budget.allowed is None:
            return "-"
        a = row.budget.allowed
        value = getattr(a, name)
        if value is None:
            return f"none ({TERMS[a.limit(name) or 'vibration'][1]})"
        if math.isnan(value):  # it rests on an error that is unknown
            return "?"
        return f"≤ {fmt(value)}" + ("*" if name in a.upper else "")
    return text


def allowance_cells() -> tuple[Cell[MissionRow], ...]:
    """The allowance's columns, one per term headed by its symbol and unit (the records
    ``allowed_<term>``)."""
    return tuple(Cell(f"{symbol} ≤ ({ALLOWANCE_UNITS[name]})", _allowed(name), "right",
                      of=f"allowed_{name}") for name, (symbol, _) in TERMS.items())


def _worst_row(result: MissionResult, sensor: str) -> MissionRow | None:
    rows = [r for r in result.rows if r.sensor == sensor and r.budget is not None]
    return max(rows, key=lambda r: (r.saturated, r.budget.total if r.budget else 0.0),
               default=None)


def _one_figure(row: MissionRow) -> str | None:
    """The single figure whose change would make ``row`` pass, the smallest change first
    (relative to its present value), as words; None if no single figure does."""
    b = row.budget
    if b is None or b.allowed is None:
        return None
    best: tuple[float, str] | None = None
    for name, (symbol, _) in TERMS.items():
        allowed = getattr(b.allowed, name)
        present = abs(b.vibration) if name == "vibration" else getattr(b, name)
        if allowed is None or present is None or present <= 0:
            continue
        if name != "vibration":  # the budget holds θ; the figure scales with it
            present_figure = present * allowed / _theta_of(b.allowed, name, row.duration)
        else:
            present_figure = present
        ratio = allowed / present_figure
        text = (f"{symbol} ≤ {fmt(allowed)} {ALLOWANCE_UNITS[name]} "
                f"(it has {fmt(present_figure)})")
        if best is None or ratio > best[0]:
            best = (ratio, text)
    return None if best is None else best[1]


def _theta_of(allowed: Any, name: str, seconds: float) -> float:
    """θ of term ``name`` at its allowed figure over ``seconds`` (deg)."""
    hours = seconds / 3600.0
    power = {"arw": 0.5, "bias_instability": 1.0, "rrw": 1.5, "repeatability": 1.0}[name]
    factor = 1.0 / 3.0 ** 0.5 if name == "rrw" else 1.0
    value: float = getattr(allowed, name) * hours ** power * factor
    return value


def answer_line(result: MissionResult) -> str | None:
    """The answer in one line (None without an angle budget): the part to buy and its
    margin, or that none passes, the closest part and the one figure that would change
    that."""
    if result.angle_budget is None:
        return None
    unit = result.angle_unit
    budget = result.angle_budget
    worst = {s: _worst_row(result, s) for s in result.sensors}
    totals = {s: (r.budget.total if r is not None and r.budget is not None else float("inf"))
              for s, r in worst.items()}
    passing = [s for k, s in enumerate(result.sensors) if result.sensor_pass[k]]
    if passing:
        best = min(passing, key=lambda s: totals[s])
        margin = budget - totals[best]
        more = f"; {len(passing) - 1} other part(s) pass too" if len(passing) > 1 else ""
        return (f"answer: buy {best}: its worst total {fmt(totals[best])} {unit} is within "
                f"the {fmt(budget)} {unit} budget by {fmt(margin)} {unit} "
                f"({fmt(100.0 * margin / budget)} %){more}.")
    unverified = [s for k, s in enumerate(result.sensors)
                  if result.sensor_status(k) == "unverified"]
    if unverified:
        s = min(unverified, key=lambda s: totals[s])
        return (f"answer: no part passes for certain; {s} passes on its published figures "
                f"(total ≥ {fmt(totals[s])} {unit}) but an unknown figure can decide it: "
                "ask its vendor.")
    closest = min(result.sensors, key=lambda s: totals[s])
    row = worst[closest]
    change = None if row is None else _one_figure(row)
    tail = (f"; it would pass with {change}" if change else
            "; no single figure changes that")
    return (f"answer: no part passes; the closest is {closest} at {fmt(totals[closest])} "
            f"{unit} against {fmt(budget)} {unit}{tail}.")
