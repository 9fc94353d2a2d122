"""A mission: an ordered list of flight segments, each under one profile for a
duration, with how the sensor sits in the vehicle (docs/model.md section 12).

Profiles are given in vehicle axes X, Y, Z; a mission's ``placement`` maps each
sensor axis x1, x2, x3 to a signed vehicle axis (a proper rotation: the
determinant of the signed permutation is +1), or is ``triad`` (the three
placements of an IMU, x3 on +X, +Y and +Z). Values are in the file's units.
"""

import math
import re
from typing import Annotated, Any, Literal

from pydantic import BeforeValidator, Field, Tag, WithJsonSchema, model_validator

from gyrovib.models._types import (
    FREE_TEXT,
    ID_TEXT,
    RATE,
    Identifier,
    Model,
    Named,
    Number,
    Text,
    Triple,
    by_kind,
    in_unit,
    rule_error,
)

#: Most segments of one mission.
MAX_SEGMENTS = 10_000
#: The longest plausible segment, in years: a duration beyond it (e.g. 1e300 s, longer
#: than the age of the universe) is read, with a warning that it is probably a typo.
MAX_DURATION_YEARS = 100
#: :data:`MAX_DURATION_YEARS` in seconds (Julian years of 365.25 days).
MAX_DURATION = MAX_DURATION_YEARS * 365.25 * 86400.0
#: Seconds per duration unit a segment may be written in.
DURATION_UNITS = {"s": 1.0, "sec": 1.0, "min": 60.0, "h": 3600.0}
_DURATION = re.compile(r"^\s*([0-9]*\.?[0-9]+(?:[eE][+-]?[0-9]+)?)\s*(s|sec|min|h)\s*$")
_DURATION_SCHEMA = {
    "description": "Duration of the segment: a number of seconds, or a text with s, min "
    "or h ('10 min', '2 h'); > 0.",
    "anyOf": [{"type": "number", "exclusiveMinimum": 0},
              {"type": "string", "pattern": _DURATION.pattern}],
}

SignedAxis = Annotated[Literal["+X", "-X", "+Y", "-Y", "+Z", "-Z"], Named("signed axis")]


def _seconds(value: Any) -> Any:
    """``"10 min"`` → 600.0; a number is kept (its bounds are checked after)."""
    if type(value) is not str:
        return value
    m = _DURATION.match(value)
    if m is None:
        raise rule_error(f"cannot read the duration {value!r}: write a number of seconds, "
                         "or a number with s, min or h ('90 s', '10 min', '2 h')")
    seconds = float(m.group(1)) * DURATION_UNITS[m.group(2)]
    if not math.isfinite(seconds) or seconds <= 0:
        raise rule_error(f"the duration {value!r} must be positive and finite")
    return seconds


Duration = Annotated[Number, Field(gt=0), BeforeValidator(_seconds),
                     WithJsonSchema(_DURATION_SCHEMA)]


class AxisPlacement(Model):
    """Each sensor axis on a signed vehicle axis; a rotation (determinant +1)."""

    x1: SignedAxis = Field(description="The vehicle axis sensor axis x1 lies on: +X … -Z.")
    x2: SignedAxis = Field(description="The vehicle axis sensor axis x2 lies on: +X … -Z.")
    x3: SignedAxis = Field(description="The vehicle axis the sensitive axis x3 lies on: "
                           "+X … -Z.")

    @model_validator(mode="after")
    def _rotation(self) -> "AxisPlacement":
        axes = [a[1] for a in (self.x1, self.x2, self.x3)]
        if len(set(axes)) != 3:
            raise rule_error("a placement puts the three sensor axes on three different "
                             f"vehicle axes, not {self.x1}, {self.x2}, {self.x3}")
        if self.determinant != 1:
            raise rule_error(
                f"the placement x1: {self.x1}, x2: {self.x2}, x3: {self.x3} has determinant "
                "-1: it is a mirror image, not a rotation a sensor can be mounted in "
                "(flip the sign of one more axis, or swap two axes)")
        return self

    @property
    def determinant(self) -> int:
        """+1 or −1: the sign of the permutation times the product of the signs."""
        source = ["XYZ".index(a[1]) for a in (self.x1, self.x2, self.x3)]
        inversions = sum(1 for i in range(3) for j in range(i + 1, 3) if source[i] > source[j])
        sign = 1 if inversions % 2 == 0 else -1
        for a in (self.x1, self.x2, self.x3):
            sign *= -1 if a[0] == "-" else 1
        return sign

    def __str__(self) -> str:
        return f"x1={self.x1},x2={self.x2},x3={self.x3}"


PlacementForm = Annotated[
    Annotated[AxisPlacement, Tag("<mapping>")]
    | Annotated[Annotated[Literal["triad"], Named("placement")], Tag("<text>")],
    by_kind("mapping or text")]


class Segment(Model):
    """One segment of a mission: a profile for a duration, optionally at another rate."""

    profile: Identifier = Field(description="The id of the profile flown in this segment "
                                "(from any file given).")
    duration: Duration = Field(description="Duration: a number of seconds, or a text with "
                               "s, min or h ('10 min', '2 h'); > 0.",
                               json_schema_extra=in_unit("s"))
    rate: Triple | None = Field(None, description=f"Carrier rate Ω_K about X, Y, Z, {RATE}; "
                                "overrides the profile's own.",
                                json_schema_extra=in_unit("rate"))


class Mission(Model):
    """A sequence of segments flown in order (docs/model.md section 12)."""

    id: Identifier = Field(description=ID_TEXT)
    name: Text | None = Field(None, description=FREE_TEXT)
    notes: Text | None = Field(None, description=FREE_TEXT)
    placement: PlacementForm | None = Field(
        None, description="How the sensor sits in the vehicle: {x1: +Y, x2: +Z, x3: +X} (a "
        "rotation), or triad (x3 on +X, +Y and +Z in turn); default x1 = +X, x2 = +Y, "
        "x3 = +Z.")
    segments: Annotated[list[Segment], Field(min_length=1, max_length=MAX_SEGMENTS)] = Field(
        description="The segments, in the order flown.")

    @property
    def placement_text(self) -> str:
        """The placement as ``gyrovib --placement`` reads it: ``triad``, ``default`` or
        ``x1=+Y,x2=+Z,x3=+X``."""
        p = self.placement
        if p is None:
            return "default"
        return p if isinstance(p, str) else str(p)
