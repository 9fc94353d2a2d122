"""gyrovib.frozen.Frozen behaves as the methods ``@dataclass(frozen=True)`` generates.

The reference is the standard library itself: each class is declared twice, once
with the generated ``__eq__``/``__hash__``/``__repr__`` and once on :class:`Frozen`,
and the two must agree on every pair of instances.
"""

from __future__ import annotations

import dataclasses
import itertools
from dataclasses import dataclass, field

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.frozen import Frozen


@dataclass(frozen=True)
class Plain:
    a: int
    b: str = "x"
    c: tuple[int, ...] = ()
    hidden: int = field(default=0, repr=False)
    ignored: int = field(default=0, compare=False)
    unhashed: int = field(default=0, hash=False)
    hashed_only: int = field(default=0, compare=False, hash=True)


@dataclass(frozen=True, eq=False, repr=False)
class Based(Frozen):
    a: int
    b: str = "x"
    c: tuple[int, ...] = ()
    hidden: int = field(default=0, repr=False)
    ignored: int = field(default=0, compare=False)
    unhashed: int = field(default=0, hash=False)
    hashed_only: int = field(default=0, compare=False, hash=True)


@dataclass(frozen=True, eq=False, repr=False)
class Child(Based):
    d: float = 0.5


@dataclass(frozen=True, eq=False, repr=False)
class Holder(Frozen):
    inner: object = None


VALUES = st.tuples(st.integers(-2, 2), st.sampled_from(["x", "y"]),
                   st.lists(st.integers(0, 2), max_size=2).map(tuple),
                   st.integers(0, 1), st.integers(0, 1), st.integers(0, 1), st.integers(0, 1))


@settings(deadline=None, max_examples=200)
@given(VALUES, VALUES)
def test_eq_hash_repr_as_the_generated_methods(left: tuple, right: tuple) -> None:
    p1, p2, b1, b2 = Plain(*left), Plain(*right), Based(*left), Based(*right)
    assert (b1 == b2) is (p1 == p2)
    assert (b1 != b2) is (p1 != p2)
    assert hash(b1) == hash(p1)
    assert repr(b1) == repr(p1).replace("Plain(", "Based(", 1)


def test_other_classes_are_not_equal_and_children_compare_their_own_fields() -> None:
    # the generated __eq__ compares instances of exactly the same class only
    assert Based(1) != Plain(1)
    assert Based(1) != Child(1)
    assert Child(1, d=0.5) == Child(1) != Child(1, d=1.0)
    assert repr(Child(1)) == "Child(a=1, b='x', c=(), ignored=0, unhashed=0, hashed_only=0, d=0.5)"


def test_frozen_and_recursive_repr() -> None:
    b = Based(1)
    with pytest.raises(dataclasses.FrozenInstanceError):
        b.a = 2  # type: ignore[misc]
    loop = Holder([])
    loop.inner.append(loop)  # type: ignore[union-attr]
    assert repr(loop) == "Holder(inner=[...])"


def test_the_library_classes_stay_frozen_value_objects() -> None:
    from gyrovib.errors import Problem

    a, b = Problem("bad", "f.yaml", 3, 4), Problem("bad", "f.yaml", 3, 4)
    assert a == b and hash(a) == hash(b) and len({a, b}) == 1
    for left, right in itertools.permutations([a, Problem("other", "f.yaml", 3, 4)], 2):
        assert left != right
    with pytest.raises(dataclasses.FrozenInstanceError):
        a.message = "x"  # type: ignore[misc]
