"""Checking parsed YAML against the format of :mod:`gyrovib.catalog.spec`.

The spec is compiled once into one small function per type; a valid file is
then checked and built into records in one plain-Python pass (no pydantic,
nothing heavy to import). On an invalid file the same pass collects every
error as an :class:`Error` (kind, path, value, context), which
:mod:`gyrovib.catalog.messages` turns into sentences and
:mod:`gyrovib.catalog.locate` places in the file.

Numbers are strict: a float or an integer (converted), never a boolean or a
text; NaN, infinities and integers too large for a float are refused.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any, NamedTuple

from gyrovib.catalog import kinds as k
from gyrovib.catalog import spec as s


class Error(NamedTuple):
    """One broken rule: ``kind`` (see messages.py), where, the value, details."""

    kind: str
    loc: tuple[Any, ...]
    value: Any
    ctx: dict[str, Any]


class Invalid(Exception):
    """The data breaks the format; ``errors`` says how, in document order."""

    def __init__(self, errors: list[Error]) -> None:
        super().__init__(f"{len(errors)} error(s)")
        self.errors = errors


_BAD: Any = object()  # a value that failed (its errors are already recorded)
Check = Callable[[Any, tuple[Any, ...], list[Error]], Any]
_SEQUENCE = (list, tuple)


def _kind(t: Any) -> str:
    """The YAML kind a type is written as."""
    if isinstance(t, k.Ref):
        return "mapping"
    if isinstance(t, (k.Fixed, k.Table, k.ListOf)):
        return "list"
    if isinstance(t, (k.Text, k.Identifier, k.Choice)):
        return "text"
    if isinstance(t, k.Either):
        return " or ".join(_kind(o) for o in t.options)
    return "integer" if isinstance(t, (k.Integer, k.Version)) else "number"


def _value_kind(v: Any) -> str:
    if type(v) is dict:
        return "mapping"
    if type(v) in _SEQUENCE:
        return "list"
    if type(v) is str:
        return "text"
    if type(v) in (int, float):
        return "number"
    return "other"


class Validator:
    """The compiled format: call it with parsed YAML to get records."""

    def __init__(self, fmt: dict[str, k.Object] | None = None,
                 builders: dict[str, Callable[[dict[str, Any]], Any]] | None = None,
                 root: str = s.ROOT) -> None:
        self.format = s.FORMAT if fmt is None else fmt
        self.builders = builders or {}
        self._objects: dict[str, Check] = {}
        for name in self.format:
            self._objects[name] = self._object(name)
        self._root = self._objects[root]

    def __call__(self, data: Any) -> Any:
        errors: list[Error] = []
        out = self._root(data, (), errors)
        if errors:
            raise Invalid(errors)
        return out

    # ---------------------------------------------------------------- compilers

    def compile(self, t: Any) -> Check:
        method = getattr(self, "_" + type(t).__name__.lower())
        return method(t)  # type: ignore[no-any-return]

    def _number(self, t: k.Number) -> Check:
        lo, hi, excl = t.minimum, t.maximum, t.exclusive_minimum

        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            kind = type(v)
            raw = v
            if kind is float:
                if v - v != 0.0:  # NaN or an infinity
                    errors.append(Error("finite", loc, v, {}))
                    return _BAD
            elif kind is int:
                try:
                    v = float(v)
                except OverflowError:
                    errors.append(Error("finite", loc, v, {}))
                    return _BAD
            else:
                errors.append(Error("type", loc, v, {"expected": "number"}))
                return _BAD
            if lo is not None and (v <= lo if excl else v < lo):
                errors.append(Error("bound", loc, raw, {"op": ">" if excl else ">=",
                                                      "bound": lo, "hint": t.hint}))
                return _BAD
            if hi is not None and v > hi:
                errors.append(Error("bound", loc, raw, {"op": "<=", "bound": hi,
                                                        "hint": t.hint}))
                return _BAD
            return v

        return check

    def _integer(self, t: k.Integer) -> Check:
        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            if type(v) is float and v.is_integer():  # 2.0 is 2 (as in JSON Schema)
                v = int(v)
            elif type(v) is not int:
                errors.append(Error("type", loc, v, {"expected": "integer"}))
                return _BAD
            if t.minimum is not None and v < t.minimum:
                errors.append(Error("bound", loc, v, {"op": ">=", "bound": t.minimum,
                                                      "hint": ""}))
                return _BAD
            return v

        return check

    def _version(self, t: k.Version) -> Check:
        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            if type(v) is not int:
                errors.append(Error("version", loc, v, {"expected": t.value}))
                return _BAD
            return v

        return check

    def _text(self, t: k.Text) -> Check:
        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            if type(v) is not str:
                errors.append(Error("type", loc, v, {"expected": "text"}))
                return _BAD
            if len(v) > t.max_length:
                errors.append(Error("text_long", loc, v, {"max": t.max_length}))
                return _BAD
            return v

        return check

    def _identifier(self, t: k.Identifier) -> Check:
        match = re.compile(t.pattern).fullmatch

        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            if type(v) is not str:
                errors.append(Error("type", loc, v, {"expected": "text"}))
            elif not v:
                errors.append(Error("id_empty", loc, v, {}))
            elif len(v) > t.max_length:
                errors.append(Error("text_long", loc, v, {"max": t.max_length}))
            elif not match(v):
                errors.append(Error("id_pattern", loc, v, {}))
            else:
                return v
            return _BAD

        return check

    def _choice(self, t: k.Choice) -> Check:
        allowed = frozenset(t.values)

        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            if type(v) is str and v in allowed:
                return v
            errors.append(Error("choice", loc, v, {"values": t.values, "what": t.what}))
            return _BAD

        return check

    def _fixed(self, t: k.Fixed) -> Check:
        item = self.compile(t.item)
        n, most = t.n, t.n if t.most is None else t.most
        expected: int | str = n  # how many, for the message
        if most > n:
            expected = f"{n} or {most}" if most == n + 1 else f"{n} to {most}"

        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            if type(v) not in _SEQUENCE:
                errors.append(Error("type", loc, v, {"expected": "list"}))
                return _BAD
            if not n <= len(v) <= most:
                kind = "too_few" if len(v) < n else "too_many"
                errors.append(Error(kind, loc, v, {"n": expected, "have": len(v),
                                                   "exact": True}))
                return _BAD
            before = len(errors)
            out = tuple([item(x, (*loc, i), errors) for i, x in enumerate(v)])
            return out if len(errors) == before else _BAD

        return check

    def _table(self, t: k.Table) -> Check:
        frequency = self.compile(k.Number(minimum=0, exclusive_minimum=True))
        value = self.compile(k.Number(minimum=0))
        need = 1

        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            if type(v) not in _SEQUENCE:
                errors.append(Error("type", loc, v, {"expected": "list"}))
                return _BAD
            if len(v) < need:
                errors.append(Error("too_few", loc, v, {"n": need, "have": len(v)}))
                return _BAD
            if len(v) > t.max_rows:
                errors.append(Error("too_many", loc, v, {"n": t.max_rows, "have": len(v)}))
                return _BAD
            before = len(errors)
            rows = []
            for i, row in enumerate(v):
                at = (*loc, i)
                if type(row) not in _SEQUENCE:
                    errors.append(Error("type", at, row, {"expected": "list"}))
                elif len(row) != 2:
                    errors.append(Error("too_few" if len(row) < 2 else "too_many", at, row,
                                        {"n": 2, "have": len(row), "exact": True}))
                else:
                    rows.append((frequency(row[0], (*at, 0), errors),
                                 value(row[1], (*at, 1), errors)))
            if len(errors) != before:
                return _BAD
            problem = s.breakpoint_problem(rows)
            if problem is not None:
                errors.append(Error("rule", (*loc, problem[1]), v, {"message": problem[0]}))
                return _BAD
            if t.band:
                message = s.band_problem(rows)
                if message is not None:
                    errors.append(Error("rule", loc, v, {"message": message}))
                    return _BAD
            return rows

        return check

    def _listof(self, t: k.ListOf) -> Check:
        item = self.compile(t.item)

        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            if type(v) not in _SEQUENCE:
                errors.append(Error("type", loc, v, {"expected": "list"}))
                return _BAD
            if t.max_length is not None and len(v) > t.max_length:
                errors.append(Error("too_many", loc, v, {"n": t.max_length, "have": len(v)}))
                return _BAD
            if len(v) < t.min_length:
                errors.append(Error("too_few", loc, v, {"n": t.min_length, "have": len(v)}))
                return _BAD
            before = len(errors)
            out = [item(x, (*loc, i), errors) for i, x in enumerate(v)]
            if len(errors) != before:
                return _BAD
            if t.unique is not None:
                seen: dict[Any, int] = {}
                for i, x in enumerate(v):
                    key = x.get(t.unique)
                    if key in seen:
                        errors.append(Error("rule", (*loc, i, t.unique), key, {
                            "message": f"{t.unique} {key!r} is given twice "
                            f"(first as item {seen[key] + 1})"}))
                        return _BAD
                    seen[key] = i
            return out

        return check

    def _either(self, t: k.Either) -> Check:
        options = [(_kind(o), self.compile(o)) for o in t.options]
        expected = " or ".join(k for k, _ in options)
        words = {w: o for o in t.options if isinstance(o, k.Choice) for w in o.values}
        lists = [o for o in t.options if isinstance(o, k.Fixed)]

        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            kind = _value_kind(v)
            if kind == "list" and words and lists:
                for i, x in enumerate(v):
                    if type(x) is str and x in words:
                        errors.append(Error("rule", (*loc, i), x, {"message": (
                            f"{x!r} stands for the whole list: write the word {x} alone, "
                            f"or {lists[0].n} numbers")}))
                        return _BAD
            for option_kind, option in options:
                if option_kind == kind or (option_kind == "integer" and kind == "number"):
                    return option(v, loc, errors)
            errors.append(Error("type", loc, v, {"expected": expected}))
            return _BAD

        return check

    def _ref(self, t: k.Ref) -> Check:
        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            return self._objects[t.name](v, loc, errors)

        return check

    def _object(self, name: str) -> Check:
        obj = self.format[name]
        checks: dict[Any, Check] = {}
        nullable = {f.name for f in obj.fields if f.nullable}
        required = [f.name for f in obj.fields if f.default is k.REQUIRED]
        plain: dict[str, Any] = {}
        fresh: dict[str, Any] = {}  # defaults built anew for each mapping
        for f in obj.fields:
            if f.default is k.REQUIRED:
                plain[f.name] = None
            elif f.default is k.EXPANDED or isinstance(f.default, list):
                plain[f.name] = None  # a placeholder keeping the fields' order
                fresh[f.name] = f.default
            else:
                plain[f.name] = f.default
        field_names = [f.name for f in obj.fields]
        build = self.builders.get(name, dict)

        def check(v: Any, loc: tuple[Any, ...], errors: list[Error]) -> Any:
            if type(v) is not dict:
                errors.append(Error("type", loc, v, {"expected": "mapping"}))
                return _BAD
            before = len(errors)
            out = dict(plain)
            for key, default in fresh.items():
                if key not in v:
                    out[key] = (self._objects[obj.field(key).type.name]({}, loc, errors)  # type: ignore[union-attr]
                                if default is k.EXPANDED else list(default))
            for key, x in v.items():
                fn = checks.get(key)
                if fn is None:
                    if key in field_names:  # compiled lazily: objects may refer to later ones
                        fn = checks[key] = self.compile(obj.field(key).type)  # type: ignore[union-attr]
                    else:
                        kind = "unknown_key" if type(key) is str else "bad_key"
                        errors.append(Error(kind, (*loc, key), key, {"fields": field_names}))
                        continue
                if x is None and key in nullable:
                    out[key] = None
                else:
                    out[key] = fn(x, (*loc, key), errors)
            for key in required:
                if key not in v:
                    errors.append(Error("missing", (*loc, key), None, {}))
            # which of a group is given is known even where a value is bad: said now,
            # not only on the next run once the other problems are mended
            self._groups(obj, out, v, loc, errors)
            if len(errors) == before:
                self._rules(obj, out, v, loc, errors)
            if len(errors) != before:
                return _BAD
            return build(out)

        return check

    @staticmethod
    def _groups(obj: k.Object, out: dict[str, Any], raw: dict[str, Any], loc: tuple[Any, ...],
                errors: list[Error]) -> None:
        """Exactly one (or at least one) of each group of fields, by what the mapping gives."""
        for group in obj.groups:
            given = sum(1 for name in group.fields
                        if (raw.get(name) if name in raw else out.get(name)) is not None)
            if given == 0 and group.optional:
                continue
            if (given == 0) or (given > 1 and not group.at_least):
                errors.append(Error("rule", loc, None, {"message": group.message}))

    @staticmethod
    def _rules(obj: k.Object, out: dict[str, Any], raw: dict[str, Any], loc: tuple[Any, ...],
               errors: list[Error]) -> None:
        """The rules that span a whole (otherwise valid) mapping."""
        before = len(errors)
        for fc in obj.field_checks:
            if out.get(fc.field) is None:
                continue
            found = fc.test(out[fc.field])
            if found is not None:
                message, row = found if isinstance(found, tuple) else (found, None)
                at = (*loc, fc.field) if row is None else (*loc, fc.field, row)
                errors.append(Error("rule", at, out[fc.field], {"message": message}))
        if len(errors) != before:
            return
        for c in obj.checks:
            message = c.test(raw if c.raw else out)
            if message is not None:
                at = loc if c.at is None else (*loc, c.at)
                errors.append(Error("rule", at, out.get(c.at) if c.at else None,
                                    {"message": message}))
