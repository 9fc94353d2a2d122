"""The catalogue format as a JSON Schema that editors understand (draft-07).

Generated from the pydantic models of :mod:`gyrovib.catalog.schema`, then
rewritten for draft-07, the newest draft yaml-language-server (VS Code's YAML
extension) and most editors implement:

* ``$defs`` → ``definitions`` and every ``$ref`` rewritten to match;
* ``prefixItems`` (2020-12 tuples) → the array form of ``items`` with
  ``additionalItems: false``;
* a ``$ref`` with sibling keywords (ignored by draft-07) is wrapped in ``allOf``;
* pydantic's generated titles (``"K2"`` for ``k2``) are dropped and
  descriptions added; every object keeps ``additionalProperties: false``;
* what the model validators check that a schema can say is added: exactly one
  of ``coefficients``/``output_coefficients`` and of ``psd``/``rms``,
  ``K1 ≠ 0``, ``gyrovib: 1``.

What a schema cannot say (increasing breakpoints, unique ids across files) is
left to ``gyrovib validate``.
"""

from __future__ import annotations

import json
from typing import Any

from gyrovib.catalog.schema import CatalogFile

DRAFT_07 = "http://json-schema.org/draft-07/schema#"

#: Keywords kept, as draft-07 defines them; anything else pydantic emits is dropped.
_DRAFT_07_KEYWORDS = frozenset({
    "$ref", "$schema", "$id", "$comment", "title", "description", "default", "examples",
    "type", "enum", "const", "multipleOf", "maximum", "exclusiveMaximum", "minimum",
    "exclusiveMinimum", "maxLength", "minLength", "pattern", "items", "additionalItems",
    "maxItems", "minItems", "uniqueItems", "contains", "maxProperties", "minProperties",
    "required", "properties", "patternProperties", "additionalProperties", "dependencies",
    "propertyNames", "if", "then", "else", "allOf", "anyOf", "oneOf", "not", "format",
    "definitions", "readOnly", "writeOnly",
})

_RATE = "in the file's rate unit (units.rate)"

#: Descriptions of fields, by model (definition) name and field name.
DESCRIPTIONS: dict[str, dict[str, str]] = {
    "CatalogFile": {
        "gyrovib": "Format version; must be 1.",
        "units": "Units of the values in this file.",
        "sensors": "Angular-rate sensors; ids unique across all files given.",
        "profiles": "Vibration environments; ids unique across all files given.",
        "allocation": "How a budget is split among the terms (eq. 18, 21, 24).",
    },
    "Units": {
        "rate": "Unit of every rate, PSD and coefficient in this file: deg/s (default), "
        "deg/h, rad/s or rpm.",
    },
    "Sensor": {
        "id": "Unique id: letters, digits, '.', '_' and '-'.",
        "name": "Free text.",
        "vendor": "Free text.",
        "part": "Free text (part number).",
        "notes": "Free text.",
        "range": f"Full-scale range, {_RATE}; > 0.",
        "coefficients": "Conversion function of eq. (2), in rate units (k1 = 1). "
        "Give this or output_coefficients.",
        "output_coefficients": "Conversion function of eq. (1), in output units. "
        "Give this or coefficients.",
        "response": "The sensor's own transmissibility ν(f): [[f Hz, gain], ...], "
        "frequencies increasing (a repeated frequency is a step).",
    },
    "Coefficients": {
        "k0": f"Bias, {_RATE}.",
        "k1": "Scale factor (1 in eq. 2).",
        "A1": "Scale-factor asymmetry (dimensionless).",
        "k2": "Second-order nonlinearity, rate^-1.",
        "k3": "Third-order nonlinearity, rate^-2.",
        "k4": "Fourth-order nonlinearity, rate^-3.",
        "k5": "Fifth-order nonlinearity, rate^-4.",
        "m1": "Cross-axis sensitivity to x1 (dimensionless).",
        "m2": "Cross-axis sensitivity to x2 (dimensionless).",
        "m31": "Product cross-axis term x3·x1, rate^-1.",
        "m32": "Product cross-axis term x3·x2, rate^-1.",
    },
    "OutputCoefficients": {
        "unit": "The output unit (free text, e.g. mV or LSB).",
        "K1": "Scale factor, output per rate unit; required and non-zero.",
        "K0": "Bias, output units.",
        "A1": "Scale-factor asymmetry (dimensionless).",
        **{
            upper: f"As {lower} of eq. (2), times K1 (output units)."
            for upper, lower in (("K2", "k2"), ("K3", "k3"), ("K4", "k4"), ("K5", "k5"),
                                 ("M1", "m1"), ("M2", "m2"), ("M31", "m31"), ("M32", "m32"))
        },
    },
    "Profile": {
        "id": "Unique id: letters, digits, '.', '_' and '-'.",
        "name": "Free text.",
        "notes": "Free text.",
        "rate": f"Carrier rate Ω_K about x1, x2, x3, {_RATE}.",
        "harmonic": "Harmonic tones of eq. (3), zero or more.",
        "random": "Gaussian broadband vibration: a PSD or the RMS per axis.",
        "mount": "Isolation-mount transmissibility ν(f): [[f Hz, gain], ...].",
    },
    "Tone": {
        "frequency": "Frequency in Hz; > 0.",
        "amplitude": f"Amplitude per axis x1, x2, x3, {_RATE}; >= 0.",
        "phase": "Phase per axis, degrees.",
    },
    "Random": {
        "psd": "PSD breakpoints per axis, rate²/Hz, log-log interpolated.",
        "rms": f"RMS per axis at the sensor, {_RATE}; no spectrum, so ν(f) does not apply.",
        "coherence": "Coherences ρ31, ρ32, each in [-1, 1]; default 1.",
    },
    "PSD": {
        axis: f"[[f Hz, S rate²/Hz], ...] for axis {axis}; left out means none."
        for axis in ("x1", "x2", "x3")
    },
    "Allocation": {
        "r": "Ratio r of eq. (18); > 0.",
        "w": "Share weights w of the five additive terms; each > 0.",
        "v": "Share weights v of the three multiplicative terms; each > 0.",
    },
}

#: Exactly-one-of rules of the model validators, by definition name.
_ONE_OF: dict[str, tuple[str, str]] = {
    "Sensor": ("coefficients", "output_coefficients"),
    "Random": ("psd", "rms"),
}


def _convert(node: Any) -> Any:
    """Rewrite one pydantic (2020-12) schema node for draft-07, recursively."""
    if isinstance(node, list):
        return [_convert(item) for item in node]
    if not isinstance(node, dict):
        return node
    out: dict[str, Any] = {}
    for key, value in node.items():
        if key == "prefixItems":
            out["items"] = [_convert(item) for item in value]
            out["additionalItems"] = False
        elif key == "$ref":
            out["$ref"] = str(value).replace("#/$defs/", "#/definitions/")
        elif key in ("default", "enum", "const", "examples"):
            out[key] = value  # values, not schemas
        elif key in ("properties", "definitions", "patternProperties"):
            out[key] = {name: _convert(sub) for name, sub in value.items()}
        elif key in _DRAFT_07_KEYWORDS:
            out[key] = _convert(value)
    if "$ref" in out and len(out) > 1:  # draft-07 ignores siblings of $ref
        ref = out.pop("$ref")
        out["allOf"] = [{"$ref": ref}]
    return out


def _strip_titles(properties: dict[str, Any]) -> None:
    for sub in properties.values():
        if isinstance(sub, dict):
            sub.pop("title", None)


def _describe(name: str, definition: dict[str, Any]) -> None:
    properties = definition.get("properties", {})
    _strip_titles(properties)
    for field, text in DESCRIPTIONS.get(name, {}).items():
        if field in properties:
            properties[field]["description"] = text
    if name in _ONE_OF:
        a, b = _ONE_OF[name]
        definition["oneOf"] = [{"required": [a]}, {"required": [b]}]
    definition["additionalProperties"] = False
    if "description" in definition:
        definition["description"] = definition["description"].replace("``", "'")


def catalog_schema() -> dict[str, Any]:
    """The JSON Schema (draft-07) of one catalogue file, as a dict."""
    raw = CatalogFile.model_json_schema()
    definitions = {name: _convert(d) for name, d in raw.pop("$defs", {}).items()}
    root = _convert(raw)
    for name, definition in definitions.items():
        _describe(name, definition)
    _describe("CatalogFile", root)
    root["properties"]["gyrovib"].update({"const": 1})
    k1 = definitions["OutputCoefficients"]["properties"]["K1"]
    k1["not"] = {"const": 0}
    schema: dict[str, Any] = {
        "$schema": DRAFT_07,
        "title": "gyrovib catalogue",
        "description": "Angular-rate sensors and vibration profiles for gyrovib "
        "(format version 1). See the README, 'Catalogue files'.",
    }
    root.pop("title", None)
    root.pop("description", None)
    schema.update(root)
    schema["definitions"] = dict(sorted(definitions.items()))
    return schema


def schema_text() -> str:
    """The schema as indented JSON text, newline-ended."""
    return json.dumps(catalog_schema(), indent=2, ensure_ascii=False) + "\n"
