"""The options of ``select --yield`` (docs/model.md section 14): the target yield of a
production lot, and the Monte-Carlo draws and seed."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

import click

F = TypeVar("F", bound=Callable[..., Any])

#: Defaults, as gyrovib.api.lots.yields and gyrovib.core.lot have them (not imported here:
#: `gyrovib --help` imports no numpy).
DRAWS = 100_000
SEED = 0


def yield_options(function: F) -> F:
    """``--yield Y``, ``--draws N``, ``--seed S``."""
    function = click.option(
        "--seed", type=click.IntRange(min=0), default=SEED, show_default=True, metavar="S",
        help="--yield: seed of the Monte-Carlo draws; the same seed gives the same yields.",
    )(function)
    function = click.option(
        "--draws", type=click.IntRange(min=1), default=DRAWS, show_default=True, metavar="N",
        help="--yield: Monte-Carlo draws per lot (the RMS test and the bound checks).",
    )(function)
    return click.option(
        "--yield", "yield_target", type=float, default=None, metavar="Y",
        help="Judge a production lot (`lot:`) by its yield: it passes a profile when the "
             "probability that a part drawn from it passes the criterion is at least Y "
             "(0 < Y < 1, e.g. 0.9973 for 3σ). Exact for --criterion worst, Monte Carlo "
             "with a 95% Wilson interval otherwise (docs/model.md section 14). A lot whose "
             "spread is not measured (units <= coefficients, a sigma of 0, a singular "
             "covariance) is unverified where its yield passes. Other sensors are judged as "
             "without it.",
    )(function)
