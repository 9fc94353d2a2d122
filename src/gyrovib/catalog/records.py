"""The validated catalogue as plain records, and the fast validator that builds them.

:mod:`gyrovib.catalog.schema` (pydantic) is the authority on the format: it
gives the JSON Schema and, for a file that is not valid, the located messages.
Importing pydantic and building its models costs more than the rest of a
``gyrovib analyze`` run on a small catalogue, so a *valid* file is checked
and built here instead, in plain Python, without pydantic.

The fast validator applies the same rules; it is conservative: it returns
records only for data it is certain the schema accepts, with the values the
schema would produce (ints as floats, pairs and triples as tuples, defaults
filled in). On anything else, an error or just something unusual (a huge
integer, an input type YAML does not produce), it raises :class:`Unsure` and
the loader falls back to pydantic, which either accepts the data or explains
what is wrong. ``tests/test_records.py`` checks the two agree.

The records have the attributes and methods of the pydantic models of the
same names (``rate_coefficients``, ``to_coefficients``, ``model_dump``), and
are immutable.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from typing import Any, ClassVar, TypeVar

R = TypeVar("R", bound="Record")

RATE_UNITS = ("deg/s", "deg/h", "rad/s", "rpm")
MAX_TABLE = 100_000
MAX_TONES = 64
MAX_TEXT = 10_000
MAX_ID = 200
#: Integers beyond this are left to pydantic (it decides whether they convert).
_MAX_EXACT_INT = 2**53

_ID = re.compile(r"[A-Za-z0-9._-]+")


def breakpoint_problem(table: list[tuple[float, float]]) -> tuple[int, str] | None:
    """The first row that breaks the order of a breakpoint table, with a message.

    Frequencies must increase; one repeat (a step) is allowed, not three in a row.
    """
    for i in range(1, len(table)):
        f0, f1 = table[i - 1][0], table[i][0]
        if f1 < f0:
            return i, (f"breakpoint frequencies must increase: {f1:g} Hz follows {f0:g} Hz "
                       "(sort the rows by frequency)")
        if f1 == f0 and i >= 2 and table[i - 2][0] == f0:
            return i, f"frequency {f0:g} Hz appears more than twice (a step uses two rows)"
    return None


def psd_has_band(table: list[tuple[float, float]]) -> bool:
    """Whether a PSD table spans a band (two different frequencies at least)."""
    return table[0][0] != table[-1][0]


def check_breakpoints(table: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """``table`` itself, or :class:`ValueError` when :func:`breakpoint_problem` finds one."""
    problem = breakpoint_problem(table)
    if problem is not None:
        raise ValueError(problem[1])
    return table


# ------------------------------------------------------------------ records


class Record:
    """An immutable record: its fields live in ``__dict__``, set once."""

    _defaults: ClassVar[dict[str, Any]] = {}

    def __init__(self, **values: Any) -> None:
        unknown = set(values) - set(self._defaults)
        if unknown:
            raise TypeError(f"{type(self).__name__}: unknown field(s) {sorted(unknown)}")
        object.__setattr__(self, "__dict__", {**self._defaults, **values})

    @classmethod
    def _make(cls: type[R], values: dict[str, Any]) -> R:
        """A record from already validated, complete values (no copy, no checks)."""
        record = object.__new__(cls)
        object.__setattr__(record, "__dict__", values)
        return record

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} is immutable")

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f"{type(self).__name__} is immutable")

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return self.__dict__ == other.__dict__

    def __hash__(self) -> int:
        return hash((type(self), tuple(_freeze(v) for v in self.__dict__.values())))

    def __repr__(self) -> str:
        fields = ", ".join(f"{k}={v!r}" for k, v in self.__dict__.items())
        return f"{type(self).__name__}({fields})"

    def model_dump(self) -> dict[str, Any]:
        """Nested plain data, as pydantic's ``model_dump()`` gives it."""
        return {k: _dump(v) for k, v in self.__dict__.items()}


def _freeze(value: Any) -> Any:
    return tuple(_freeze(v) for v in value) if isinstance(value, list) else value


def _dump(value: Any) -> Any:
    if isinstance(value, Record):
        return value.model_dump()
    if isinstance(value, list):
        return [_dump(v) for v in value]
    if isinstance(value, tuple):
        return tuple(_dump(v) for v in value)
    return value


Pair = tuple[float, float]
Triple = tuple[float, float, float]


class Units(Record):
    rate: str
    _defaults: ClassVar[dict[str, Any]] = {"rate": "deg/s"}


_COEFFICIENTS = ("k0", "k1", "A1", "k2", "k3", "k4", "k5", "m1", "m2", "m31", "m32")
_OUTPUT = ("K1", "K0", "A1", "K2", "K3", "K4", "K5", "M1", "M2", "M31", "M32")


class Coefficients(Record):
    """Eq. (2), in rate units: an omitted coefficient is 0, except ``k1 = 1``."""

    k0: float
    k1: float
    A1: float
    k2: float
    k3: float
    k4: float
    k5: float
    m1: float
    m2: float
    m31: float
    m32: float
    _defaults: ClassVar[dict[str, Any]] = {**dict.fromkeys(_COEFFICIENTS, 0.0), "k1": 1.0}


class OutputCoefficients(Record):
    """Eq. (1), in output units per rate unit; divided by ``K1`` to give eq. (2)."""

    unit: str | None
    K1: float
    K0: float
    A1: float
    K2: float
    K3: float
    K4: float
    K5: float
    M1: float
    M2: float
    M31: float
    M32: float
    _defaults: ClassVar[dict[str, Any]] = {"unit": None, **dict.fromkeys(_OUTPUT, 0.0)}

    def to_coefficients(self) -> Coefficients:
        """``k0 = K0/K1``, ``kn = Kn/K1``, ``mi = Mi/K1``, ``m3i = M3i/K1``; k1 = 1."""
        k = self.K1
        return Coefficients._make({
            "k0": self.K0 / k, "k1": 1.0, "A1": self.A1, "k2": self.K2 / k,
            "k3": self.K3 / k, "k4": self.K4 / k, "k5": self.K5 / k, "m1": self.M1 / k,
            "m2": self.M2 / k, "m31": self.M31 / k, "m32": self.M32 / k,
        })


class Sensor(Record):
    """One angular-rate sensor: its conversion function and, optionally, ν_sensor(f)."""

    id: str
    name: str | None
    vendor: str | None
    part: str | None
    notes: str | None
    range: float | None
    coefficients: Coefficients | None
    output_coefficients: OutputCoefficients | None
    response: list[Pair] | None
    _defaults: ClassVar[dict[str, Any]] = {
        "id": None, "name": None, "vendor": None, "part": None, "notes": None, "range": None,
        "coefficients": None, "output_coefficients": None, "response": None,
    }

    @property
    def rate_coefficients(self) -> Coefficients:
        """The eq. (2) coefficients, whichever form the file used."""
        if self.coefficients is not None:
            return self.coefficients
        assert self.output_coefficients is not None
        return self.output_coefficients.to_coefficients()


class Tone(Record):
    frequency: float
    amplitude: Triple
    phase: Triple
    _defaults: ClassVar[dict[str, Any]] = {
        "frequency": None, "amplitude": None, "phase": (0.0, 0.0, 0.0),
    }


class PSD(Record):
    x1: list[Pair] | None
    x2: list[Pair] | None
    x3: list[Pair] | None
    _defaults: ClassVar[dict[str, Any]] = {"x1": None, "x2": None, "x3": None}


class Random(Record):
    psd: PSD | None
    rms: Triple | None
    coherence: Pair
    _defaults: ClassVar[dict[str, Any]] = {"psd": None, "rms": None, "coherence": (1.0, 1.0)}


class Profile(Record):
    id: str
    name: str | None
    notes: str | None
    rate: Triple
    harmonic: list[Tone]
    random: Random | None
    mount: list[Pair] | None
    _defaults: ClassVar[dict[str, Any]] = {
        "id": None, "name": None, "notes": None, "rate": (0.0, 0.0, 0.0), "harmonic": [],
        "random": None, "mount": None,
    }


class Allocation(Record):
    """How the budget is split (eq. 18, 21, 24): ratio r and share weights w, v."""

    r: float
    w: tuple[float, float, float, float, float]
    v: Triple
    _defaults: ClassVar[dict[str, Any]] = {
        "r": 1.5, "w": (1.0, 1.0, 1.0, 0.5, 0.5), "v": (1.0, 0.5, 0.5),
    }


class CatalogFile(Record):
    gyrovib: int
    units: Units
    sensors: list[Sensor]
    profiles: list[Profile]
    allocation: Allocation | None
    _defaults: ClassVar[dict[str, Any]] = {
        "gyrovib": 1, "units": Units(), "sensors": [], "profiles": [], "allocation": None,
    }


# ------------------------------------------------------------------ the fast validator


class Unsure(Exception):
    """The fast validator does not vouch for the data: let pydantic decide."""


def _number(x: Any) -> float:
    t = type(x)
    if t is float:
        if x - x == 0.0:  # false for NaN and ±inf
            return x  # type: ignore[no-any-return]
    elif t is int and -_MAX_EXACT_INT <= x <= _MAX_EXACT_INT:
        return float(x)
    raise Unsure


def _positive(x: Any) -> float:
    v = _number(x)
    if v > 0.0:
        return v
    raise Unsure


def _non_negative(x: Any) -> float:
    v = _number(x)
    if v >= 0.0:
        return v
    raise Unsure


def _coherence(x: Any) -> float:
    v = _number(x)
    if -1.0 <= v <= 1.0:
        return v
    raise Unsure


def _text(x: Any) -> str | None:
    if x is None or (type(x) is str and len(x) <= MAX_TEXT):
        return x
    raise Unsure


def _identifier(x: Any) -> str:
    if type(x) is str and len(x) <= MAX_ID and _ID.fullmatch(x):
        return x
    raise Unsure


def _fixed(x: Any, n: int, item: Callable[[Any], float]) -> tuple[float, ...]:
    if type(x) in (list, tuple) and len(x) == n:
        return tuple(item(v) for v in x)
    raise Unsure


def _table(x: Any) -> list[Pair] | None:
    if x is None:
        return None
    if type(x) not in (list, tuple) or not 1 <= len(x) <= MAX_TABLE:
        raise Unsure
    out: list[Pair] = []
    for point in x:
        if type(point) not in (list, tuple) or len(point) != 2:
            raise Unsure
        out.append((_positive(point[0]), _non_negative(point[1])))
    try:
        return check_breakpoints(out)
    except ValueError:
        raise Unsure from None


def _mapping(x: Any, cls: type[Record], required: tuple[str, ...] = ()) -> dict[str, Any]:
    """``x`` as a dict of ``cls``'s fields only, with the required ones present."""
    if type(x) is not dict or not x.keys() <= cls._defaults.keys():
        raise Unsure
    for key in required:
        if key not in x:
            raise Unsure
    return x


def _optional(x: Any, build: Callable[[Any], Any]) -> Any:
    return None if x is None else build(x)


def _numbers(x: dict[str, Any], cls: type[Record]) -> dict[str, Any]:
    values = dict(cls._defaults)
    for key, value in x.items():
        values[key] = _number(value)
    return values


def _coefficients(x: Any) -> Coefficients:
    return Coefficients._make(_numbers(_mapping(x, Coefficients), Coefficients))


def _output_coefficients(x: Any) -> OutputCoefficients:
    x = _mapping(x, OutputCoefficients, ("K1",))
    unit = _text(x.get("unit"))
    values = _numbers({k: v for k, v in x.items() if k != "unit"}, OutputCoefficients)
    values["unit"] = unit
    k1 = values["K1"]
    if k1 == 0.0 or not all(math.isfinite(v / k1) for k, v in values.items()
                            if k not in ("unit", "A1", "K1")):
        raise Unsure
    return OutputCoefficients._make(values)


def _sensor(x: Any) -> Sensor:
    x = _mapping(x, Sensor, ("id",))
    get = x.get
    coefficients = _optional(get("coefficients"), _coefficients)
    output = _optional(get("output_coefficients"), _output_coefficients)
    if (coefficients is None) == (output is None):
        raise Unsure
    return Sensor._make({
        "id": _identifier(x["id"]),
        "name": _text(get("name")),
        "vendor": _text(get("vendor")),
        "part": _text(get("part")),
        "notes": _text(get("notes")),
        "range": _optional(get("range"), _positive),
        "coefficients": coefficients,
        "output_coefficients": output,
        "response": _table(get("response")),
    })


def _tone(x: Any) -> Tone:
    x = _mapping(x, Tone, ("frequency", "amplitude"))
    return Tone._make({
        "frequency": _positive(x["frequency"]),
        "amplitude": _fixed(x["amplitude"], 3, _non_negative),
        "phase": _fixed(x["phase"], 3, _number) if "phase" in x else (0.0, 0.0, 0.0),
    })


def _psd(x: Any) -> PSD:
    x = _mapping(x, PSD)
    tables = {axis: _table(x.get(axis)) for axis in ("x1", "x2", "x3")}
    present = [t for t in tables.values() if t is not None]
    if not present or not all(psd_has_band(t) for t in present):
        raise Unsure
    return PSD._make(tables)


def _random(x: Any) -> Random:
    x = _mapping(x, Random)
    psd = _optional(x.get("psd"), _psd)
    rms = _optional(x.get("rms"), lambda v: _fixed(v, 3, _non_negative))
    if (psd is None) == (rms is None):
        raise Unsure
    coherence = _fixed(x["coherence"], 2, _coherence) if "coherence" in x else (1.0, 1.0)
    return Random._make({"psd": psd, "rms": rms, "coherence": coherence})


def _profile(x: Any) -> Profile:
    x = _mapping(x, Profile, ("id",))
    get = x.get
    harmonic = get("harmonic", [])
    if type(harmonic) not in (list, tuple) or len(harmonic) > MAX_TONES:
        raise Unsure
    return Profile._make({
        "id": _identifier(x["id"]),
        "name": _text(get("name")),
        "notes": _text(get("notes")),
        "rate": _fixed(x["rate"], 3, _number) if "rate" in x else (0.0, 0.0, 0.0),
        "harmonic": [_tone(t) for t in harmonic],
        "random": _optional(get("random"), _random),
        "mount": _table(get("mount")),
    })


def _allocation(x: Any) -> Allocation:
    x = _mapping(x, Allocation)
    values = dict(Allocation._defaults)
    if "r" in x:
        values["r"] = _positive(x["r"])
    if "w" in x:
        values["w"] = _fixed(x["w"], 5, _positive)
    if "v" in x:
        values["v"] = _fixed(x["v"], 3, _positive)
    return Allocation._make(values)


def _units(x: Any) -> Units:
    x = _mapping(x, Units)
    rate = x.get("rate", "deg/s")
    if type(rate) is not str or rate not in RATE_UNITS:
        raise Unsure
    return Units._make({"rate": rate})


def _list(x: Any) -> list[Any] | tuple[Any, ...]:
    if type(x) in (list, tuple):
        return x  # type: ignore[no-any-return]
    raise Unsure


def catalog_file(data: Any) -> CatalogFile:
    """Validate parsed YAML and build the records, or raise :class:`Unsure`."""
    x = _mapping(data, CatalogFile, ("gyrovib",))
    version = x["gyrovib"]
    if type(version) is not int or version != 1:
        raise Unsure
    get = x.get
    try:
        return CatalogFile._make({
            "gyrovib": 1,
            "units": _units(x["units"]) if "units" in x else Units(),
            "sensors": [_sensor(s) for s in _list(get("sensors", []))],
            "profiles": [_profile(p) for p in _list(get("profiles", []))],
            "allocation": _optional(get("allocation"), _allocation),
        })
    except (TypeError, KeyError, AttributeError, OverflowError, RecursionError):
        raise Unsure from None
