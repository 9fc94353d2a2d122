"""What the models say of the value at a path of a catalogue file: its allowed
keys, choices, bounds' hints and lengths. Messages read these here rather than
repeating them (see :mod:`gyrovib.catalog.messages`)."""

from __future__ import annotations

import types
from collections.abc import Sequence
from typing import Annotated, Any, Literal, NamedTuple, Union, get_args, get_origin

from annotated_types import MaxLen, MinLen
from pydantic import BaseModel

from gyrovib.models._types import TAGS, Hint, Named
from gyrovib.models.catalogue import Catalogue

__all__ = ["TAGS", "Node", "at", "fields"]


class Node(NamedTuple):
    """What is known of the value at a path."""

    #: The words a choice allows (empty if not a choice) and what they are called.
    choices: tuple[str, ...] = ()
    what: str = ""
    #: Appended to an out-of-bounds message.
    hint: str = ""
    #: (fewest, most) values of a list of variable length, when both are set.
    lengths: tuple[int, int] | None = None
    #: How many values a fixed-length list holds (0: not one).
    size: int = 0


def _leaves(t: Any, meta: list[Any]) -> list[tuple[Any, list[Any]]]:
    """The types a value of ``t`` may be (unions and ``Annotated`` unwrapped), each
    with the metadata met on the way."""
    origin = get_origin(t)
    if origin is Annotated:
        inner, *extra = get_args(t)
        return _leaves(inner, [*meta, *extra])
    if origin is Union or isinstance(t, types.UnionType):
        return [leaf for a in get_args(t) for leaf in _leaves(a, meta)]
    return [(t, meta)]


def _root() -> list[tuple[Any, list[Any]]]:
    return [(Catalogue, [])]


def _step(leaves: list[tuple[Any, list[Any]]], part: Any) -> list[tuple[Any, list[Any]]]:
    out: list[tuple[Any, list[Any]]] = []
    for t, _ in leaves:
        if isinstance(t, type) and issubclass(t, BaseModel) and isinstance(part, str):
            field = t.model_fields.get(part)
            if field is not None:
                out += _leaves(field.annotation, list(field.metadata))
        elif get_origin(t) is list and isinstance(part, int):
            out += _leaves(get_args(t)[0], [])
        elif get_origin(t) is tuple and isinstance(part, int):
            args = get_args(t)
            if len(args) == 2 and args[1] is Ellipsis:
                out += _leaves(args[0], [])
            elif 0 <= part < len(args):
                out += _leaves(args[part], [])
    return out


def _walk(loc: Sequence[Any]) -> list[tuple[Any, list[Any]]]:
    leaves = _root()
    for part in loc:
        if part in TAGS:
            continue
        leaves = _step(leaves, part)
    return leaves


def fields(loc: Sequence[Any]) -> tuple[str, ...]:
    """The keys the mapping at ``loc`` may hold."""
    for t, _ in _walk(loc):
        if isinstance(t, type) and issubclass(t, BaseModel):
            return tuple(t.model_fields)
    return ()


def _words(meta: list[Any], what: str, hint: str) -> tuple[str, str]:
    """The first name (:class:`Named`) and hint (:class:`Hint`) met, ``meta`` after the
    ones already found."""
    for m in meta:
        if isinstance(m, Named):
            what = what or m.what
        elif isinstance(m, Hint):
            hint = hint or m.text
    return what, hint


def _lengths(t: Any, meta: list[Any]) -> tuple[int, int] | None:
    """(fewest, most) values of a tuple of variable length, when both are set."""
    low = next((m.min_length for m in meta if isinstance(m, MinLen)), None)
    high = next((m.max_length for m in meta if isinstance(m, MaxLen)), None)
    if low is not None and high is not None and get_origin(t) is tuple:
        return (low, high)
    return None


def at(loc: Sequence[Any]) -> Node:
    """What the models say of the value at ``loc``."""
    choices: tuple[str, ...] = ()
    what = hint = ""
    lengths = None
    size = 0
    for t, meta in _walk(loc):
        args = get_args(t)
        if get_origin(t) is tuple and Ellipsis not in args:
            size = size or len(args)
        if get_origin(t) is Literal:
            choices += tuple(str(a) for a in get_args(t))
        what, hint = _words(meta, what, hint)
        lengths = _lengths(t, meta) or lengths
    return Node(choices, what, hint, lengths, size)
