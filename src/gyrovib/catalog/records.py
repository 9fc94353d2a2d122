"""The validated catalogue as plain, immutable records.

Each record class has the fields of the mapping of the same name in
:data:`gyrovib.catalog.spec.FORMAT` (its defaults come from there), as
attributes, with a few derived views (``Sensor.rate_coefficients``,
``OutputCoefficients.to_coefficients``). Numbers are floats, fixed-length
lists tuples, breakpoint tables lists of ``(f, value)`` tuples; values are in
the file's own units (conversion happens in :mod:`gyrovib.api`).

:func:`catalog_file` validates parsed YAML and builds the records in one pass
(:mod:`gyrovib.catalog.validate`), or raises :class:`Invalid`.
"""

from __future__ import annotations

from typing import Any, ClassVar, TypeVar

from gyrovib.catalog import spec
from gyrovib.catalog.spec import MAX_TONES, RATE_UNITS  # noqa: F401  (re-exported)
from gyrovib.catalog.validate import Invalid, Validator

R = TypeVar("R", bound="Record")


class Record:
    """An immutable record: its fields live in ``__dict__``, set once."""

    _defaults: ClassVar[dict[str, Any]] = {}

    def __init_subclass__(cls) -> None:
        cls._defaults = spec.defaults(cls.__name__) if cls.__name__ in spec.FORMAT else {}

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


class PSD(Record):
    x1: list[Pair] | None
    x2: list[Pair] | None
    x3: list[Pair] | None


class Random(Record):
    psd: PSD | None
    rms: Triple | None
    coherence: Pair


class Profile(Record):
    id: str
    name: str | None
    notes: str | None
    rate: Triple
    harmonic: list[Tone]
    random: Random | None
    mount: list[Pair] | None


class Allocation(Record):
    """How the budget is split (eq. 18, 21, 24): ratio r and share weights w, v."""

    r: float
    w: tuple[float, float, float, float, float]
    v: Triple


class CatalogFile(Record):
    gyrovib: int
    units: Units
    sensors: list[Sensor]
    profiles: list[Profile]
    allocation: Allocation | None

    @property
    def rate_unit(self) -> str:
        """The unit of every rate in the file (``units.rate``)."""
        return self.units.rate




#: Record classes by the name of their mapping in the spec.
RECORDS: dict[str, type[Record]] = {
    cls.__name__: cls for cls in (Units, Coefficients, OutputCoefficients, Sensor, Tone, PSD,
                                  Random, Profile, Allocation, CatalogFile)
}

CatalogFile._defaults["units"] = Units()

_VALIDATOR = Validator(builders={name: cls._make for name, cls in RECORDS.items()})


def catalog_file(data: Any) -> CatalogFile:
    """Validate parsed YAML and build the records, or raise :class:`Invalid`."""
    return _VALIDATOR(data)  # type: ignore[no-any-return]


__all__ = ["Invalid", "catalog_file", *RECORDS]
