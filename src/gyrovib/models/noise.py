"""A sensor's noise figures (docs/model.md section 15): the ``noise:`` block.

Each figure is written as a bare number in its default unit, as a text with its
unit and, where the datasheet says so, its qualifier (``"0.12 deg/sqrt(h) typ"``,
``"8 °/h"``), or as a mapping ``{value, unit, qualifier}``; once validated it is a
:class:`NoiseFigure` (a bare number gets the default unit and no qualifier).
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
    """One noise figure with its unit and, where the datasheet gives one, its qualifier."""

    value: NoiseValue = Field(description="The value, in unit; >= 0.")
    unit: str = Field(description="Its unit (see the figure for the units allowed).")
    qualifier: Annotated[Qualifier, Named("qualifier")] | None = Field(
        None, description="The datasheet's qualifier: typ (typical) or max (guaranteed).")


def _unit_pattern(figure: str) -> str:
    return "|".join(re.escape(u) for u in NOISE_UNITS[figure])


def _text_pattern(figure: str) -> str:
    return rf"^ *({NUMBER_TEXT}) *({_unit_pattern(figure)}) *(?: +(typ|max))? *$"


def _reader(figure: str) -> Any:
    pattern = re.compile(_text_pattern(figure))
    units = NOISE_UNITS[figure]

    def read_text(value: str) -> NoiseFigure:
        match = pattern.match(value)
        if match is None:
            raise rule_error(
                f"cannot read {value!r} as the {WHAT[figure]}: write a number, a unit and "
                f"optionally typ or max, e.g. '{_example(figure)}' (units: "
                + ", ".join(units) + ")")
        return NoiseFigure(value=float(match.group(1)), unit=match.group(2),
                           qualifier=match.group(3))

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
        "mapping {value, unit, qualifier}"))
    unit_schema = {"type": "string", "enum": list(NOISE_UNITS[figure])}
    return Annotated[
        Annotated[NoiseValue, AfterValidator(from_number), Tag("<number>"),
                  WithJsonSchema({"type": "number", "minimum": 0,
                                  "maximum": MAX_MAGNITUDE})]
        | Annotated[str, Strict(), AfterValidator(read_text), Tag("<text>"),
                    WithJsonSchema({"type": "string", "pattern": _text_pattern(figure)})]
        | Annotated[NoiseFigure, AfterValidator(check_unit), Tag("<mapping>"),
                    WithJsonSchema({"type": "object", "additionalProperties": False,
                                    "required": ["value", "unit"],
                                    "properties": {
                                        "value": {"type": "number", "minimum": 0,
                                                  "maximum": MAX_MAGNITUDE},
                                        "unit": unit_schema,
                                        "qualifier": {"enum": ["typ", "max"]}}})],
        kinds]


def _field(figure: str, text: str) -> Any:
    return Field(None, description=f"{text} A number in {default_unit(figure)}, or with its "
                 "unit (" + ", ".join(NOISE_UNITS[figure]) + ") and optionally typ/max: "
                 f"'{_example(figure)}' or {{value, unit, qualifier}}. Omitted: unknown, "
                 "never 0.")


class Noise(Model):
    """The noise figures of a sensor at rest (docs/model.md section 15); each omitted one
    is unknown."""

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

    @model_validator(mode="after")
    def _something(self) -> "Noise":
        if all(getattr(self, name) is None for name in WHAT):
            raise rule_error("a noise block gives at least one of " + ", ".join(WHAT)
                             + " (an empty block says nothing: leave it out)")
        return self

    def figures(self) -> dict[str, NoiseFigure | None]:
        """Each figure as validated (None: not given, unknown)."""
        return {name: getattr(self, name) for name in WHAT}

