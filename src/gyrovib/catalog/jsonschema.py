"""The catalogue format as a JSON Schema that editors understand (draft-07).

Written straight from :data:`gyrovib.catalog.spec.FORMAT`, for draft-07, the
newest draft yaml-language-server (VS Code's YAML extension) and most editors
implement: tuples as the array form of ``items`` with ``additionalItems:
false``, ``definitions``, no ``$ref`` with siblings (wrapped in ``allOf``),
every object closed (``additionalProperties: false``) and every property
described.

Numbers are bounded by the largest float, so ``.inf`` and integers too large
for a float are refused as ``validate`` refuses them (JSON has no NaN).
The groups of the spec become ``oneOf``/``anyOf`` over the keys given a
non-null value, so ``coefficients: null`` means "not given" here too.
What a schema cannot say (increasing breakpoints, a PSD's band, ids unique
across files, K1 so small that a division overflows) is left to
``gyrovib validate``.
"""

from __future__ import annotations

import json
from typing import Any

from gyrovib.catalog import kinds as k
from gyrovib.catalog import spec as s

DRAFT_07 = "http://json-schema.org/draft-07/schema#"


def _plain(value: Any) -> Any:
    """A default as JSON: tuples as lists."""
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    return value


def _number(t: k.Number) -> dict[str, Any]:
    out: dict[str, Any] = {"type": "number"}
    if t.minimum is None:
        out["minimum"] = -s.FLOAT_MAX
    elif t.exclusive_minimum:
        out["exclusiveMinimum"] = t.minimum
    else:
        out["minimum"] = t.minimum
    out["maximum"] = s.FLOAT_MAX if t.maximum is None else t.maximum
    return out


def _fixed(n: int, items: list[dict[str, Any]]) -> dict[str, Any]:
    """``n`` to ``len(items)`` values, the i-th of ``items[i]``."""
    return {"type": "array", "items": items, "minItems": n, "maxItems": len(items),
            "additionalItems": False}


def type_schema(t: Any) -> dict[str, Any]:
    """The schema of one value type of the spec."""
    if isinstance(t, k.Number):
        return _number(t)
    if isinstance(t, k.Integer):
        return {"type": "integer", **({"minimum": t.minimum} if t.minimum is not None else {})}
    if isinstance(t, k.Version):
        return {"type": "integer", "const": t.value}
    if isinstance(t, k.Text):
        return {"type": "string", "maxLength": t.max_length}
    if isinstance(t, k.Identifier):
        return {"type": "string", "pattern": t.pattern, "minLength": 1,
                "maxLength": t.max_length}
    if isinstance(t, k.Choice):
        return {"type": "string", "enum": list(t.values)}
    if isinstance(t, k.Fixed):
        return _fixed(t.n, [type_schema(t.item)] * (t.most or t.n))
    if isinstance(t, k.Table):
        row = _fixed(2, [_number(k.Number(minimum=0, exclusive_minimum=True)),
                         _number(k.Number(minimum=0))])
        return {"type": "array", "items": row, "minItems": 2 if t.band else 1,
                "maxItems": t.max_rows}
    if isinstance(t, k.Ref):
        return {"$ref": f"#/definitions/{t.name}"}
    if isinstance(t, k.ListOf):
        out: dict[str, Any] = {"type": "array", "items": type_schema(t.item)}
        if t.min_length:
            out["minItems"] = t.min_length
        if t.max_length is not None:
            out["maxItems"] = t.max_length
        return out
    if isinstance(t, k.Either):
        return {"anyOf": [type_schema(o) for o in t.options]}
    raise TypeError(f"no JSON Schema for {t!r}")  # pragma: no cover - a spec bug


def _property(f: k.Field, extra: dict[str, Any] | None,
              fmt: dict[str, k.Object]) -> dict[str, Any]:
    schema = type_schema(f.type)
    if extra:
        schema = {"allOf": [schema, extra]} if "$ref" in schema else {**schema, **extra}
    if f.nullable:
        schema = {"anyOf": [schema, {"type": "null"}]}
    elif "$ref" in schema:
        schema = {"allOf": [schema]}
    schema["description"] = f.description
    if f.default is k.EXPANDED:
        schema["default"] = _plain(s.defaults(f.type.name, fmt))
    elif f.default is not k.REQUIRED and f.default is not None:
        schema["default"] = _plain(f.default)
    return schema


def _given(name: str) -> dict[str, Any]:
    return {"required": [name], "properties": {name: {"not": {"type": "null"}}}}


def object_schema(obj: k.Object, fmt: dict[str, k.Object] | None = None) -> dict[str, Any]:
    """The schema of one mapping of the spec."""
    extras = {fc.field: fc.schema for fc in obj.field_checks if fc.schema}
    out: dict[str, Any] = {
        "type": "object",
        "description": obj.description,
        "properties": {f.name: _property(f, extras.get(f.name), s.FORMAT if fmt is None else fmt)
                       for f in obj.fields},
        "additionalProperties": False,
    }
    required = [f.name for f in obj.fields if f.default is k.REQUIRED]
    if required:
        out["required"] = required
    rules: list[dict[str, Any]] = []
    for group in obj.groups:
        branches = [_given(name) for name in group.fields]
        if group.at_least:
            rules.append({"anyOf": branches})
        elif group.optional:
            rules.append({"not": {"anyOf": [{"allOf": [a, b]} for i, a in enumerate(branches)
                                            for b in branches[i + 1:]]}})
        else:
            rules.append({"oneOf": branches})
    rules.extend(c.schema for c in obj.checks if c.schema)
    if len(rules) == 1:
        out.update(rules[0])
    elif rules:
        out["allOf"] = rules
    return out


def catalog_schema(fmt: dict[str, k.Object] | None = None) -> dict[str, Any]:
    """The JSON Schema (draft-07) of one catalogue file, as a dict."""
    fmt = s.FORMAT if fmt is None else fmt
    root = object_schema(fmt[s.ROOT], fmt)
    root.pop("description")
    schema: dict[str, Any] = {
        "$schema": DRAFT_07,
        "title": "gyrovib catalogue",
        "description": "Angular-rate sensors and vibration profiles for gyrovib "
        "(format version 1). See the README, 'Catalogue files'.",
        **root,
        "definitions": {name: object_schema(obj, fmt) for name, obj in sorted(fmt.items())
                        if name != s.ROOT},
    }
    return schema


def schema_text() -> str:
    """The schema as indented JSON text, newline-ended."""
    return json.dumps(catalog_schema(), indent=2, ensure_ascii=False) + "\n"
