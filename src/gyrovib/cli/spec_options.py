"""Options of the datasheet (spec-form) features: the split and the stated envelope."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, TypeVar

import click

from gyrovib.cli.options import positive_rate
from gyrovib.errors import OptionError

F = TypeVar("F", bound=Callable[..., Any])

#: The YAML words of a nonlinearity's definition (catalogue ``specs.nonlinearity``).
NL_FITS = ("least-squares", "minimax", "endpoint")
NL_MEASURES = ("max", "rms")
NL_OF = ("range", "span")


def spec_weights_option(f: F) -> F:
    return click.option(
        "--spec-weights", default=None, metavar="NL,VRE",
        help="Split of the budget between the nonlinearity envelope and the VRE term "
             "for the datasheet bounds (default 1,1 over the parts the profile excites).",
    )(f)


def assume_unknown_option(f: F) -> F:
    return click.option(
        "--assume-unknown", "assume_unknown", type=click.Choice(["zero"]), default=None,
        help="Take a figure a datasheet does not publish (VRE, m31, m32) as 0 where it can "
             "matter. By default it is unknown: a part that passes on its published figures "
             "but hangs on an unpublished one is 'unverified' (not passing), with the "
             "questions for its vendor; the output says when the assumption was made.",
    )(f)


def parse_spec_weights(text: str | None) -> tuple[float, float]:
    """``--spec-weights NL,VRE`` → two positive finite weights (default (1, 1))."""
    if text is None:
        return (1.0, 1.0)
    pieces = [p.strip() for p in text.split(",")]
    try:
        values = tuple(float(p) for p in pieces)
    except ValueError:
        values = ()
    if len(values) != 2 or not all(math.isfinite(v) and v > 0 for v in values):
        raise OptionError(f"--spec-weights {text!r}: give two positive numbers, NL,VRE")
    return (values[0], values[1])


def range_options(f: F) -> F:
    f = click.option("--nl-of", type=click.Choice(NL_OF), default="range", show_default=True,
                     help="The allowable nonlinearity in %FS of the range R or of the "
                          "span 2R.")(f)
    f = click.option("--nl-measure", type=click.Choice(NL_MEASURES), default="max",
                     show_default=True,
                     help="Nonlinearity measure: the peak deviation, or its rms.")(f)
    f = click.option("--nl-fit", type=click.Choice(NL_FITS), default="least-squares",
                     show_default=True,
                     help="Reference line of the nonlinearity: best-fit (least-squares), "
                          "independent (minimax) or terminal (endpoint).")(f)
    f = click.option("--range", "range_", default=None, metavar="R",
                     help="Also give the allowable datasheet figures (nonlinearity in %FS "
                          "of R, VRE) for a part of full-scale range R (in --unit, or with "
                          "a unit).")(f)
    return f


def parse_range(text: str | None, unit: str) -> float | None:
    """``--range`` → R in deg/s (positive, finite), or None."""
    return None if text is None else positive_rate("--range", text, unit, "the range")
