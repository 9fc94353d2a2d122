"""A vibration profile: the carrier's rate, harmonic tones, phase-locked
harmonics, the random part, the mount and the linear vibration. Values are in
the file's units."""

from typing import Annotated, Any, ClassVar, Literal

from pydantic import AfterValidator, BeforeValidator, Field, Strict, Tag, model_validator

from gyrovib.models._types import (
    FREE_TEXT,
    ID_TEXT,
    RATE,
    AccelerationMagnitude,
    AsInteger,
    BandTable,
    Group,
    Hint,
    Identifier,
    Magnitude,
    Model,
    Named,
    Number,
    SignedMagnitude,
    Table,
    Text,
    Triple,
    by_kind,
    groups_schema,
    in_unit,
    one_of,
    raise_at,
    rule_error,
)

#: Most harmonic tones (or harmonic orders, or locked groups) of one profile.
MAX_TONES = 64
#: The highest order n of a phase-locked harmonic.
MAX_ORDER = 64
ORDER_WHY = (f" (the highest order is {MAX_ORDER}: the exact evaluation of a locked group "
             "samples the fundamental's period finely enough for its highest order, so its "
             "cost grows with that order)")

NonNegativeTriple = tuple[Magnitude, Magnitude, Magnitude]
AccelerationTriple = tuple[AccelerationMagnitude, AccelerationMagnitude, AccelerationMagnitude]
Coherence = Annotated[Number, Field(ge=-1, le=1), Hint(" (a coherence lies in [-1, 1])")]


def correlation_problem(r12: float, r13: float, r23: float) -> str | None:
    """Why [[1, r12, r13], [r12, 1, r23], [r13, r23, 1]] is no correlation matrix, or None.

    With every |r| <= 1 the 2×2 minors are >= 0, so the matrix is positive
    semi-definite exactly when its determinant is >= 0 (to rounding)."""
    det = 1.0 + 2.0 * r12 * r13 * r23 - r12 * r12 - r13 * r13 - r23 * r23
    if det >= -1e-12:
        return None
    return (f"the matrix [[1, {r12:g}, {r13:g}], [{r12:g}, 1, {r23:g}], [{r13:g}, {r23:g}, 1]] "
            f"is not a valid correlation matrix: it is not positive semi-definite (determinant "
            f"{det:.3g} < 0), so no three signals have these coherences (e.g. if two pairs "
            "are fully correlated, the third pair is too)")


def _phase() -> Any:
    return Field((0.0, 0.0, 0.0), description="Phase per axis, degrees.",
                 json_schema_extra=in_unit("deg"))


class Tone(Model):
    """One harmonic tone of eq. (3): per-axis amplitude (rate) and phase (degrees)."""

    frequency: Annotated[Number, Field(gt=0)] = Field(
        description="Frequency in Hz; > 0.", json_schema_extra=in_unit("Hz"))
    amplitude: NonNegativeTriple = Field(
        description=f"Amplitude per axis x1, x2, x3, {RATE}; >= 0.",
        json_schema_extra=in_unit("rate"))
    phase: Triple = _phase()


def _psd_axis(axis: str, shown: str, kind: str) -> Any:
    return Field(None, description=f"[[f Hz, S {shown}], ...] for axis {axis}; "
                 "left out means none.", json_schema_extra=in_unit(f"{kind}^2/Hz"))


_AXES = (Group(("x1", "x2", "x3"), "give the PSD of at least one axis (x1, x2 or x3)",
               at_least=True),)


class PSD(Model):
    """Per-axis PSD breakpoints, rate²/Hz; an axis left out has none."""

    x1: BandTable | None = _psd_axis("x1", "rate²/Hz", "rate")
    x2: BandTable | None = _psd_axis("x2", "rate²/Hz", "rate")
    x3: BandTable | None = _psd_axis("x3", "rate²/Hz", "rate")

    model_config = Model.model_config | {"json_schema_extra": groups_schema(*_AXES)}
    check_one_of: ClassVar[Any] = one_of(*_AXES)


_RANDOM = (Group(("psd", "rms"),
                 "give the random part as 'psd' or as 'rms', exactly one of them"),)


class Random(Model):
    """The Gaussian broadband part: a PSD or the RMS per axis at the sensor."""

    psd: PSD | None = Field(
        None, description="PSD breakpoints per axis, rate²/Hz, log-log interpolated.")
    rms: NonNegativeTriple | None = Field(
        None, description=f"RMS per axis at the sensor, {RATE}; no spectrum, "
        "so ν(f) does not apply.", json_schema_extra=in_unit("rate"))
    coherence: Annotated[tuple[Coherence, ...], Field(min_length=2, max_length=3)] = Field(
        (1.0, 1.0), description="Coherences ρ31, ρ32 and optionally ρ12 (docs/model.md section "
        "12; default ρ31·ρ32), each in [-1, 1]; default 1.")

    model_config = Model.model_config | {"json_schema_extra": groups_schema(*_RANDOM)}
    check_one_of: ClassVar[Any] = one_of(*_RANDOM)

    @model_validator(mode="after")
    def _correlation(self) -> "Random":
        """ρ31, ρ32 and ρ12 (the third value, or ρ31·ρ32) form a correlation matrix."""
        values = tuple(self.coherence)
        r31, r32 = values[0], values[1]
        r12 = values[2] if len(values) > 2 else r31 * r32
        problem = correlation_problem(r12, r31, r32)
        if problem is not None:
            raise_at(("coherence",), rule_error(problem),
                     list(values), "Random")
        return self


# ---------------------------------------------------------------- locked harmonics


def _whole_word(value: Any) -> Any:
    """``[worst, 0, 0]``: the word stands for the whole list."""
    if isinstance(value, (list, tuple)):
        for i, x in enumerate(value):
            if x == "worst" and type(x) is str:
                raise_at((i,), rule_error(
                    f"{x!r} stands for the whole list: write the word {x} alone, "
                    "or 3 numbers"), x, "phase")
    return value


PhaseOrWorst = Annotated[
    Annotated[Triple, Tag("<list>")]
    | Annotated[Annotated[Literal["worst"], Named("phase")], Tag("<text>")],
    by_kind("list or text"), BeforeValidator(_whole_word)]


class Order(Model):
    """One harmonic of a locked group: ``phase`` is a triple (degrees) or ``"worst"``."""

    order: Annotated[int, Strict(), Field(ge=1, le=MAX_ORDER), Hint(ORDER_WHY), AsInteger] = Field(
        description=f"The harmonic number n (frequency n·f0); an integer from 1 to {MAX_ORDER}.")
    amplitude: NonNegativeTriple = Field(
        description=f"Amplitude per axis x1, x2, x3, {RATE}; >= 0.",
        json_schema_extra=in_unit("rate"))
    phase: PhaseOrWorst = Field(
        (0.0, 0.0, 0.0), description="Phase per axis in degrees, or the word worst: the "
        "worst case over the relative phases.", json_schema_extra=in_unit("deg"))

    @property
    def worst_phase(self) -> bool:
        """Whether the phases are unknown and the worst case is asked for."""
        return self.phase == "worst"


def _orders_once(orders: list[Order]) -> list[Order]:
    seen: dict[int, int] = {}
    for i, o in enumerate(orders):
        if o.order in seen:
            raise_at((i, "order"), rule_error(
                f"order {o.order!r} is given twice (first as item {seen[o.order] + 1})"),
                o.order, "orders")
        seen[o.order] = i
    return orders


class Harmonics(Model):
    """One group of phase-locked harmonics: orders of one fundamental."""

    fundamental: Annotated[Number, Field(gt=0)] = Field(
        description="Fundamental frequency f0 in Hz; > 0.", json_schema_extra=in_unit("Hz"))
    orders: Annotated[list[Order], Field(min_length=1, max_length=MAX_TONES),
                      AfterValidator(_orders_once)] = Field(
        description="The harmonics n·f0, each order once.")


def _as_list(value: Harmonics | list[Harmonics]) -> list[Harmonics]:
    return [value] if isinstance(value, Harmonics) else value


HarmonicsForm = Annotated[
    Annotated[Harmonics, Tag("<mapping>")]
    | Annotated[list[Harmonics], Field(max_length=MAX_TONES), Tag("<list>")],
    by_kind("mapping or list"), AfterValidator(_as_list)]


# ---------------------------------------------------------------- linear vibration


class AccelerationTone(Model):
    """One harmonic tone of the acceleration."""

    frequency: Annotated[Number, Field(gt=0)] = Field(
        description="Frequency in Hz; > 0.", json_schema_extra=in_unit("Hz"))
    amplitude: AccelerationTriple = Field(
        description="Amplitude per axis x1, x2, x3, in units.acceleration; >= 0.",
        json_schema_extra=in_unit("acceleration"))
    phase: Triple = _phase()


class AccelerationPSD(Model):
    """Per-axis acceleration PSD breakpoints, (units.acceleration)²/Hz."""

    x1: BandTable | None = _psd_axis("x1", "g²/Hz", "acceleration")
    x2: BandTable | None = _psd_axis("x2", "g²/Hz", "acceleration")
    x3: BandTable | None = _psd_axis("x3", "g²/Hz", "acceleration")

    model_config = Model.model_config | {"json_schema_extra": groups_schema(*_AXES)}
    check_one_of: ClassVar[Any] = one_of(*_AXES)


_ACCELERATION_RANDOM = (Group(("psd", "rms"), "give the random acceleration as 'psd' or as "
                              "'rms', exactly one of them"),)


class AccelerationRandom(Model):
    """The Gaussian broadband part of the acceleration."""

    psd: AccelerationPSD | None = Field(
        None, description="PSD breakpoints per axis, acceleration²/Hz.")
    rms: AccelerationTriple | None = Field(
        None, description="RMS per axis, in units.acceleration.",
        json_schema_extra=in_unit("acceleration"))
    coherence: tuple[Coherence, Coherence, Coherence] = Field(
        (0.0, 0.0, 0.0), description="Coherences ρ12, ρ13, ρ23, each in [-1, 1]; default 0 "
        "(independent axes).")

    model_config = Model.model_config | {
        "json_schema_extra": groups_schema(*_ACCELERATION_RANDOM)}
    check_one_of: ClassVar[Any] = one_of(*_ACCELERATION_RANDOM)

    @model_validator(mode="after")
    def _correlation(self) -> "AccelerationRandom":
        """ρ12, ρ13, ρ23 form a correlation matrix."""
        problem = correlation_problem(*self.coherence)
        if problem is not None:
            raise_at(("coherence",), rule_error(problem), list(self.coherence),
                     "AccelerationRandom")
        return self


class Acceleration(Model):
    """Linear vibration at the sensor's axes, in the file's acceleration unit."""

    harmonic: Annotated[list[AccelerationTone], Field(max_length=MAX_TONES)] = Field(
        [], description="Harmonic tones of the acceleration, zero or more.")
    random: AccelerationRandom | None = Field(
        None, description="Gaussian broadband acceleration: a PSD or the RMS per axis.")
    mount: Table | None = Field(
        None, description="Mount transmissibility for the linear vibration "
        "[[f Hz, gain], ...]; default: the profile's mount.")


# ---------------------------------------------------------------- the profile


class Profile(Model):
    """One vibration environment with the carrier's own rate Ω_K.

    ``harmonics``: the phase-locked groups, a list (one group written alone is a
    list of one; read it typed through ``harmonic_groups``); ``acceleration``:
    the linear vibration in units.acceleration, or None.
    """

    id: Identifier = Field(description=ID_TEXT)
    name: Text | None = Field(None, description=FREE_TEXT)
    notes: Text | None = Field(None, description=FREE_TEXT)
    rate: tuple[SignedMagnitude, SignedMagnitude, SignedMagnitude] = Field(
        (0.0, 0.0, 0.0), description=f"Carrier rate Ω_K about x1, x2, x3, {RATE}.",
        json_schema_extra=in_unit("rate"))
    harmonic: Annotated[list[Tone], Field(max_length=MAX_TONES)] = Field(
        [], description="Harmonic tones of eq. (3), zero or more.")
    random: Random | None = Field(
        None, description="Gaussian broadband vibration: a PSD or the RMS per axis.")
    mount: Table | None = Field(
        None, description="Isolation-mount transmissibility ν(f): [[f Hz, gain], ...].")
    harmonics: HarmonicsForm | None = Field(
        None, description="Phase-locked harmonics of one source (docs/model.md section 10): "
        "one group, or a list of groups.")
    acceleration: Acceleration | None = Field(
        None, description="Linear vibration at the sensor's axes (docs/model.md section 8).")
    not_recorded: Annotated[list[Literal["x1", "x2", "x3", "acceleration"]],
                            Field(max_length=4)] = Field(
        [], description="What the recording this profile was fitted from did not record "
        "(docs/model.md section 13): unknown, not 0, so an error that depends on it is "
        "unknown and its verdict unverified.")

    @model_validator(mode="after")
    def _groups_listed(self) -> "Profile":
        """``harmonics`` is a list of groups, also when one group or none was written."""
        if not isinstance(self.harmonics, list):
            self.__dict__["harmonics"] = [] if self.harmonics is None else [self.harmonics]
        return self

    @property
    def harmonic_groups(self) -> list[Harmonics]:
        """The phase-locked groups, a list (empty when none)."""
        h = self.harmonics
        return [] if h is None else [h] if isinstance(h, Harmonics) else h
