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
from gyrovib.errors import CatalogError

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
        """Nested plain data (mappings, lists and numbers), as the file holds it."""
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
    acceleration: str


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


class G2Sensitivity(Record):
    """Acceleration-squared sensitivity G_jk (MODEL.md section 8), rate unit per g²."""

    G11: float
    G22: float
    G33: float
    G12: float
    G13: float
    G23: float


class Nonlinearity(Record):
    """A datasheet nonlinearity (MODEL.md section 11)."""

    value: float
    unit: str
    fit: str
    measure: str
    of: str


class Asymmetry(Record):
    value: float
    unit: str


class Specs(Record):
    """A sensor given by its datasheet instead of coefficients (MODEL.md section 11).

    ``range``: R in the file's rate unit. ``nonlinearity``: :class:`Nonlinearity`,
    its ``value`` in its own ``unit`` (``"%FS"`` of R or of the span 2R as ``of``
    says, or an absolute rate in the rate unit named, not necessarily the file's).
    ``asymmetry``: :class:`Asymmetry` (``value`` in ``unit`` ``"ppm"`` or ``"%"``),
    or None. ``vre``: the bound on |G_jj|, rate per acceleration unit², or None.
    """

    range: float
    nonlinearity: Nonlinearity
    asymmetry: Asymmetry | None
    vre: float | None


class Response(Record):
    """The mapping form of ``response:`` (only while validating; see :class:`Sensor`)."""

    at: str
    table: list[Pair]


class Sensor(Record):
    """One angular-rate sensor: its conversion function and, optionally, ν_sensor(f).

    Values are in the file's own units (rates in ``units.rate``, accelerations
    in ``units.acceleration``):

    ========================= =============================================================
    attribute                 meaning
    ========================= =============================================================
    ``coefficients``          eq. (2) coefficients, or None
    ``output_coefficients``   eq. (1) coefficients, or None
    ``specs``                 :class:`Specs` (the datasheet form), or None; exactly one
                              of these three is given
    ``response``              ν_sensor(f) as ``[(f Hz, gain), ...]``, or None, whichever
                              form the file used (a bare table or ``{at, table}``)
    ``response_at``           ``"output"`` (default: no credit) or ``"input"`` (MODEL.md 9)
    ``g2_sensitivity``        :class:`G2Sensitivity` as written, or None
    ``vre``                   the ``vre:`` shorthand as written (signed), or None
    ``g2``                    (G11, G22, G33, G12, G13, G23), rate per acceleration unit²,
                              from either form; zeros when neither is given
    ========================= =============================================================
    """

    id: str
    name: str | None
    vendor: str | None
    part: str | None
    notes: str | None
    range: float | None
    coefficients: Coefficients | None
    output_coefficients: OutputCoefficients | None
    specs: Specs | None
    response: list[Pair] | None
    response_at: str
    g2_sensitivity: G2Sensitivity | None
    vre: float | None

    @property
    def g2(self) -> tuple[float, float, float, float, float, float]:
        """(G11, G22, G33, G12, G13, G23), rate per (units.acceleration)²; 0 if not given."""
        if self.g2_sensitivity is not None:
            g = self.g2_sensitivity
            return (g.G11, g.G22, g.G33, g.G12, g.G13, g.G23)
        v = 0.0 if self.vre is None else self.vre
        return (v, v, v, 0.0, 0.0, 0.0)

    @property
    def rate_coefficients(self) -> Coefficients:
        """The eq. (2) coefficients, whichever form the file used."""
        if self.coefficients is not None:
            return self.coefficients
        if self.output_coefficients is None:  # the datasheet form: no single function
            raise CatalogError(f"sensor {self.id!r} is given by its datasheet ('specs:'), "
                               "not by coefficients; it has no conversion function to use here")
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


class Order(Record):
    """One harmonic of a locked group: ``phase`` is a triple (degrees) or ``"worst"``."""

    order: int
    amplitude: Triple
    phase: Triple | str

    @property
    def worst_phase(self) -> bool:
        """Whether the phases are unknown and the worst case is asked for."""
        return self.phase == "worst"


class Harmonics(Record):
    """Phase-locked harmonics n·f0 of one source (MODEL.md section 10)."""

    fundamental: float
    orders: list[Order]


class AccelerationTone(Tone):
    """A tone of the acceleration: the fields of :class:`Tone`, amplitude in g or m/s²."""


class AccelerationPSD(PSD):
    """An acceleration PSD: the fields of :class:`PSD`, in (units.acceleration)²/Hz."""


class AccelerationRandom(Record):
    psd: AccelerationPSD | None
    rms: Triple | None
    coherence: Triple


class Acceleration(Record):
    """Linear vibration at the sensor's axes (MODEL.md section 8), in units.acceleration."""

    harmonic: list[AccelerationTone]
    random: AccelerationRandom | None
    mount: list[Pair] | None


class Profile(Record):
    """One vibration environment.

    ================ ===================================================================
    attribute        meaning (values in the file's units)
    ================ ===================================================================
    ``harmonics``    list of :class:`Harmonics` groups (a single group in the file is
                     a list of one); empty when not given
    ``acceleration`` :class:`Acceleration` (linear vibration, in units.acceleration:
                     tone amplitudes and RMS in g or m/s², PSDs in their squares per
                     Hz; coherences ρ12, ρ13, ρ23), or None
    ================ ===================================================================
    """

    id: str
    name: str | None
    notes: str | None
    rate: Triple
    harmonic: list[Tone]
    random: Random | None
    mount: list[Pair] | None
    harmonics: list[Harmonics]
    acceleration: Acceleration | None


class Allocation(Record):
    """How the budget is split (eq. 18, 21, 24): ratio r and share weights w, v."""

    r: float
    #: w1..w5, or w1..w6 with w6 the weight of the g² term (MODEL.md section 8).
    w: tuple[float, ...]
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

    @property
    def acceleration_unit(self) -> str:
        """The unit of every acceleration in the file: ``"g"`` or ``"m/s^2"``
        (``m/s2`` as written is the same unit). Values are not converted here."""
        return "m/s^2" if self.units.acceleration == "m/s2" else self.units.acceleration




#: Record classes by the name of their mapping in the spec.
RECORDS: dict[str, type[Record]] = {
    cls.__name__: cls for cls in (
        Units, Coefficients, OutputCoefficients, G2Sensitivity, Nonlinearity, Asymmetry,
        Specs, Response, Sensor, Tone, PSD, Random, Order, Harmonics, AccelerationTone,
        AccelerationPSD, AccelerationRandom, Acceleration, Profile, Allocation, CatalogFile)
}


def _sensor(values: dict[str, Any]) -> Sensor:
    """One ``response`` attribute whichever form was written, and where it acts."""
    response = values["response"]
    if isinstance(response, Response):
        values["response"], values["response_at"] = response.table, response.at
    else:
        values["response_at"] = spec.RESPONSE_AT[0]
    return Sensor._make(values)


def _profile(values: dict[str, Any]) -> Profile:
    """``harmonics`` as a list of groups, also when one group was written."""
    groups = values["harmonics"]
    values["harmonics"] = [] if groups is None else \
        [groups] if isinstance(groups, Harmonics) else groups
    return Profile._make(values)


_BUILDERS: dict[str, Any] = {name: cls._make for name, cls in RECORDS.items()}
_BUILDERS.update(Sensor=_sensor, Profile=_profile)

CatalogFile._defaults["units"] = Units()
Sensor._defaults["response_at"] = spec.RESPONSE_AT[0]
Profile._defaults["harmonics"] = []

_VALIDATOR = Validator(builders=_BUILDERS)


def catalog_file(data: Any) -> CatalogFile:
    """Validate parsed YAML and build the records, or raise :class:`Invalid`."""
    return _VALIDATOR(data)  # type: ignore[no-any-return]


__all__ = ["Invalid", "catalog_file", *RECORDS]
