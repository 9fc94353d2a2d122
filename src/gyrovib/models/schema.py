"""The catalogue's JSON Schema, as pydantic writes it from the models, in the
draft-07 form editors implement (yaml-language-server, VS Code's YAML
extension).

Pydantic writes draft 2020-12; :func:`draft_07` is the small step between the
two: ``$defs`` become ``definitions`` (and every ``$ref`` follows), a tuple's
``prefixItems`` the array form of ``items`` with ``additionalItems: false``, a
``$ref`` with siblings is wrapped in ``allOf`` (draft-07 ignores them), titles
are dropped (each property has its description) and a number without a bound
is bounded by the largest float, so ``.inf`` and integers too large for a
float are refused as ``gyrovib validate`` refuses them (JSON has no NaN).

What a schema cannot say (increasing breakpoints, a PSD's band, ids unique
across files, K1 so small that a division overflows) is left to ``gyrovib
validate``.
"""

from __future__ import annotations

import json
from typing import Any

from gyrovib.models.catalogue import Catalogue

DRAFT_07 = "http://json-schema.org/draft-07/schema#"
#: Largest finite float: the bound of a number without one.
FLOAT_MAX = 1.7976931348623157e308

_DATA = ("default", "enum", "const", "examples")  # values, not schemas


def _number(node: dict[str, Any]) -> None:
    if "minimum" not in node and "exclusiveMinimum" not in node:
        node["minimum"] = -FLOAT_MAX
    if "maximum" not in node and "exclusiveMaximum" not in node:
        node["maximum"] = FLOAT_MAX


def _convert_entry(key: str, value: Any, node: dict[str, Any], out: dict[str, Any]) -> None:
    """Put the draft-07 form of ``node[key]`` into ``out`` (titles are dropped)."""
    if key == "title":
        return
    if key in _DATA:
        out[key] = value
    elif key == "properties":
        out[key] = {name: _convert(v) for name, v in value.items()}
    elif key == "$ref":
        out[key] = value.replace("#/$defs/", "#/definitions/")
    elif key == "prefixItems":
        out["items"] = _convert(value)
        if node.get("maxItems") == len(value) or "items" not in node:
            out["additionalItems"] = False
    elif key == "items" and "prefixItems" in node:
        out["additionalItems"] = _convert(value)
    else:
        out[key] = _convert(value)


def _convert(node: Any) -> Any:
    if isinstance(node, list):
        return [_convert(x) for x in node]
    if not isinstance(node, dict):
        return node
    out: dict[str, Any] = {}
    for key, value in node.items():
        _convert_entry(key, value, node, out)
    if out.get("type") == "number":
        _number(out)
    if "$ref" in out and len(out) > 1:
        ref = out.pop("$ref")
        out = {"allOf": [{"$ref": ref}, *out.pop("allOf", [])], **out}
    return out


def draft_07(schema: dict[str, Any]) -> dict[str, Any]:
    """A pydantic (draft 2020-12) schema in draft-07 form."""
    body = dict(schema)
    definitions = body.pop("$defs", {})
    out: dict[str, Any] = _convert(body)
    if definitions:
        out["definitions"] = {name: _convert(d) for name, d in sorted(definitions.items())}
    return out


def catalog_schema() -> dict[str, Any]:
    """The JSON Schema (draft-07) of one catalogue file, as a dict."""
    body = draft_07(Catalogue.model_json_schema(mode="validation"))
    return {
        "$schema": DRAFT_07,
        "title": "gyrovib catalogue",
        "description": "Angular-rate sensors and vibration profiles for gyrovib "
        "(format version 1). See the README, 'Catalogue files'.",
        **{k: v for k, v in body.items() if k != "description"},
    }


def schema_text() -> str:
    """The schema as indented JSON text, newline-ended."""
    return json.dumps(catalog_schema(), indent=2, ensure_ascii=False) + "\n"
