"""Errors of the catalogue models as sentences: where, what, what to write.

:func:`errors` turns a pydantic ``ValidationError`` of :mod:`gyrovib.models`
into :class:`Error` records (kind, path in the file, value, details) in the
order of the file; :func:`message` phrases one, with one small function per
kind of error. Bounds, allowed values and key names are read from the models
(:func:`gyrovib.models.introspect.at`), never written here. The place in the
file (line and column) is added by :mod:`gyrovib.catalog.locate`.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

from pydantic import ValidationError

from gyrovib.models import introspect

#: The top-level key holding the format version.
VERSION_KEY = "gyrovib"
#: Top-level lists of items with an id unique across files, with the item's name.
SECTIONS = (("sensors", "sensor"), ("profiles", "profile"), ("missions", "mission"))
#: The key of an item's id.
ID_KEY = "id"
#: The top-level key every merged file must agree on.
SHARED_KEY = "allocation"

_SHOWN_ID = re.compile(r"[A-Za-z0-9._-]{1,80}")
_SECTIONS = dict(SECTIONS)


class Error(NamedTuple):
    """One broken rule: ``kind`` (see :data:`_KINDS`), where, the value, details."""

    kind: str
    loc: tuple[Any, ...]
    value: Any
    ctx: dict[str, Any]


# ---------------------------------------------------------------- pydantic's errors

_TYPES = {"float_type": "number", "int_type": "integer", "int_from_float": "integer",
          "int_parsing": "integer", "string_type": "text", "list_type": "list",
          "tuple_type": "list", "model_type": "mapping", "model_attributes_type": "mapping",
          "dict_type": "mapping"}
_BOUNDS = {"greater_than": (">", "gt"), "greater_than_equal": (">=", "ge"),
           "less_than_equal": ("<=", "le"), "less_than": ("<", "lt")}


def _value(data: Any, loc: Sequence[Any]) -> Any:
    for part in loc:
        try:
            data = data[part]
        except (KeyError, IndexError, TypeError):
            return None
    return data


def _short_list(e: Any, loc: tuple[Any, ...], data: Any) -> Error | None:
    """A missing value of a fixed-length list: the list is too short."""
    if not (loc and isinstance(loc[-1], int)):
        return None
    given = _value(data, loc[:-1])
    return Error("too_few", loc[:-1], given, {"n": introspect.at(loc[:-1]).size,
                                              "have": len(given), "exact": True})


def _missing_key(e: Any, loc: tuple[Any, ...], data: Any) -> Error:
    return _short_list(e, loc, data) or Error("missing", loc, None, {})


def _extra(e: Any, loc: tuple[Any, ...], data: Any) -> Error:
    fields = introspect.fields(loc[:-1])
    return Error("unknown_key" if isinstance(loc[-1], str) else "bad_key", loc, loc[-1],
                 {"fields": fields})


def _float_type(e: Any, loc: tuple[Any, ...], data: Any) -> Error:
    if type(e["input"]) is int:
        return Error("finite", loc, e["input"], {})  # an integer too large for a float
    return Error("type", loc, e["input"], {"expected": _TYPES["float_type"]})


def _bound(e: Any, loc: tuple[Any, ...], data: Any) -> Error:
    op, key = _BOUNDS[e["type"]]
    return Error("bound", loc, e["input"], {"op": op, "bound": _ctx(e)[key],
                                            "hint": introspect.at(loc).hint})


def _length_words(low: int, high: int) -> Any:
    """How many values a list of ``low`` to ``high`` values holds, in words."""
    if low == high:
        return low
    return f"{low} or {high}" if high == low + 1 else f"{low} to {high}"


def _length(e: Any, loc: tuple[Any, ...], data: Any) -> Error:
    kind, value, ctx = e["type"], e["input"], _ctx(e)
    node = introspect.at(loc)
    exact = ctx.get("field_type") == "Tuple"
    if exact and isinstance(value, (list, tuple)):
        low, high = node.lengths or (node.size, node.size)
        if low and low <= len(value) <= high:  # counted after its bad values were dropped
            return Error("ignored", loc, value, {})
    n: Any = ctx.get("min_length" if kind == "too_short" else "max_length")
    if exact and node.lengths is not None:
        n = _length_words(*node.lengths)
    have = len(value) if isinstance(value, (list, tuple)) else ctx.get("actual_length")
    return Error("too_few" if kind == "too_short" else "too_many", loc, value,
                 {"n": n, "have": have, "exact": exact})


def _literal(e: Any, loc: tuple[Any, ...], data: Any) -> Error:
    node = introspect.at(loc)
    return Error("choice", loc, e["input"], {"values": node.choices, "what": node.what})


def _ctx(e: Any) -> dict[str, Any]:
    return e.get("ctx") or {}


def _simple(kind: str, ctx: Callable[[Any], dict[str, Any]] = lambda e: {}
            ) -> Callable[[Any, tuple[Any, ...], Any], Error]:
    """A handler that names the kind ``kind``, with the details ``ctx(e)``."""
    return lambda e, loc, data: Error(kind, loc, e["input"], ctx(e))


#: pydantic's error types (and the models' own), each to the handler of its kind.
_HANDLERS: dict[str, Callable[[Any, tuple[Any, ...], Any], Error]] = {
    "rule": lambda e, loc, data: Error(e["type"], loc, e["input"], dict(_ctx(e))),
    "version": lambda e, loc, data: Error(e["type"], loc, e["input"], dict(_ctx(e))),
    "missing": _missing_key,
    "extra_forbidden": _extra,
    "invalid_key": _simple("bad_key", lambda e: {"fields": ()}),
    "finite_number": _simple("finite"),
    **{kind: _simple("type", lambda e: {"expected": _TYPES[e["type"]]}) for kind in _TYPES},
    "float_type": _float_type,
    "kind": _simple("type", lambda e: {"expected": e["msg"]}),  # a union chosen by the
    # kind of value written
    **{kind: _bound for kind in _BOUNDS},
    "too_short": _length,
    "too_long": _length,
    "literal_error": _literal,
    "string_pattern_mismatch": _simple("id_pattern"),
    "string_too_short": _simple("id_empty"),
    "string_too_long": _simple("text_long", lambda e: {"max": _ctx(e)["max_length"]}),
}


def _error(e: Any, data: Any) -> Error:
    """One pydantic error as an :class:`Error`."""
    loc = tuple(p for p in e["loc"] if p not in introspect.TAGS)
    handler = _HANDLERS.get(e["type"])
    if handler is None:  # pragma: no cover - a new kind
        return Error("rule", loc, e["input"], {"message": e["msg"]})
    return handler(e, loc, data)


def _order(data: Any, loc: tuple[Any, ...]) -> tuple[int, ...]:
    """Where ``loc`` is in the document, as positions (the key order of each mapping)."""
    out: list[int] = []
    node = data
    for part in loc:
        if isinstance(node, dict):
            keys = list(node)
            out.append(keys.index(part) if part in node else len(keys))
            node = node.get(part)
        elif isinstance(node, list) and isinstance(part, int) and 0 <= part < len(node):
            out.append(part)
            node = node[part]
        else:
            break
    return tuple(out)


def errors(exc: ValidationError, data: Any) -> list[Error]:
    """The errors of ``exc`` (raised validating ``data``), in the order of the file."""
    every = [_error(x, data) for x in exc.errors(include_url=False)]
    # one error per place and kind (pydantic reports a short tuple once per missing
    # value), but every rule broken there
    found = list({(e.kind, e.loc, e.ctx.get("message")): e for e in every
                  if e.kind != "ignored"}.values())
    if not found:  # (cannot happen: a wrong count comes with the values' own problems)
        found = [e._replace(kind="rule", ctx={"message": "not valid here"}) for e in every]
    # a list of the wrong length is said once, not with its values' own problems
    lengths = {e.loc for e in found if e.kind in ("too_few", "too_many")}
    if lengths:
        found = [e for e in found
                 if not any(e.loc[:len(at)] == at and len(e.loc) > len(at) for at in lengths)]
    # a rule of a mapping (or value) comes after the problems within it, as it is judged
    # on the whole
    found.sort(key=lambda e: (*_order(data, e.loc), _LAST) if e.kind == "rule"
               else _order(data, e.loc))
    return found


_LAST = 1 << 62


def _item_name(loc: Sequence[Any], data: Any) -> str:
    """``sensor 'fog-a'`` if ``loc`` starts at an item of a section with a showable id."""
    if not (len(loc) >= 2 and loc[0] in _SECTIONS and isinstance(loc[1], int)
            and isinstance(data, dict)):
        return ""
    items = data.get(loc[0])
    item = items[loc[1]] if isinstance(items, list) and loc[1] < len(items) else None
    ident = item.get(ID_KEY) if isinstance(item, dict) else None
    if isinstance(ident, str) and _SHOWN_ID.fullmatch(ident):
        return f"{_SECTIONS[loc[0]]} {ident!r}"
    return ""


def where(loc: Sequence[Any], data: Any) -> str:
    """A readable path: ``sensor 'fog-a': coefficients.k2``, ``profiles[2].rate[1]``."""
    head = _item_name(loc, data)
    text = ""
    for part in loc[2 if head else 0:]:
        text += f"[{part}]" if isinstance(part, int) else ("." if text else "") + str(part)
    if head and text:
        return f"{head}: {text}"
    return head or text


def describe(value: Any) -> str:
    """A value as the user wrote it, for 'not ...' messages."""
    if isinstance(value, bool):
        return f"the boolean {str(value).lower()}"
    if value is None:
        return "empty (null)"
    if isinstance(value, str):
        shown = value if len(value) <= 40 else value[:37] + "..."
        return f"the text {shown!r}"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, (list, tuple)):
        return "a list"
    if isinstance(value, int) and abs(value) > 10**20:
        return "an integer too large for a floating-point number"
    return repr(value)


def _unknown_key(e: Error, prefix: str, at: str, text: str | None) -> str:
    key = str(e.loc[-1])
    fields = list(e.ctx["fields"])
    message = f"{prefix}unknown key {key!r}"
    close = [f for f in fields if f.lower() == key.lower().replace("-", "_")] or \
        difflib.get_close_matches(key, fields, n=1, cutoff=0.6)
    if close:
        return message + f"; did you mean {close[0]!r}?"
    return message + f"; allowed here: {', '.join(fields)}" if fields else message


def _bad_key(e: Error, prefix: str, at: str, text: str | None) -> str:
    return f"{prefix}a key must be a name, not {describe(e.value)}"


def _missing(e: Error, prefix: str, at: str, text: str | None) -> str:
    return f"{prefix}missing required key {str(e.loc[-1])!r}"


def _version(e: Error, prefix: str, at: str, text: str | None) -> str:
    return (f"{at}: the format version must be the number {e.ctx['expected']}, "
            f"not {describe(e.value)}")


def _too_few(e: Error, prefix: str, at: str, text: str | None) -> str:
    if e.ctx.get("exact"):
        return f"{at}: too few values ({e.ctx['have']}; expected {e.ctx['n']})"
    return f"{at}: too few values (at least {e.ctx['n']} needed)"


def _too_many(e: Error, prefix: str, at: str, text: str | None) -> str:
    if e.ctx.get("exact"):
        return f"{at}: too many values ({e.ctx['have']}; expected {e.ctx['n']})"
    return f"{at}: too many values ({e.ctx['have']}; expected at most {e.ctx['n']})"


def _finite(e: Error, prefix: str, at: str, text: str | None) -> str:
    written = (text or "").strip().lower()
    if "nan" in written:
        what = "NaN is not a number gyrovib accepts"
    elif "inf" in written:
        what = "infinities are not accepted"
    elif written:
        shown = written if len(written) <= 24 else \
            f"{written[:12]}...({len(written)} characters)"
        what = f"{shown} overflows a floating-point number (max ~1.8e308)"
    else:
        what = "the value overflows or is not finite"
    return f"{at}: {what}; write a finite number"


def _type(e: Error, prefix: str, at: str, text: str | None) -> str:
    expected = e.ctx["expected"]
    if expected == "mapping":
        return f"{at}: must be a mapping of keys to values, not {describe(e.value)}"
    if expected in ("number", "integer"):
        return f"{at}: must be a{'n' if expected == 'integer' else ''} {expected}, " \
               f"not {describe(e.value)}"
    return f"{at}: must be {'a ' if expected != 'text' else ''}{expected}, " \
           f"not {describe(e.value)}"


_BOUND_WORDS = {">": "must be greater than", ">=": "must not be less than",
                "<": "must be less than", "<=": "must not be greater than"}


def _bound_text(e: Error, prefix: str, at: str, text: str | None) -> str:
    op, bound = e.ctx["op"], e.ctx["bound"]
    shown = int(bound) if float(bound).is_integer() and abs(bound) < 1e7 else f"{bound:g}"
    what = f"{_BOUND_WORDS[op]} {shown}"
    if bound == 0 and op == ">=":
        what = "must not be negative"
    elif bound == 0 and op == ">":
        what = "must be positive (greater than 0)"
    return f"{at}: {what}{e.ctx.get('hint', '')}, got {e.value!r}"


def _id_pattern(e: Error, prefix: str, at: str, text: str | None) -> str:
    return (f"{at}: the id {e.value!r} may hold only letters, digits, '.', '_' and '-' "
            "(no spaces or slashes)")


def _id_empty(e: Error, prefix: str, at: str, text: str | None) -> str:
    return f"{at}: the id must not be empty"


def _text_long(e: Error, prefix: str, at: str, text: str | None) -> str:
    return f"{at}: too long ({len(e.value)} characters; at most {e.ctx['max']})"


def _choice(e: Error, prefix: str, at: str, text: str | None) -> str:
    known = ", ".join(e.ctx["values"])
    if e.ctx.get("what") and isinstance(e.value, str):
        return f"{at}: unknown {e.ctx['what']} {e.value!r}; use one of {known}"
    return f"{at}: {e.value!r} is not allowed; use one of {known}"


def _rule(e: Error, prefix: str, at: str, text: str | None) -> str:
    return f"{at}: {e.ctx['message']}" if at else str(e.ctx["message"])


_KINDS: dict[str, Callable[[Error, str, str, str | None], str]] = {
    "unknown_key": _unknown_key, "bad_key": _bad_key, "missing": _missing,
    "version": _version, "too_few": _too_few, "too_many": _too_many, "finite": _finite,
    "type": _type, "bound": _bound_text, "id_pattern": _id_pattern, "id_empty": _id_empty,
    "text_long": _text_long, "choice": _choice, "rule": _rule,
}


def message(error: Error, data: Any = None, text: str | None = None) -> str:
    """One error as a sentence; ``text``: the scalar as written in the file, if known."""
    parent = where(error.loc[:-1], data)
    prefix = f"{parent}: " if parent else ""
    at = where(error.loc, data)
    return _KINDS[error.kind](error, prefix, at, text)
