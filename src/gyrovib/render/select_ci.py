"""``select`` for continuous integration: JUnit XML (one test case per sensor ×
profile) and GitHub workflow annotations (one per sensor, at its catalogue line)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from gyrovib.api import SelectionResult
from gyrovib.render.common import fmt
from gyrovib.render.formats import Case, junit_of
from gyrovib.render.github import annotations as github_annotations
from gyrovib.render.select import (
    _CRITERION,
    _margin,
    _summary,
    _unknown_names,
    failures,
    limit_text,
)

__all__ = ["to_github", "to_junit"]


def to_junit(result: SelectionResult) -> str:
    """JUnit XML: one testcase per sensor × profile (classname = sensor, name = profile)."""
    return junit_of("gyrovib select", f"gyrovib select: budget {fmt(result.budget)} "
                    f"{result.unit}, method {result.method}, criterion {result.criterion}",
                    [_case(result, i, j) for i in range(len(result.sensors))
                     for j in range(len(result.profiles))])


def _case(result: SelectionResult, i: int, j: int) -> Case:
    """Sensor ``i`` under profile ``j`` as a JUnit test case; an unverified one fails."""
    names = ", ".join(_unknown_names(result, i, j))
    if result.is_unverified(i, j) and math.isnan(result.rms[i, j]):
        out = f"unverified ({names} unknown); Δ_V(RMS) unknown"
    elif result.is_unverified(i, j):
        out = (f"unverified ({names} unknown); on the published figures "
               f"Δ_V(RMS) = {fmt(result.rms[i, j])} {result.unit}")
    else:
        out = (f"Δ_V(RMS) = {fmt(result.rms[i, j])} {result.unit}, "
               f"margin {_margin(result.margin[i, j])}"
               + (f" (assumed {names} = 0: --assume-unknown zero)" if names else ""))
    if result.passed[i, j]:
        return result.sensors[i], result.profiles[j], out, None
    reasons = failures(result, i, j)
    kind = "Unverified" if result.is_unverified(i, j) else "BudgetExceeded"
    return result.sensors[i], result.profiles[j], out, (kind, "; ".join(reasons),
                                                        "\n".join(reasons))


def to_github(
    result: SelectionResult, locations: Sequence[tuple[str | None, int | None]]
) -> str:
    """GitHub workflow annotations: one ``::error`` per failing sensor at its catalogue line,
    a ``::notice`` per passing sensor, and a closing summary notice.

    GitHub shows 10 of each level per step: past that the worst are annotated,
    one notice counts the rest, and those follow as plain log lines.

    ``locations[i]`` is the (file, line) of sensor ``i``'s ``id:``.
    """
    items: list[tuple[str | None, int | None, str | None, str, str]] = []
    rank: list[float] = []  # GitHub shows 10 of each level: the smallest margins first
    for i, sensor in enumerate(result.sensors):
        file, line = locations[i]
        rank.append(float(result.worst_margin[i]))
        if result.sensor_pass[i]:
            worst = _margin(float(result.worst_margin[i]))
            met = (f"meets Δ* = {fmt(result.budget)} {result.unit} under every profile; worst "
                   f"margin {worst}")
            if result.yields is not None and result.yields.is_lot(i):
                lowest = fmt(float(np.nanmin(result.yields.value[i])), 4)
                met = (f"(a production lot) has a yield of at least {result.yields.target:g} "
                       f"under every profile (lowest {lowest}) against Δ* = "
                       f"{fmt(result.budget)} {result.unit}")
            items.append((file, line, f"{sensor} passes", f"{sensor} {met}", "notice"))
            continue
        reasons = [f"{result.profiles[j]}: {'; '.join(failures(result, i, j))}"
                   for j in range(len(result.profiles)) if not result.passed[i, j]]
        if result.sensor_status(i) == "unverified":
            asks = "; ".join(result.questions.get(i, ()))
            text = (f"{sensor} passes Δ* = {fmt(result.budget)} {result.unit} on its "
                    "published figures, but an unpublished one can decide it. Ask the "
                    f"vendor: {asks}. " if asks or not _not_recorded(result, i) else
                    f"{sensor}: its error is unknown under a profile fitted from a recording "
                    "that lacks an axis it depends on. ")
            items.append((file, line, f"{sensor} is unverified", text + " | ".join(reasons),
                          "error"))
            continue
        items.append((file, line, f"{sensor} fails the budget",
                      f"{sensor} fails Δ* = {fmt(result.budget)} {result.unit} "
                      f"({_CRITERION[result.criterion]}). Limited by {limit_text(result, i)}. "
                      + " | ".join(reasons), "error"))
    items.append((None, None, "gyrovib select", _summary(result), "notice"))
    rank.append(-math.inf)  # the summary is always shown
    return github_annotations(items, rank=rank)


def _not_recorded(result: SelectionResult, i: int) -> bool:
    """Whether sensor ``i`` is unverified on a part a fitted profile's recording lacks."""
    return any(n in ("x1", "x2", "x3", "acceleration") for n in result.sensor_unknown(i))
