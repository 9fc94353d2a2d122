"""Options shared by several commands, and their parsing into library arguments."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any, TypeVar, cast

import click

from gyrovib import units
from gyrovib.errors import GyrovibError, Note, OptionError, Problem
from gyrovib.limits import DEFAULT_PEAK_FACTOR

F = TypeVar("F", bound=Callable[..., Any])
T = TypeVar("T")

UNIT_CHOICES = tuple(units.RATE_UNITS)


#: The option of each library argument whose flag is not ``--`` + its name with dashes.
FLAGS = {"yield_target": "--yield", "profile_id": "--id", "rates": "--rate-range",
         "profiles": "--profile", "sensors": "--sensor"}


def flag(argument: str) -> str:
    """The command-line option of a library argument: ``per_decade`` → ``--per-decade``."""
    return FLAGS.get(argument, "--" + argument.replace("_", "-"))


def as_option(exc: GyrovibError) -> GyrovibError:
    """A library error that names arguments, worded with the options that set them
    (``samples=10: …`` → ``--samples 10: …``, a located problem's ``{fs}`` → ``--fs``);
    any other error as it is. The one place arguments become options."""
    if isinstance(exc, OptionError) and exc.template is not None:
        # placed at a file (one recording among several), it stays placed there
        file = exc.problems[0].file if exc.problems else None
        worded = exc.worded(flag, head=True)
        return OptionError(worded if file is None else Problem(worded, file))
    if not any(p.template is not None for p in exc.problems):
        return exc
    return GyrovibError(tuple(p.worded(flag) for p in exc.problems))


def option_words(argument: str, value: object) -> str:
    """A library argument as the option that sets it, with the value a note gives it:
    ``breakpoints`` → ``--breakpoints``, ``strict=True`` → ``--strict``,
    ``accel_unit='g'`` → ``--accel-unit g``."""
    if value is None or value is True:
        return flag(argument)
    return f"{flag(argument)} {value}"


def as_options(result: T) -> T:
    """``result`` with each note it carries (:class:`~gyrovib.errors.Note`: in its fields,
    their tuples, lists and dicts, and the results they hold) worded with the options
    (:func:`option_words`): what the command line prints and writes names its options,
    as :func:`as_option` does for errors. What holds no note is returned as it is."""
    return cast(T, _worded(result))


def _worded(value: Any) -> Any:
    if isinstance(value, Note):
        return value.worded(option_words)
    if type(value) in (tuple, list):
        items = [_worded(item) for item in value]
        same = all(new is old for new, old in zip(items, value, strict=True))
        return value if same else type(value)(items)
    if isinstance(value, dict):
        worded = {key: _worded(item) for key, item in value.items()}
        return value if all(worded[k] is v for k, v in value.items()) else worded
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return _worded_fields(value)
    return value


def _worded_fields(result: Any) -> Any:
    """A dataclass with the fields that hold notes replaced (:func:`_worded`)."""
    changed = {f.name: new for f in dataclasses.fields(result) if f.init
               and (new := _worded(getattr(result, f.name))) is not getattr(result, f.name)}
    return dataclasses.replace(result, **changed) if changed else result


#: Where ``--bundled`` leaves its choice for :func:`gyrovib.cli.common.load_catalog`.
BUNDLED_KEY = "gyrovib.bundled"


def _keep_bundled(ctx: click.Context, param: click.Parameter, value: str | None) -> None:
    if value is not None:
        ctx.meta[BUNDLED_KEY] = value


def bundled_option(f: F) -> F:
    return click.option(
        "--bundled", type=click.Choice(["sensors", "profiles", "all"]), default=None,
        expose_value=False, callback=_keep_bundled, is_eager=True,
        help="Add the bundled catalogues (the public sensors, the example profiles, or "
             "both) to the files given: e.g. your own profiles with --bundled sensors. "
             "`gyrovib catalog export DIR` writes them out for editing.")(f)


def files_argument(f: F) -> F:
    return bundled_option(click.argument("files", nargs=-1, metavar="[FILE]...")(f))


def selection_options(f: F) -> F:
    f = click.option("--profile", "profiles", multiple=True, metavar="ID",
                     help="Only this profile (repeatable).")(f)
    f = click.option("--sensor", "sensors", multiple=True, metavar="ID",
                     help="Only this sensor (repeatable).")(f)
    return f


def unit_option(f: F) -> F:
    return click.option(
        "--unit", default="deg/s", show_default=True, metavar="UNIT",
        help=f"Rate unit of every output value: {', '.join(UNIT_CHOICES)}.",
    )(f)


def budget_unit_option(f: F) -> F:
    """``--unit`` of the commands with a budget: it defaults to the budget's own unit."""
    return click.option(
        "--unit", default=None, metavar="UNIT",
        help=f"Rate unit of every output value: {', '.join(UNIT_CHOICES)}. Default: the "
             "unit --budget is written in (36deg/h: deg/h), else deg/s; a bare --budget "
             "and --rate are read in it.",
    )(f)


def resolve_unit(unit: str | None, budget: str | None) -> str:
    """``--unit`` as given, else the unit ``--budget`` carries, else deg/s (README, "Units")."""
    if unit is not None:
        return units.canonical_unit(unit)
    return (None if budget is None else units.quantity_unit(budget)) or "deg/s"


def peak_factor_option(f: F) -> F:
    return click.option(
        "--peak-factor", "peak_factor", type=click.FloatRange(min=0.0), default=DEFAULT_PEAK_FACTOR,
        show_default=True, metavar="K",
        help="κ of the saturation check (docs/model.md section 9): a sensor saturates when "
             "|Ω_K3| + Σ tone amplitudes + locked-harmonic peaks + κ·σ3, at its nonlinear "
             "element, exceeds its range.",
    )(f)


def rate_option(f: F) -> F:
    return click.option(
        "--rate", metavar="R",
        help="Override the carrier rate: Ω_K3 as one number, or Ω_K1,Ω_K2,Ω_K3; each "
             "in --unit unless it carries its own (e.g. 36deg/h).",
    )(f)


def output_option(f: F) -> F:
    return click.option("--output", "-o", metavar="PATH",
                        help="Write to PATH (atomically) instead of standard output.")(f)


def format_option(*choices: str) -> Callable[[F], F]:
    def decorate(f: F) -> F:
        return click.option(
            "--format", "fmt", type=click.Choice(choices), default=choices[0],
            show_default=True, help="Output format.",
        )(f)

    return decorate


def parse_rate_option(text: str | None, unit: str) -> list[float] | None:
    """``--rate`` in ``unit`` → list of deg/s values (1 or 3 of them)."""
    if text is None:
        return None
    pieces = [p for p in text.replace(" ", "").split(",")]
    if len(pieces) not in (1, 3) or any(not p for p in pieces):
        raise OptionError(f"--rate {text!r}: give one number (Ω_K3) or three, comma-separated")
    try:
        return [units.quantity(p, unit) for p in pieces]
    except OptionError as exc:
        raise OptionError(f"--rate: {exc.problems[0].message}") from None


def positive_rate(option: str, text: str, unit: str, what: str) -> float:
    """A rate option's value in deg/s (a number in ``unit`` or with its own unit); > 0."""
    try:
        return units.quantity(text, unit, positive=True)
    except units.NotPositive:
        raise OptionError(f"{option} {text!r}: {what} must be positive") from None
    except OptionError as exc:
        raise OptionError(f"{option}: {exc.problems[0].message}") from None


def parse_budget(text: str, unit: str) -> float:
    """``--budget`` → Δ*_V in deg/s; must be positive and finite."""
    return positive_rate("--budget", text, unit, "the budget")


def budget_option(f: F) -> F:
    return click.option(
        "--budget", required=True, metavar="B",
        help="Δ*_V, the allowed vibration error: a number in --unit, or with a unit "
             "(36deg/h, '0.01 deg/s').",
    )(f)


def method_option(f: F) -> F:
    return click.option(
        "--method", type=click.Choice(["exact", "paper"]), default="exact", show_default=True,
        help="exact: exact moments and derived shares; paper: the paper's printed formulas "
             "and constants.",
    )(f)


def allocation_option(f: F) -> F:
    return click.option(
        "--allocation", metavar="r[,w1..w5[,w6],v1..v3]",
        help="How the budget is split (eq. 18, 21, 24): r alone, or r and the weights "
             "w (A1, k2, k4, m31, m32[, g² term of a linear vibration, default 1]) and v "
             "(Ω, Ω², Ω³ terms), comma-separated. Default: the catalogue's 'allocation:', "
             "else the paper's 1.5,1,1,1,0.5,0.5,1,0.5,0.5.",
    )(f)


def parse_allocation(text: str | None) -> list[float] | None:
    """``--allocation`` → r alone, the 9 numbers r, w1..w5, v1..v3 or the 10 numbers
    r, w1..w6, v1..v3 (w6: the g² term, docs/model.md section 8), positive and finite."""
    if text is None:
        return None
    pieces = [p.strip() for p in text.split(",")]
    values: list[float] = []
    for piece in pieces:
        try:
            value = float(piece)
        except ValueError:
            raise OptionError(f"--allocation {text!r}: {piece!r} is not a number") from None
        if not (math.isfinite(value) and value > 0):
            raise OptionError(f"--allocation {text!r}: every value must be positive and finite")
        values.append(value)
    if len(values) not in (1, 9, 10):
        raise OptionError(
            f"--allocation {text!r}: give r alone, 9 numbers r,w1,...,w5,v1,v2,v3 or 10 "
            f"numbers r,w1,...,w6,v1,v2,v3 (got {len(values)})"
        )
    return values


def budget_options(f: F) -> F:
    """``--budget``, ``--method``, ``--rate``, ``--unit`` (from the budget) and
    ``--allocation``, in that order: the options of a budget split (select, bounds,
    report); :func:`budget_arguments` turns them into the library's arguments."""
    for option in (allocation_option, budget_unit_option, rate_option, method_option,
                   budget_option):
        f = option(f)
    return f


def budget_arguments(budget: str, unit: str | None, rate: str | None,
                     allocation: str | None) -> dict[str, Any]:
    """The values of :func:`budget_options` as the library takes them: ``unit`` (given,
    else the budget's), ``rate`` and ``budget`` in that unit, and ``allocation``."""
    unit = resolve_unit(unit, budget)
    return {"unit": unit, "rate": parse_rate_option(rate, unit),
            "budget": parse_budget(budget, unit), "allocation": parse_allocation(allocation)}


def placement_option(f: F) -> F:
    return click.option(
        "--placement", metavar="P",
        help="How the sensor sits in the vehicle (profiles are in vehicle axes X, Y, Z; "
             "docs/model.md section 12): x1=+Y,x2=+Z,x3=+X (a rotation), or triad (x3 on +X, "
             "+Y and +Z in turn). Default x1=+X,x2=+Y,x3=+Z.",
    )(f)


def parse_placement(text: str | None) -> Any:
    """``--placement`` → a :class:`gyrovib.core.placement.Placement`, the triad's tuple,
    or None (the one parser: :func:`gyrovib.core.placement.parse`)."""
    if text is None:
        return None
    # lazy: this module is loaded by --help, which must not load numpy
    from gyrovib.core.placement import parse

    try:
        return parse(text)
    except ValueError as exc:
        raise OptionError(f"--placement {text!r}: {exc}") from None


def parse_angle_budget(text: str) -> float:
    """``--angle-budget`` (``0.5deg``, ``2 mrad``) → θ* in radians; positive, finite."""
    # lazy: this module is loaded by --help, which must not load numpy
    from gyrovib.api.commands.mission import angle_in_rad

    try:
        return angle_in_rad(text)
    except ValueError as exc:
        raise OptionError(f"--angle-budget {text!r}: {exc}") from None
