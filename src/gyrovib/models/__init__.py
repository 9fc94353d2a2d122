"""The catalogue format as pydantic models: the one definition of every key a
catalogue file may hold, with its type, bounds, default, unit and description,
and the rules across keys (exactly one of a group, K1 ≠ 0, ...).

>>> from gyrovib.models import Catalogue, Sensor
>>> s = Sensor(id="s", coefficients={"k2": 1e-4})
>>> s.rate_coefficients.k2
0.0001

Values are in the file's own units (``units.rate``, ``units.acceleration``);
:mod:`gyrovib.api` converts them. A catalogue file is validated in one call
(:func:`validate_document`); :mod:`gyrovib.catalog` reads the YAML and turns
the errors into located messages; :mod:`gyrovib.models.schema` writes the
models' JSON Schema for editors (draft-07).

Models are frozen, closed (an unknown key is an error) and strict where YAML
could be coerced wrongly: a number is a float or an integer, never a boolean
or a text such as ``"1e3"``.
"""

from __future__ import annotations

from typing import Any

from pydantic import ValidationError

from gyrovib.models._types import TAGS
from gyrovib.models.catalogue import VERSION, Allocation, Catalogue, Units
from gyrovib.models.mission import AxisPlacement, Mission, Segment
from gyrovib.models.noise import Noise, NoiseFigure
from gyrovib.models.profile import (
    MAX_TONES,
    PSD,
    Acceleration,
    AccelerationPSD,
    AccelerationRandom,
    AccelerationTone,
    Harmonics,
    Order,
    Profile,
    Random,
    Tone,
)
from gyrovib.models.sensor import (
    Asymmetry,
    Coefficients,
    G2Quantity,
    G2Sensitivity,
    Lot,
    Nonlinearity,
    OutputCoefficients,
    Response,
    Sensor,
    Specs,
)
from gyrovib.models.uncertainty import Sigmas, Uncertainty

__all__ = [
    "MAX_TONES",
    "PSD",
    "VERSION",
    "Acceleration",
    "AccelerationPSD",
    "AccelerationRandom",
    "AccelerationTone",
    "Allocation",
    "Asymmetry",
    "AxisPlacement",
    "Catalogue",
    "Coefficients",
    "G2Quantity",
    "G2Sensitivity",
    "Harmonics",
    "Lot",
    "Mission",
    "Noise",
    "NoiseFigure",
    "Nonlinearity",
    "Order",
    "OutputCoefficients",
    "Profile",
    "Random",
    "Response",
    "Segment",
    "Sensor",
    "Sigmas",
    "Specs",
    "Tone",
    "Uncertainty",
    "Units",
    "validate_document",
]


def validate_document(data: Any) -> Catalogue:
    """Validate a whole parsed catalogue file in one call; raises
    :class:`pydantic.ValidationError` with every problem found.

    An integer beyond 64 bits is a number too when a float holds it (2**70): pydantic
    refuses it as a float, so on that refusal alone such integers are converted and
    the document validated again (the path of valid files pays nothing)."""
    try:
        return Catalogue.model_validate(data)
    except ValidationError as exc:
        big = [e["loc"] for e in exc.errors(include_url=False)
               if e["type"] == "float_type" and type(e["input"]) is int
               and _fits(e["input"])]
        if not big:
            raise
    return Catalogue.model_validate(_with_floats(data, big))


def _fits(value: int) -> bool:
    try:
        float(value)
    except OverflowError:
        return False
    return True


def _with_floats(data: Any, paths: list[tuple[Any, ...]]) -> Any:
    """``data`` with the integers at ``paths`` as floats (the containers on the way
    copied, the rest shared)."""
    def put(node: Any, path: tuple[Any, ...]) -> Any:
        if not path:
            return float(node)
        head, rest = path[0], path[1:]
        if head in TAGS:
            return put(node, rest)
        if isinstance(node, dict):
            return {**node, head: put(node[head], rest)}
        copy = list(node)
        copy[head] = put(node[head], rest)
        return copy

    for path in paths:
        data = put(data, tuple(path))
    return data
