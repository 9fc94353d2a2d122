"""Why a verdict fails, in words: ``select``'s reasons (its JSON's and DataFrame's
``reason``, its tables, JUnit and annotations) and an unverified ``mission`` row's.

The library finds what fails and hands it over as codes and numbers (:class:`Failure`,
:class:`Yield`), never as a result object; this module words them, as
:mod:`gyrovib.errors` words problems, so the JSON, the frame and the tables share one
text. Numbers are written with 4 significant figures, as in the tables.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import NamedTuple

from gyrovib.errors import Note
from gyrovib.formatting import fmt
from gyrovib.units import coefficient_unit

#: How a reason names taking an unpublished figure as 0: a note naming the argument, which
#: a result hands to its failures (the command line's copy of it names the option).
ASSUME_ZERO = Note("{assume_unknown}", ("assume_unknown", "zero"))


class Yield(NamedTuple):
    """A lot's yield at one sensor × profile (docs/model.md section 14): its value, the
    95 % interval (NaN for an exact yield), ``exact`` or ``monte-carlo``, and the draws."""

    value: float
    low: float
    high: float
    method: str
    draws: int


class Failure(NamedTuple):
    """One reason a sensor fails under a profile, as the library finds it. ``code``: what
    fails (a key of :data:`_WORDS`); ``numbers``: the figures it compares (a value and its
    bound or budget; a saturation's reach, range and κ; a yield's target); ``names``: a
    coefficient's name, or the unknown figures of an unverified cell; ``unit``: the rate
    unit; ``spec``: a datasheet part's; ``lot`` and ``note``: a lot's yield and why it is
    no measurement (an unverified lot) or its target is missed; ``advice``: how it names
    taking the unknown as 0 (the result's :data:`ASSUME_ZERO`)."""

    code: str
    numbers: tuple[float, ...] = ()
    names: tuple[str, ...] = ()
    unit: str = ""
    spec: bool = False
    lot: Yield | None = None
    note: str = ""
    advice: str = ASSUME_ZERO


def saturation_reason(reach: float, range_: float, peak_factor: float, unit: str) -> str:
    """Why a saturating sensor fails (docs/model.md section 9); ``reach``, ``range_`` in
    ``unit``."""
    return (f"saturated: |Ω_K3| + Σ tone amplitudes + locked peaks + {peak_factor:g}σ3 = "
            f"{reach:.6g} {unit} exceeds the range {range_:.6g} {unit}")


def yield_text(lot: Yield) -> str:
    """A lot's yield in words: ``0.9912 (exact)`` or ``0.9911 [0.9905, 0.9917] (monte-carlo,
    100000 draws)``."""
    if lot.method == "exact":
        return f"{fmt(lot.value, 4)} (exact)"
    return (f"{fmt(lot.value, 4)} [{fmt(lot.low, 4)}, {fmt(lot.high, 4)}] "
            f"(monte-carlo, {lot.draws} draws)")


#: Why each unknown figure can matter, as a reason names it.
UNKNOWN_WORDS = {
    "vre": "VRE not published (the profile has linear vibration, so its g² term "
           "G_jj·⟨a_j²⟩ can rectify; docs/model.md section 8)",
    "m31": "m31 not published (the profile has cross-axis vibration x1 correlated with "
           "x3, so m31·C31 can rectify; docs/model.md section 11)",
    "m32": "m32 not published (the profile has cross-axis vibration x2 correlated with "
           "x3, so m32·C32 can rectify; docs/model.md section 11)",
    "spread": "the lot's spread is not measured (too few units, or units without spread: "
              "its yield is not a measurement; docs/model.md section 14)",
    # the noise figures of a mission's budget (docs/model.md section 15)
    "arw": "angle random walk not given (N·√T)",
    "bias_instability": "bias instability not given (B·T)",
    "rrw": "rate random walk not given (K·T^1.5/√3)",
    "bias_repeatability": "bias repeatability not given (R·T; 0 if the bias is calibrated "
                          "at each start)",
}


#: What a profile fitted from a recording may lack (docs/model.md section 13), as a reason
#: names it.
NOT_RECORDED_WORDS = {"x1": "axis x1", "x2": "axis x2", "x3": "axis x3 (the sensitive axis)",
                      "acceleration": "the accelerations"}


#: Why a coefficient-form sensor's missing g² figure can matter, as a reason names it.
G2_WORDS = ("g² sensitivity not given (no g2_sensitivity or vre in the catalogue; the profile "
            "has linear vibration, so its g² term G_jj·⟨a_j²⟩ can rectify; docs/model.md "
            "section 8)")


def unverified_text(names: Sequence[str], spec: bool, advice: str) -> str:
    """The reason of an unverified verdict whose unpublished figures are ``names``
    (``select`` and ``mission`` alike); ``spec``: a datasheet part (else a coefficient
    sensor, whose missing g² figure is "not given" rather than "not published"). Names of
    :data:`NOT_RECORDED_WORDS` are parts a fitted profile's recording did not record.
    ``advice``: how to take the figures as 0 (select's: :attr:`Failure.advice`; mission's
    renderer: the command line's option)."""
    parts = [n for n in names if n in NOT_RECORDED_WORDS]
    figures = [n for n in names if n not in NOT_RECORDED_WORDS]
    out = []
    if parts:
        out.append("unverified: the profile was fitted from a recording without "
                   + ", ".join(NOT_RECORDED_WORDS[n] for n in parts)
                   + ", and this sensor's error depends on it (unknown, not 0; docs/model.md "
                   "section 13) -- record every axis")
    if figures:
        out.append("unverified: passes on its published figures, but "
                   + "; ".join(UNKNOWN_WORDS[n] if spec or n != "vre" else G2_WORDS
                               for n in figures)
                   + f" -- ask the vendor, or {advice} to take it as 0")
    return "; ".join(out)


def _unverified(f: Failure) -> str:
    """The unpublished figures that can decide the cell, then (a lot whose spread is not
    measured) why its yield is no measurement (docs/model.md sections 11, 14)."""
    out = [unverified_text(f.names, spec=f.spec, advice=f.advice)] if f.names else []
    if f.lot is not None:
        out.append(f"unverified: the yield {yield_text(f.lot)} is not a measurement, the "
                   f"lot's spread is not measured: {f.note} -- measure more units, "
                   f"or {f.advice} to take the lot as given")
    return "; ".join(out)


def _below(f: Failure) -> str:
    """A lot's yield under its target (docs/model.md section 14)."""
    assert f.lot is not None
    return f"yield {yield_text(f.lot)} is below {f.numbers[0]:g}"


def _coefficient(f: Failure) -> str:
    unit = coefficient_unit(f.names[0], f.unit)
    tail = "" if unit == "1" else f" {unit}"
    return f"|{f.names[0]}| = {fmt(f.numbers[0])} exceeds its bound {fmt(f.numbers[1])}{tail}"


def _worst(f: Failure) -> str:
    what = "worst |Δ_V| over the datasheet envelope" if f.spec else "|Δ_V|"
    return (f"{what} = {fmt(f.numbers[0])} {f.unit} exceeds the budget "
            f"{fmt(f.numbers[1])} {f.unit}")


#: The wording of each :attr:`Failure.code`.
_WORDS: dict[str, Callable[[Failure], str]] = {
    "unverified": _unverified,
    "saturated": lambda f: saturation_reason(f.numbers[0], f.numbers[1], f.numbers[2], f.unit),
    "yield": _below,
    "coefficient": _coefficient,
    "vre": lambda f: (f"effective VRE |Δ0(6)|/Σ⟨a_j²⟩ = {fmt(f.numbers[0])} {f.unit}/g^2 "
                      f"exceeds its bound {fmt(f.numbers[1])} {f.unit}/g^2"),
    "nonlinearity": lambda f: (f"datasheet nonlinearity {fmt(f.numbers[0])} %FS exceeds the "
                               f"allowable {fmt(f.numbers[1])} %FS"),
    "datasheet_vre": lambda f: (f"datasheet VRE {fmt(f.numbers[0])} {f.unit}/g² exceeds the "
                                f"allowable {fmt(f.numbers[1])} {f.unit}/g²"),
    "rms": lambda f: (f"Δ_V(RMS) = {fmt(f.numbers[0])} {f.unit} exceeds the budget "
                      f"{fmt(f.numbers[1])} {f.unit}"),
    "worst": _worst,
}


def worded(failures: Sequence[Failure]) -> list[str]:
    """Each failure in words, in order."""
    return [_WORDS[f.code](f) for f in failures]


def reason(failures: Sequence[Failure]) -> str | None:
    """The failures in one line (the JSON's and the frame's ``reason``); None without."""
    return "; ".join(worded(failures)) or None
