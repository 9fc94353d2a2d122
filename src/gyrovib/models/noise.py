"""A sensor's noise figures (docs/model.md section 15): the ``noise:`` block.

Each figure is written as a bare number in its default unit, as a text with its
unit and, where the datasheet says so, its qualifier (``"0.12 deg/sqrt(h) typ"``,
``"8 °/h"``), or as a mapping ``{value, unit, qualifier}``; once validated it is a
:class:`NoiseFigure` (a bare number gets the default unit and no qualifier).

A figure the measurement does not resolve is an upper **bound**: ``"≤ 0.8 deg/h/sqrt(h)"``,
``"<= 0.8 deg/h/sqrt(h)"`` or ``{bound: 0.8, unit: deg/h/sqrt(h)}`` (``gyrovib allan -o``
writes them so); the mission budget uses its bound as the figure and says so.

Where a triad's axes differ, the block holds one sub-block per axis (``x:``, ``y:``,
``z:``, each with the same figures); figures written directly under ``noise:`` hold for
every axis that does not give its own.
The units and their factors are :data:`gyrovib.units.NOISE_UNITS`;
:mod:`gyrovib.api.noise` converts them.
"""

import re
from typing import Annotated, Any, Literal

from pydantic import (
    AfterValidator,
    Discriminator,
    Field,
    Strict,
    Tag,
    WithJsonSchema,
    model_validator,
)

from gyrovib.models._types import (
    MAX_MAGNITUDE,
    NUMBER_TEXT,
    Hint,
    Model,
    Named,
    Number,
    raise_at,
    rule_error,
    value_kind,
)
from gyrovib.units import NOISE_UNITS

#: A datasheet's qualifier of a figure: typical or guaranteed maximum.
Qualifier = Literal["typ", "max"]
NOISE_WHY = " (a noise figure in its unit: beyond any gyro, and squared over a mission)"
#: A noise figure's value: >= 0 and bounded.
NoiseValue = Annotated[Number, Field(ge=0, le=MAX_MAGNITUDE), Hint(NOISE_WHY)]

#: What each figure is, for descriptions and messages.
WHAT = {
    "arw": "angle random walk N",
    "bias_instability": "bias instability B (the Allan deviation's floor / 0.664)",
    "rrw": "rate random walk K",
    "bias_repeatability": "bias repeatability R (run to run, 1σ)",
}


def default_unit(figure: str) -> str:
    """The unit a bare number of ``figure`` is read in."""
    return next(iter(NOISE_UNITS[figure]))


class NoiseFigure(Model):
    """One noise figure with its unit and, where the datasheet gives one, its qualifier;
    or an upper bound of it (``bound``, no value)."""

    value: NoiseValue | None = Field(None, description="The value, in unit; >= 0.")
    bound: NoiseValue | None = Field(
        None, description="An upper bound, in unit (instead of a value): a figure the "
                          "measurement does not resolve.")
    unit: str = Field(description="Its unit (see the figure for the units allowed).")
    qualifier: Annotated[Qualifier, Named("qualifier")] | None = Field(
        None, description="The datasheet's qualifier: typ (typical) or max (guaranteed).")

    @model_validator(mode="after")
    def _value_or_bound(self) -> "NoiseFigure":
        if (self.value is None) == (self.bound is None):
            raise rule_error("give a value or a bound (not both): {value: 0.8, unit: …} or "
                             "{bound: 0.8, unit: …}")
        return self

    @property
    def is_bound(self) -> bool:
        """Whether the figure is only an upper bound."""
        return self.bound is not None

    @property
    def upper(self) -> float:
        """The value, or the bound: what a budget uses."""
        out = self.value if self.value is not None else self.bound
        assert out is not None
        return out


def _unit_pattern(figure: str) -> str:
    return "|".join(re.escape(u) for u in NOISE_UNITS[figure])


def _text_pattern(figure: str) -> str:
    return rf"^ *(≤|<=)? *({NUMBER_TEXT}) *({_unit_pattern(figure)}) *(?: +(typ|max))? *$"


def _reader(figure: str) -> Any:
    pattern = re.compile(_text_pattern(figure))
    units = NOISE_UNITS[figure]

    def read_text(value: str) -> NoiseFigure:
        match = pattern.match(value)
        if match is None:
            raise rule_error(
                f"cannot read {value!r} as the {WHAT[figure]}: write a number, a unit and "
                f"optionally typ or max, e.g. '{_example(figure)}', or a bound such as "
                f"'≤ {_example(figure).split(' typ')[0].split(' max')[0]}' (units: "
                + ", ".join(units) + ")")
        number = float(match.group(2))
        if match.group(1):
            return NoiseFigure(bound=number, unit=match.group(3), qualifier=match.group(4))
        return NoiseFigure(value=number, unit=match.group(3), qualifier=match.group(4))

    def from_number(value: float) -> NoiseFigure:
        return NoiseFigure.model_construct(value=value, unit=default_unit(figure),
                                           qualifier=None)

    def check_unit(q: NoiseFigure) -> NoiseFigure:
        if q.unit not in units:
            raise_at(("unit",), rule_error(
                f"{q.unit!r} is not a unit of the {WHAT[figure]}: use one of "
                + ", ".join(units)), q.unit, "NoiseFigure")
        return q

    return read_text, from_number, check_unit


def _example(figure: str) -> str:
    return {"arw": "0.12 deg/sqrt(h) typ", "bias_instability": "8 deg/h",
            "rrw": "0.5 deg/h/sqrt(h)", "bias_repeatability": "20 deg/h max"}[figure]


def _figure_type(figure: str) -> Any:
    """A figure as written (number, text or mapping) → :class:`NoiseFigure`."""
    read_text, from_number, check_unit = _reader(figure)
    kinds = Discriminator(value_kind, custom_error_type="kind", custom_error_message=(
        f"a number ({default_unit(figure)}), a text such as '{_example(figure)}' or a "
        "mapping {value, unit, qualifier} (or {bound, unit})"))
    magnitude = {"type": "number", "minimum": 0, "maximum": MAX_MAGNITUDE}
    unit_schema = {"type": "string", "enum": list(NOISE_UNITS[figure])}
    return Annotated[
        Annotated[NoiseValue, AfterValidator(from_number), Tag("<number>"),
                  WithJsonSchema({"type": "number", "minimum": 0,
                                  "maximum": MAX_MAGNITUDE})]
        | Annotated[str, Strict(), AfterValidator(read_text), Tag("<text>"),
                    WithJsonSchema({"type": "string", "pattern": _text_pattern(figure)})]
        | Annotated[NoiseFigure, AfterValidator(check_unit), Tag("<mapping>"),
                    WithJsonSchema({"type": "object", "additionalProperties": False,
                                    "required": ["unit"],
                                    "oneOf": [{"required": ["value"]},
                                              {"required": ["bound"]}],
                                    "properties": {
                                        "value": magnitude, "bound": magnitude,
                                        "unit": unit_schema,
                                        "qualifier": {"enum": ["typ", "max"]}}})],
        kinds]


def _field(figure: str, text: str) -> Any:
    return Field(None, description=f"{text} A number in {default_unit(figure)}, or with its "
                 "unit (" + ", ".join(NOISE_UNITS[figure]) + ") and optionally typ/max: "
                 f"'{_example(figure)}' or {{value, unit, qualifier}}. Omitted: unknown, "
                 "never 0.")


class NoiseAxis(Model):
    """The noise figures of one axis of a triad (or of every axis: :class:`Noise`); each
    omitted one is unknown."""

    arw: _figure_type("arw") | None = _field(  # type: ignore[valid-type]
        "arw", "Angle random walk N: the Allan deviation's slope −½, read at τ = 1 s.")
    bias_instability: _figure_type("bias_instability") | None = _field(  # type: ignore[valid-type]
        "bias_instability", "Bias instability B: the Allan deviation's minimum / 0.664 "
        "(in-run bias stability).")
    rrw: _figure_type("rrw") | None = _field(  # type: ignore[valid-type]
        "rrw", "Rate random walk K: the Allan deviation's slope +½, read at τ = 3 s.")
    bias_repeatability: _figure_type("bias_repeatability") | None = _field(  # type: ignore[valid-type]
        "bias_repeatability", "Bias repeatability R: run to run, 1σ (adds R·T over a "
        "mission).")

    def figures(self) -> dict[str, NoiseFigure | None]:
        """Each figure as validated (None: not given, unknown)."""
        return {name: getattr(self, name) for name in WHAT}


def _axis_field(axis: str) -> Any:
    return Field(None, description=f"The figures of the triad's {axis} axis where they "
                 "differ from the others (the figures given directly under noise: hold "
                 "for an axis without its own).")


class Noise(NoiseAxis):
    """The noise figures of a sensor at rest (docs/model.md section 15); each omitted one
    is unknown. ``x``, ``y``, ``z``: a triad's axes where they differ."""

    x: NoiseAxis | None = _axis_field("x")
    y: NoiseAxis | None = _axis_field("y")
    z: NoiseAxis | None = _axis_field("z")

    @model_validator(mode="after")
    def _something(self) -> "Noise":
        blocks = [self] + [b for b in (self.x, self.y, self.z) if b is not None]
        if all(getattr(b, name) is None for b in blocks for name in WHAT):
            raise rule_error("a noise block gives at least one of " + ", ".join(WHAT)
                             + " (an empty block says nothing: leave it out)")
        return self

    def for_axis(self, axis: str | None) -> dict[str, NoiseFigure | None]:
        """Each figure of ``axis`` ("x", "y", "z"; its own, else the block's); for None
        (a single-axis sensor, or any axis) the block's own figure, else the largest of
        the axes' (the conservative choice)."""
        own = self.figures()
        axes = {"x": self.x, "y": self.y, "z": self.z}
        if axis is not None:
            block = axes.get(axis.lower())
            if block is None:
                return own
            return {name: fig if fig is not None else own[name]
                    for name, fig in block.figures().items()}
        out = dict(own)
        for block in axes.values():
            if block is None:
                continue
            for name, fig in block.figures().items():
                if own[name] is None and fig is not None:
                    current = out[name]
                    if current is None or _default(name, fig) > _default(name, current):
                        out[name] = fig
        return out


def _default(name: str, fig: NoiseFigure) -> float:
    return fig.upper * NOISE_UNITS[name][fig.unit]
