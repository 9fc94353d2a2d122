"""A base for frozen dataclasses that makes them cheaper to define.

``@dataclass(frozen=True)`` compiles six methods for every class (``__init__``,
``__repr__``, ``__eq__``, ``__hash__``, ``__setattr__``, ``__delattr__``), about
0.6 ms a class, and a first ``gyrovib analyze`` defines some twenty of them.
A subclass of :class:`Frozen` declared
``@dataclass(frozen=True, eq=False, repr=False)`` compiles only the first and the
last two; :class:`Frozen` gives the other three once for all classes, with the
behaviour the generated ones have: the same fields compared (``compare=True``),
hashed (``hash``, else ``compare``) and shown (``repr=True``), the same text.

>>> from dataclasses import dataclass, field
>>> @dataclass(frozen=True, eq=False, repr=False)
... class Point(Frozen):
...     x: float
...     y: float = field(default=0.0, compare=False)
>>> Point(1.0, 2.0)
Point(x=1.0, y=2.0)
>>> Point(1.0, 2.0) == Point(1.0, 3.0), hash(Point(1.0)) == hash((1.0,))
(True, True)
"""

from __future__ import annotations

import dataclasses
from reprlib import recursive_repr
from typing import Any


def _compared(value: Any) -> tuple[Any, ...]:
    return tuple(getattr(value, f.name) for f in dataclasses.fields(value) if f.compare)


class Frozen:
    """``__eq__``, ``__hash__`` and ``__repr__`` as ``@dataclass(frozen=True)`` writes them."""

    __slots__ = ()

    def __eq__(self, other: object) -> bool:
        if other.__class__ is self.__class__:
            return _compared(self) == _compared(other)
        return NotImplemented

    def __hash__(self) -> int:
        return hash(tuple(getattr(self, f.name) for f in dataclasses.fields(self)  # type: ignore[arg-type]
                          if (f.compare if f.hash is None else f.hash)))

    @recursive_repr()
    def __repr__(self) -> str:
        shown = ", ".join(f"{f.name}={getattr(self, f.name)!r}"
                          for f in dataclasses.fields(self) if f.repr)  # type: ignore[arg-type]
        return f"{self.__class__.__qualname__}({shown})"
