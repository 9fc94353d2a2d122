"""``select`` for continuous integration: JUnit XML (one test case per sensor ×
profile) and GitHub workflow annotations (one per sensor, at its catalogue line)."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Sequence

import numpy as np

from gyrovib.api import SelectionResult
from gyrovib.render.common import fmt
from gyrovib.render.github import annotations
from gyrovib.render.select import (
    _CRITERION,
    _margin,
    _summary,
    _unknown_names,
    failures,
    limit_text,
)

__all__ = ["to_github", "to_junit"]


# ------------------------------------------------------------------ JUnit


def to_junit(result: SelectionResult) -> str:
    """JUnit XML: one testcase per sensor × profile (classname = sensor, name = profile)."""
    n_cases = len(result.sensors) * len(result.profiles)
    n_fail = int((~result.passed.astype(bool)).sum())  # an unverified case fails too
    suites = ET.Element("testsuites", name="gyrovib select", tests=str(n_cases),
                        failures=str(n_fail), errors="0")
    suite = ET.SubElement(
        suites, "testsuite",
        name=f"gyrovib select: budget {fmt(result.budget)} {result.unit}, method "
             f"{result.method}, criterion {result.criterion}",
        tests=str(n_cases), failures=str(n_fail), errors="0", skipped="0",
    )
    for i, sensor in enumerate(result.sensors):
        for j, profile in enumerate(result.profiles):
            case = ET.SubElement(suite, "testcase", classname=sensor, name=profile, time="0")
            out = ET.SubElement(case, "system-out")
            names = ", ".join(_unknown_names(result, i, j))
            if result.is_unverified(i, j) and math.isnan(result.rms[i, j]):
                out.text = f"unverified ({names} unknown); Δ_V(RMS) unknown"
            elif result.is_unverified(i, j):
                out.text = (f"unverified ({names} unknown); on the published figures "
                            f"Δ_V(RMS) = {fmt(result.rms[i, j])} {result.unit}")
            else:
                out.text = (f"Δ_V(RMS) = {fmt(result.rms[i, j])} {result.unit}, "
                            f"margin {_margin(result.margin[i, j])}"
                            + (f" (assumed {names} = 0: --assume-unknown zero)" if names
                               else ""))
            if not result.passed[i, j]:
                reasons = failures(result, i, j)
                kind = "Unverified" if result.is_unverified(i, j) else "BudgetExceeded"
                failure = ET.Element("failure", message="; ".join(reasons), type=kind)
                failure.text = "\n".join(reasons)
                case.insert(0, failure)
    ET.indent(suites)
    return ET.tostring(suites, encoding="unicode", xml_declaration=True) + "\n"


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
    return annotations(items, rank=rank)


def _not_recorded(result: SelectionResult, i: int) -> bool:
    """Whether sensor ``i`` is unverified on a part a fitted profile's recording lacks."""
    return any(n in ("x1", "x2", "x3", "acceleration") for n in result.sensor_unknown(i))
