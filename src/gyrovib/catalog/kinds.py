"""The vocabulary the catalogue format is written in: value types, fields,
mappings and rules (see :mod:`gyrovib.catalog.spec` for the format itself).

Each is an immutable named tuple (cheap to define at start-up; change one
with ``._replace``).

No ``from __future__ import annotations`` here: with it, ``typing.NamedTuple``
turns every field annotation into a ``ForwardRef``, which compiles the string
(44 compilations, ~2 ms of every start-up); evaluated, the annotations cost
nothing."""

from collections.abc import Callable
from typing import Any, NamedTuple

#: Most rows of a breakpoint table.
MAX_TABLE = 100_000
#: Longest free text.
MAX_TEXT = 10_000
#: Longest id.
MAX_ID = 200
#: What an id may hold.
ID_PATTERN = r"^[A-Za-z0-9._-]+$"


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


#: Default of a field that must be given.
REQUIRED: Any = _Required()


class _Expanded:
    def __repr__(self) -> str:
        return "EXPANDED"


#: Default of an object field: the object with all of its own defaults.
EXPANDED: Any = _Expanded()


# ------------------------------------------------------------------ value types


class Number(NamedTuple):
    """A finite float (an integer is accepted and converted); optional bounds."""

    minimum: float | None = None
    exclusive_minimum: bool = False
    maximum: float | None = None
    #: Appended to an out-of-bounds message.
    hint: str = ""


class Integer(NamedTuple):
    """An integer (not a float, not a boolean), optionally ``>= minimum``."""

    minimum: int | None = None


class Version(NamedTuple):
    """The format version: the integer ``value``."""

    value: int


class Text(NamedTuple):
    """Free text, at most ``max_length`` characters."""

    max_length: int = MAX_TEXT


class Identifier(NamedTuple):
    """An id: :data:`ID_PATTERN`, 1 to :data:`MAX_ID` characters."""

    pattern: str = ID_PATTERN
    max_length: int = MAX_ID


class Choice(NamedTuple):
    """One word of ``values``; ``what`` names it in messages ("rate unit")."""

    values: tuple[str, ...]
    what: str = ""


class Fixed(NamedTuple):
    """A list of exactly ``n`` values of one type (a triple, a pair...), or of ``n`` to
    ``most`` values when ``most`` is given."""

    n: int
    item: Any
    most: int | None = None


class Table(NamedTuple):
    """Breakpoints ``[[f Hz > 0, value >= 0], ...]``, frequencies increasing
    (a repeated frequency is a step); ``band``: at least two distinct frequencies."""

    band: bool = False
    max_rows: int = MAX_TABLE


class Ref(NamedTuple):
    """A mapping described by ``FORMAT[name]``."""

    name: str


class ListOf(NamedTuple):
    """A list of ``item``, at most ``max_length`` long; ``unique``: a key of the
    items whose values must differ."""

    item: Any
    max_length: int | None = None
    unique: str | None = None
    min_length: int = 0


class Either(NamedTuple):
    """One of several types, chosen by the kind of value written: the first
    option whose YAML kind (mapping, list, text, number) matches is used."""

    options: tuple[Any, ...]


class Field(NamedTuple):
    """One key of a mapping."""

    name: str
    type: Any
    default: Any = None
    #: ``null`` is accepted and means "not given" (for optional fields).
    nullable: bool = False
    description: str = ""
    #: The kind of unit the value is in: "rate", "acceleration", "Hz", "deg", ...
    unit: str = ""


class Group(NamedTuple):
    """Among ``fields``, exactly one (or, ``at_least``, one or more) non-null."""

    fields: tuple[str, ...]
    message: str
    at_least: bool = False
    #: Whether none at all is allowed (then it is "at most one").
    optional: bool = False


class FieldCheck(NamedTuple):
    """A rule on one valid field: ``test(value)`` gives a message (or
    ``(message, row)`` pointing at a row) when broken, else None; ``schema``:
    what JSON Schema can say of it."""

    field: str
    test: Callable[[Any], Any]
    schema: dict[str, Any] | None = None


class Check(NamedTuple):
    """A rule on a whole valid mapping: ``test(values)`` gives a message or None.
    ``at``: the field the message is placed at (default: the mapping); ``raw``:
    ``test`` sees the mapping as written (no defaults filled in); ``schema``:
    what JSON Schema can say of it (None: it cannot)."""

    test: Callable[[dict[str, Any]], str | None]
    at: str | None = None
    raw: bool = False
    schema: dict[str, Any] | None = None


class Object(NamedTuple):
    """A mapping: its fields and the rules across them."""

    description: str
    fields: tuple[Field, ...]
    groups: tuple[Group, ...] = ()
    field_checks: tuple[FieldCheck, ...] = ()
    checks: tuple[Check, ...] = ()

    def field(self, name: str) -> Field | None:
        for f in self.fields:
            if f.name == name:
                return f
        return None
