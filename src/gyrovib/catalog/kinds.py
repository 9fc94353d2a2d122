"""The vocabulary the catalogue format is written in: value types, fields,
mappings and rules (see :mod:`gyrovib.catalog.spec` for the format itself)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

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


@dataclass(frozen=True)
class Number:
    """A finite float (an integer is accepted and converted); optional bounds."""

    minimum: float | None = None
    exclusive_minimum: bool = False
    maximum: float | None = None
    #: Appended to an out-of-bounds message.
    hint: str = ""


@dataclass(frozen=True)
class Integer:
    """An integer (not a float, not a boolean), optionally ``>= minimum``."""

    minimum: int | None = None


@dataclass(frozen=True)
class Version:
    """The format version: the integer ``value``."""

    value: int


@dataclass(frozen=True)
class Text:
    """Free text, at most ``max_length`` characters."""

    max_length: int = MAX_TEXT


@dataclass(frozen=True)
class Identifier:
    """An id: :data:`ID_PATTERN`, 1 to :data:`MAX_ID` characters."""

    pattern: str = ID_PATTERN
    max_length: int = MAX_ID


@dataclass(frozen=True)
class Choice:
    """One word of ``values``; ``what`` names it in messages ("rate unit")."""

    values: tuple[str, ...]
    what: str = ""


@dataclass(frozen=True)
class Fixed:
    """A list of exactly ``n`` values of one type (a triple, a pair...)."""

    n: int
    item: Any


@dataclass(frozen=True)
class Table:
    """Breakpoints ``[[f Hz > 0, value >= 0], ...]``, frequencies increasing
    (a repeated frequency is a step); ``band``: at least two distinct frequencies."""

    band: bool = False
    max_rows: int = MAX_TABLE


@dataclass(frozen=True)
class Ref:
    """A mapping described by ``FORMAT[name]``."""

    name: str


@dataclass(frozen=True)
class ListOf:
    """A list of ``item``, at most ``max_length`` long; ``unique``: a key of the
    items whose values must differ."""

    item: Any
    max_length: int | None = None
    unique: str | None = None
    min_length: int = 0


@dataclass(frozen=True)
class Either:
    """One of several types, chosen by the kind of value written: the first
    option whose YAML kind (mapping, list, text, number) matches is used."""

    options: tuple[Any, ...]


@dataclass(frozen=True)
class Field:
    name: str
    type: Any
    default: Any = None
    #: ``null`` is accepted and means "not given" (for optional fields).
    nullable: bool = False
    description: str = ""
    #: The kind of unit the value is in: "rate", "acceleration", "Hz", "deg", ...
    unit: str = ""


@dataclass(frozen=True)
class Group:
    """Among ``fields``, exactly one (or, ``at_least``, one or more) non-null."""

    fields: tuple[str, ...]
    message: str
    at_least: bool = False
    #: Whether none at all is allowed (then it is "at most one").
    optional: bool = False


@dataclass(frozen=True)
class FieldCheck:
    """A rule on one valid field: ``test(value)`` gives a message (or
    ``(message, row)`` pointing at a row) when broken, else None; ``schema``:
    what JSON Schema can say of it."""

    field: str
    test: Callable[[Any], Any]
    schema: dict[str, Any] | None = None


@dataclass(frozen=True)
class Check:
    """A rule on a whole valid mapping: ``test(values)`` gives a message or None.
    ``at``: the field the message is placed at (default: the mapping); ``raw``:
    ``test`` sees the mapping as written (no defaults filled in); ``schema``:
    what JSON Schema can say of it (None: it cannot)."""

    test: Callable[[dict[str, Any]], str | None]
    at: str | None = None
    raw: bool = False
    schema: dict[str, Any] | None = None


@dataclass(frozen=True)
class Object:
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
