"""Reading catalogue files: YAML → validated models, with every error located.

The YAML dialect is the safe subset, resolved the way people write numbers:
``1e-5`` is a float (plain YAML 1.1 reads it as a string), ``yes``/``no``,
dates and sexagesimal numbers are *not* special. Only plain mappings,
sequences and scalars are constructed; any tag that would build an object is
refused. libyaml's ``CSafeLoader`` is used when PyYAML was built with it.

On the happy path nothing but parsing and validation runs, and neither
imports pydantic: plain data is built straight from libyaml's node tree, and
checked and turned into records by :mod:`gyrovib.catalog.records`. Anything
unusual (tags, anchors, merge keys, duplicate keys) goes through PyYAML's own
constructor; anything the fast validator does not vouch for goes through the
pydantic models of :mod:`gyrovib.catalog.schema`. When validation fails, the
file is composed once more to find the line and column of each offending
value, so errors read ``FILE:LINE:COL: message``.
"""

from __future__ import annotations

import gc
import math
import re
from collections.abc import Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

import yaml

from gyrovib.catalog import records
from gyrovib.catalog.records import Allocation, CatalogFile, Profile, Sensor
from gyrovib.errors import CatalogError, Problem

if TYPE_CHECKING:
    from pydantic import ValidationError

_BaseLoader: Any = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

#: Most problems reported for one file; the rest are summarised.
MAX_PROBLEMS = 50
#: Expanded size above which a document with aliases is refused (alias bombs).
MAX_EXPANDED_NODES = 2_000_000
#: Deepest nesting of mappings and sequences accepted (a catalogue needs 7);
#: libyaml's composer recurses in C, so a deeper document could crash it.
MAX_DEPTH = 64
#: Largest catalogue file read, in bytes.
MAX_FILE_BYTES = 16 * 1024 * 1024

_YAML_PREFIX = "tag:yaml.org,2002:"


def _tag_name(tag: str) -> str:
    """A tag as it is written in the file: ``!!python/name:x`` rather than the URI."""
    return "!!" + tag[len(_YAML_PREFIX):] if tag.startswith(_YAML_PREFIX) else tag


class _Loader(_BaseLoader):  # type: ignore[misc]
    """Safe loader with YAML 1.2-style scalars and duplicate-key detection."""

    def construct_mapping(self, node: Any, deep: bool = False) -> Any:
        if isinstance(node, yaml.MappingNode):
            seen: dict[Any, Any] = {}
            for key_node, _ in node.value:
                if key_node.tag == "tag:yaml.org,2002:merge":
                    continue
                key = self.construct_object(key_node, deep=True)
                try:
                    hash(key)
                except TypeError:
                    raise yaml.constructor.ConstructorError(
                        None, None, "a mapping key must be a plain value", key_node.start_mark
                    ) from None
                if key in seen:
                    raise yaml.constructor.ConstructorError(
                        None,
                        None,
                        f"duplicate key {key!r} (first at line {seen[key].line + 1})",
                        key_node.start_mark,
                    )
                seen[key] = key_node.start_mark
        return super().construct_mapping(node, deep=deep)

    def construct_object(self, node: Any, deep: bool = False) -> Any:
        """Place a scalar that cannot be converted (``!!float abc``, an integer
        of more digits than Python converts) at its node."""
        try:
            return super().construct_object(node, deep=deep)
        except (ValueError, OverflowError) as exc:
            if isinstance(exc, yaml.YAMLError):
                raise
            text = str(node.value)
            shown = text[:40] + ("..." if len(text) > 40 else "")
            why = " (too many digits)" if "digits" in str(exc) else ""
            kind = node.tag.rsplit(":", 1)[-1]
            raise yaml.constructor.ConstructorError(
                None, None, f"{shown!r} is not a valid {kind}{why}", node.start_mark,
            ) from None


def _install_resolvers() -> None:
    resolvers: dict[Any, list[tuple[str, re.Pattern[str]]]] = {}
    keep = {"tag:yaml.org,2002:null", "tag:yaml.org,2002:merge"}
    for first, entries in _BaseLoader.yaml_implicit_resolvers.items():
        kept = [(tag, rx) for tag, rx in entries if tag in keep]
        if kept:
            resolvers[first] = kept
    _Loader.yaml_implicit_resolvers = resolvers
    _Loader.add_implicit_resolver(
        "tag:yaml.org,2002:bool", re.compile(r"^(?:true|True|TRUE|false|False|FALSE)$"),
        list("tTfF"),
    )
    _Loader.add_implicit_resolver(
        "tag:yaml.org,2002:int", re.compile(r"^[-+]?(?:0|[1-9][0-9]*)$"), list("-+0123456789")
    )
    _Loader.add_implicit_resolver(
        "tag:yaml.org,2002:float",
        re.compile(
            r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?"
            r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$"
        ),
        list("-+0123456789."),
    )


_install_resolvers()

_STR = "tag:yaml.org,2002:str"
#: Implicit resolvers of a plain scalar by its first character ("" for empty).
_PLAIN_RESOLVERS: dict[str, list[tuple[str, re.Pattern[str]]]] = {
    first: list(entries) for first, entries in _Loader.yaml_implicit_resolvers.items()
}
assert None not in _PLAIN_RESOLVERS  # no wildcard resolver: dispatch on the first character


def _resolve(self: Any, kind: Any, value: Any, implicit: Any) -> Any:
    """BaseResolver.resolve without its generality: there are no path resolvers."""
    if kind is yaml.ScalarNode:
        if implicit[0]:
            for tag, regexp in _PLAIN_RESOLVERS.get(value[:1], ()):
                if regexp.match(value):
                    return tag
        return _STR
    return _BaseLoader.resolve(self, kind, value, implicit)


_Loader.resolve = _resolve


class _Unusual(Exception):
    """The fast construction cannot build this document; PyYAML's constructor will."""


def _float(value: str) -> float:
    try:
        return float(value)
    except ValueError:  # .inf, -.Inf, .nan: as SafeConstructor.construct_yaml_float
        lowered = value.lower()
        sign = -1.0 if lowered.startswith("-") else 1.0
        lowered = lowered.lstrip("+-")
        if lowered == ".inf":
            return sign * math.inf
        if lowered == ".nan":
            return math.nan
        raise _Unusual from None


_SCALARS: dict[str, Any] = {
    _STR: None,
    "tag:yaml.org,2002:int": int,
    "tag:yaml.org,2002:float": _float,
    "tag:yaml.org,2002:bool": lambda v: v.lower() == "true",
    "tag:yaml.org,2002:null": lambda v: None,
}
_SEQ, _MAP = "tag:yaml.org,2002:seq", "tag:yaml.org,2002:map"


def _build(node: Any) -> Any:
    """Plain data of a node tree holding only plain scalars, lists and mappings.

    The result equals what the constructor builds; anything else (a tag, a
    duplicate or non-scalar key) raises :class:`_Unusual`.
    """
    tag = node.tag
    if tag == _MAP:
        out: dict[Any, Any] = {}
        for key_node, value_node in node.value:
            if type(key_node) is not yaml.ScalarNode:
                raise _Unusual
            key_tag = key_node.tag
            if key_tag == _STR:
                key = key_node.value
            elif key_tag in _SCALARS:
                key = _SCALARS[key_tag](key_node.value)
            else:
                raise _Unusual
            if key in out:
                raise _Unusual
            out[key] = _build(value_node)
        return out
    if tag == _SEQ:
        return [_build(child) for child in node.value]
    if tag == _STR:
        return node.value
    convert = _SCALARS.get(tag)
    if convert is None or type(node) is not yaml.ScalarNode:
        raise _Unusual
    return convert(node.value)


@contextmanager
def _gc_paused() -> Iterator[None]:
    """Pause the cyclic garbage collector while building large acyclic data.

    Building a catalogue allocates hundreds of thousands of containers and no
    cycle; each full collection would walk all of them again.
    """
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()

_ALLOWED_TAGS = {
    "tag:yaml.org,2002:map",
    "tag:yaml.org,2002:seq",
    "tag:yaml.org,2002:str",
    "tag:yaml.org,2002:int",
    "tag:yaml.org,2002:float",
    "tag:yaml.org,2002:bool",
    "tag:yaml.org,2002:null",
    "tag:yaml.org,2002:merge",
}


def _check_nodes(node: Any) -> None:
    """Refuse object-building tags and alias bombs before anything is constructed."""
    sizes: dict[int, int] = {}
    stack: list[tuple[Any, bool]] = [(node, False)]
    while stack:
        current, done = stack.pop()
        key = id(current)
        if done:
            children = (
                [n for pair in current.value for n in pair]
                if isinstance(current, yaml.MappingNode)
                else current.value
            )
            size = 1 + sum(sizes[id(c)] for c in children)
            if size > MAX_EXPANDED_NODES:
                raise yaml.constructor.ConstructorError(
                    None, None,
                    "the document expands to too many values through its aliases "
                    "(an alias bomb?); refusing it",
                    current.start_mark,
                )
            sizes[key] = size
            continue
        if key in sizes:
            continue
        if current.tag not in _ALLOWED_TAGS:
            raise yaml.constructor.ConstructorError(
                None, None,
                f"the YAML tag {_tag_name(current.tag)!r} is not allowed in a catalogue "
                "(it could build objects or run code); write plain values",
                current.start_mark,
            )
        if isinstance(current, yaml.ScalarNode):
            sizes[key] = 1
            continue
        sizes[key] = 0  # provisional: guards against recursive aliases
        stack.append((current, True))
        children = (
            [n for pair in current.value for n in pair]
            if isinstance(current, yaml.MappingNode)
            else current.value
        )
        for child in children:
            if sizes.get(id(child)) == 0:  # still being expanded: an ancestor
                raise yaml.constructor.ConstructorError(
                    None, None,
                    "an alias refers to a value that contains it (a recursive structure); "
                    "refusing it",
                    current.start_mark,
                )
            stack.append((child, False))


_TOO_DEEP = f"values are nested more than {MAX_DEPTH} levels deep; a catalogue needs fewer than 10"


def _check_depth(text: str) -> None:
    """Refuse documents nested deeper than :data:`MAX_DEPTH`, before composing them.

    Only events are read (libyaml's parser keeps its own stack), and reading
    stops at the first level too deep, so a hostile document costs little.
    """
    loader = _Loader(text)
    try:
        depth = 0
        while loader.check_event():
            event: Any = loader.get_event()
            if isinstance(event, yaml.CollectionStartEvent):
                depth += 1
                if depth > MAX_DEPTH:
                    mark: Any = event.start_mark
                    raise yaml.constructor.ConstructorError(
                        None, None,
                        _TOO_DEEP,
                        mark,
                    )
            elif isinstance(event, yaml.CollectionEndEvent):
                depth -= 1
    finally:
        loader.dispose()


#: Characters YAML does not allow in a stream (C0/C1 controls other than tab/newlines, ...).
_NON_PRINTABLE = re.compile(
    "[^\x09\x0a\x0d\x20-\x7e\x85\xa0-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]"
)


def _check_characters(text: str, name: str) -> None:
    bad = _NON_PRINTABLE.search(text)
    if bad is not None:
        at = bad.start()
        line = text.count("\n", 0, at) + 1
        column = at - (text.rfind("\n", 0, at) + 1) + 1
        raise CatalogError(Problem(
            f"the character U+{ord(bad.group()):04X} (a control character) is not allowed "
            "in YAML; remove it", name, line, column))


def _parse(text: str, name: str) -> Any:
    """Parse YAML text to plain Python data, raising located :class:`CatalogError`."""
    _check_characters(text, name)
    try:
        _check_depth(text)
        with _gc_paused():
            # the node tree is freed before the collector resumes: only the data is new
            return _construct(_Loader(text), text)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        message = exc.problem or "invalid YAML"
        if "nesting depth" in message:
            # PyYAML >= 6.0.2 has a nesting limit of its own that may answer before ours
            message = _TOO_DEEP
        if exc.context and exc.problem_mark is not None:
            message = f"{message} ({exc.context})"
        if mark is None:
            raise CatalogError(Problem(message, name)) from None
        raise CatalogError(Problem(message, name, mark.line + 1, mark.column + 1)) from None
    except yaml.YAMLError as exc:
        raise CatalogError(Problem(f"invalid YAML: {exc}", name)) from None


def _construct(loader: Any, text: str) -> Any:
    """Compose and construct the single document of ``text``."""
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        if "&" in text or "!" in text:
            _check_nodes(node)
        elif "<<" not in text:
            try:
                return _build(node)
            except (_Unusual, RecursionError, ValueError, OverflowError):
                pass  # PyYAML's constructor builds it, or places the error
        return loader.construct_document(node)
    finally:
        loader.dispose()


def _read_text(path: Path, name: str) -> str:
    try:
        with path.open("rb") as handle:
            raw = handle.read(MAX_FILE_BYTES + 1)
    except FileNotFoundError:
        raise CatalogError(Problem("no such file or directory", name)) from None
    except IsADirectoryError:
        raise CatalogError(
            Problem("is a directory; give the catalogue files in it (e.g. DIR/*.yaml)", name)
        ) from None
    except OSError as exc:
        raise CatalogError(Problem(f"cannot read: {exc.strerror or exc}", name)) from None
    if len(raw) > MAX_FILE_BYTES:
        raise CatalogError(
            Problem(f"the file is larger than {MAX_FILE_BYTES // 2**20} MiB; "
                    "that is not a catalogue", name)
        )
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise CatalogError(Problem("the file is UTF-16 text; save the catalogue as UTF-8",
                                   name, 1, 1))
    if b"\0" in raw:
        at = raw.index(b"\0")
        before = raw[:at]
        raise CatalogError(
            Problem("binary data (a NUL byte), not a YAML text file", name,
                    before.count(b"\n") + 1, at - (before.rfind(b"\n") + 1) + 1)
        )
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        before = raw[: exc.start]
        line = before.count(b"\n") + 1
        column = exc.start - (before.rfind(b"\n") + 1) + 1
        raise CatalogError(
            Problem(
                f"not UTF-8 text (byte 0x{raw[exc.start]:02x}); save the catalogue as UTF-8",
                name, line, column,
            )
        ) from None


# ---------------------------------------------------------------- locating errors


def _compose(text: str) -> Any:
    """The node tree of ``text`` (None when it cannot be composed)."""
    try:
        return yaml.compose(text, Loader=_Loader)
    except (yaml.YAMLError, RecursionError):
        return None


def _find(root: Any, path: Sequence[Any], want_key: bool) -> tuple[Any, tuple[int, int] | None]:
    """The node at ``path`` under ``root`` and its (line, column), 1-based.

    Where the path leaves the document (a missing key), the deepest node
    reached is returned. With ``want_key`` the last step gives the key's place.
    """
    if root is None:
        return None, None
    node = root
    mark = node.start_mark
    for i, part in enumerate(path):
        last = i == len(path) - 1
        if isinstance(node, yaml.MappingNode):
            for key_node, value_node in reversed(_flat_pairs(node)):
                if isinstance(key_node, yaml.ScalarNode) and key_node.value == str(part):
                    mark = key_node.start_mark if (last and want_key) else value_node.start_mark
                    node = value_node
                    break
            else:
                break
        elif isinstance(node, yaml.SequenceNode) and isinstance(part, int):
            if 0 <= part < len(node.value):
                node = node.value[part]
                mark = node.start_mark
            else:
                break
        else:
            break
    return node, (mark.line + 1, mark.column + 1)


def _flat_pairs(node: Any, depth: int = 0) -> list[tuple[Any, Any]]:
    """A mapping's key/value node pairs with ``<<`` merges expanded (merged first)."""
    pairs: list[tuple[Any, Any]] = []
    own: list[tuple[Any, Any]] = []
    for key_node, value_node in node.value:
        if key_node.tag == "tag:yaml.org,2002:merge" and depth < 8:
            merged = value_node.value if isinstance(value_node, yaml.SequenceNode) else [value_node]
            for m in merged:
                if isinstance(m, yaml.MappingNode):
                    pairs.extend(_flat_pairs(m, depth + 1))
        else:
            own.append((key_node, value_node))
    return pairs + own


def _locate(text: str, path: Sequence[Any], want_key: bool) -> tuple[int, int] | None:
    """Line and column (1-based) of the value at ``path`` in the YAML ``text``."""
    return _find(_compose(text), path, want_key)[1]


def _where(loc: Sequence[Any], data: Any) -> str:
    """A readable path: ``sensor 'fog-a': coefficients.k2``, ``profiles[2].rate[1]``."""
    parts: list[str] = []
    start = 0
    if (len(loc) >= 2 and loc[0] in ("sensors", "profiles") and isinstance(loc[1], int)
            and isinstance(data, dict)):
        items = data.get(loc[0])
        item = items[loc[1]] if isinstance(items, list) and loc[1] < len(items) else None
        ident = item.get("id") if isinstance(item, dict) else None
        if isinstance(ident, str) and re.fullmatch(r"[A-Za-z0-9._-]{1,80}", ident):
            parts.append(f"{loc[0][:-1]} {ident!r}")
            start = 2
    text = ""
    for part in loc[start:]:
        if isinstance(part, int):
            text += f"[{part}]"
        else:
            text += ("." if text else "") + str(part)
    if parts and text:
        return f"{parts[0]}: {text}"
    return parts[0] if parts else text


def _describe(value: Any) -> str:
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
    if isinstance(value, list):
        return "a list"
    if isinstance(value, int) and abs(value) > 10**20:
        return "an integer too large for a floating-point number"
    return repr(value)


def _scalar_text(node: Any) -> str | None:
    return node.value if isinstance(node, yaml.ScalarNode) else None


def _friendly(error: Mapping[str, Any], model_fields: Iterable[str] = (), data: Any = None,
              node: Any = None) -> str:
    """One pydantic error as a sentence: where, what is wrong, and what to write."""
    import difflib  # only on the error path: its import is slow

    kind = error["type"]
    loc = tuple(error["loc"])
    value = error.get("input")
    ctx = error.get("ctx") or {}
    where = _where(loc, data)
    parent = _where(loc[:-1], data)
    prefix = f"{parent}: " if parent else ""
    if kind == "extra_forbidden":
        key = str(loc[-1])
        fields = list(model_fields)
        message = f"{prefix}unknown key {key!r}"
        close = [f for f in fields if f.lower() == key.lower().replace("-", "_")] or \
            difflib.get_close_matches(key, fields, n=1, cutoff=0.6)
        if close:
            message += f"; did you mean {close[0]!r}?"
        elif fields:
            message += f"; allowed here: {', '.join(fields)}"
        return message
    if kind == "invalid_key":
        return f"{prefix}a key must be a name, not {_describe(value)}"
    if kind == "missing":
        if loc and isinstance(loc[-1], int):
            return f"{prefix}too few values (item {loc[-1] + 1} is missing)"
        return f"{prefix}missing required key {str(loc[-1])!r}" if loc else "missing required key"
    if loc == ("gyrovib",) and kind != "value_error":
        return f"gyrovib: the format version must be the number 1, not {_describe(value)}"
    if kind == "too_long":
        expected = ctx.get("max_length")
        have = ctx.get("actual_length")
        if expected is not None and have is not None and isinstance(value, (list, tuple)):
            return f"{where}: too many values ({have}; expected at most {expected})"
        return f"{where}: too many values"
    if kind == "too_short":
        expected = ctx.get("min_length")
        return f"{where}: too few values (at least {expected} needed)" if expected else \
            f"{where}: too few values"
    if kind == "finite_number" or (kind == "float_type" and isinstance(value, int)
                                    and not isinstance(value, bool)):
        text = (_scalar_text(node) or "").strip().lower()
        if "nan" in text:
            what = "NaN is not a number gyrovib accepts"
        elif "inf" in text:
            what = "infinities are not accepted"
        elif text:
            shown = text if len(text) <= 24 else f"{text[:12]}...({len(text)} characters)"
            what = f"{shown} overflows a floating-point number (max ~1.8e308)"
        else:
            what = "the value overflows or is not finite"
        return f"{where}: {what}; write a finite number"
    if kind in {"float_type", "int_type", "float_parsing", "int_parsing"}:
        return f"{where}: must be a number, not {_describe(value)}"
    if kind in {"greater_than_equal", "greater_than", "less_than_equal", "less_than"}:
        bound = ctx.get("ge", ctx.get("gt", ctx.get("le", ctx.get("lt"))))
        words = {"greater_than_equal": "must not be less than",
                 "greater_than": "must be greater than",
                 "less_than_equal": "must not be greater than",
                 "less_than": "must be less than"}[kind]
        what = f"{words} {bound}"
        if kind == "greater_than_equal" and bound == 0:
            what = "must not be negative"
        elif kind == "greater_than" and bound == 0:
            what = "must be positive (greater than 0)"
        if "coherence" in loc:
            what += " (a coherence lies in [-1, 1])"
        return f"{where}: {what}, got {value!r}"
    if kind == "string_pattern_mismatch" and loc and loc[-1] == "id":
        return (f"{where}: the id {value!r} may hold only letters, digits, '.', '_' and '-' "
                "(no spaces or slashes)")
    if kind == "string_too_short" and loc and loc[-1] == "id":
        return f"{where}: the id must not be empty"
    if kind in {"string_type", "str_type"}:
        return f"{where}: must be text, not {_describe(value)}"
    if kind == "literal_error":
        expected = str(ctx.get("expected", "")).replace("'", "")
        if loc and loc[-1] == "rate" and "units" in loc:
            known = expected.replace(" or", ",")
            return f"{where}: unknown rate unit {value!r}; use one of {known}"
        return f"{where}: {value!r} is not allowed; use one of {expected.replace(' or', ',')}"
    if kind in {"model_type", "model_attributes_type", "dict_type"}:
        return f"{where}: must be a mapping of keys to values, not {_describe(value)}"
    if kind in {"list_type", "tuple_type"}:
        return f"{where}: must be a list, not {_describe(value)}"
    msg = str(error["msg"])
    for lead in ("Value error, ", "Assertion failed, "):
        if msg.startswith(lead):
            msg = msg[len(lead):]
            break
    else:
        msg = msg[0].lower() + msg[1:] if msg.startswith("Input ") else msg
    return f"{where}: {msg}" if where else msg


def _fields_at(loc: Sequence[Any]) -> list[str]:
    """Known keys of the model that holds ``loc`` (for typo suggestions)."""
    from gyrovib.catalog import schema

    model: Any = schema.CatalogFile
    for part in loc[:-1]:
        if isinstance(part, int):
            continue
        field = model.model_fields.get(part)
        if field is None:
            return []
        annotation = str(field.annotation)
        for candidate in (
            schema.Sensor, schema.Profile, schema.OutputCoefficients, schema.Coefficients,
            schema.Tone, schema.Random, schema.PSD, schema.Units, schema.Allocation,
        ):
            if re.search(rf"\b{candidate.__name__}\b", annotation):
                model = candidate
                break
        else:
            return []
    return list(model.model_fields)


def _validation_problems(exc: ValidationError, text: str, name: str,
                         data: Any = None) -> list[Problem]:
    root = _compose(text)
    problems = []
    for error in exc.errors()[:MAX_PROBLEMS]:
        loc = tuple(error["loc"])
        index = (error.get("ctx") or {}).get("index")
        if isinstance(index, int):  # a table check naming the offending row
            loc = (*loc, index)
        node, place = _find(root, loc,
                            want_key=error["type"] in ("extra_forbidden", "invalid_key"))
        message = _friendly(error, _fields_at(tuple(error["loc"])), data, node)
        if place is None:
            problems.append(Problem(message, name))
        else:
            problems.append(Problem(message, name, place[0], place[1]))
    problems.sort(key=lambda p: (p.line or 0, p.column or 0))
    hidden = exc.error_count() - MAX_PROBLEMS
    if hidden > 0:
        problems.append(Problem(f"... and {hidden} more problems", name))
    return problems


# ---------------------------------------------------------------- public API


@dataclass(frozen=True)
class CatalogSource:
    """One validated file: its name as given, its text and its model."""

    name: str
    text: str
    model: CatalogFile

    def locate(self, path: Sequence[Any]) -> tuple[int, int] | None:
        """Line and column of the value at ``path`` (e.g. ``("sensors", 3, "id")``)."""
        return _locate(self.text, path, want_key=False)

    def problem(self, message: str, path: Sequence[Any]) -> Problem:
        """A :class:`Problem` placed at ``path`` in this file."""
        place = self.locate(path)
        if place is None:
            return Problem(message, self.name)
        return Problem(message, self.name, *place)


def parse_catalog(text: str, name: str = "<string>") -> CatalogSource:
    """Parse and validate one catalogue given as text."""
    data = _parse(text, name)
    if data is None:
        raise CatalogError(
            Problem("the file is empty; a catalogue starts with 'gyrovib: 1'", name, 1, 1)
        )
    if not isinstance(data, dict):
        raise CatalogError(
            Problem(
                f"the top level must be a mapping with 'gyrovib: 1', not a {type(data).__name__}",
                name, 1, 1,
            )
        )
    if "gyrovib" not in data:
        raise CatalogError(
            Problem("missing 'gyrovib: 1' (the format version) at the top level", name, 1, 1)
        )
    try:
        with _gc_paused():
            model = records.catalog_file(data)
    except records.Unsure:
        model = _validate_with_schema(data, text, name)
    return CatalogSource(name=name, text=text, model=model)


def _validate_with_schema(data: Any, text: str, name: str) -> CatalogFile:
    """Validate with the pydantic models: located problems, or the records after all."""
    from pydantic import ValidationError

    from gyrovib.catalog import schema

    try:
        checked = schema.CatalogFile.model_validate(data)
    except ValidationError as exc:
        raise CatalogError(_validation_problems(exc, text, name, data)) from None
    try:  # valid, with something the fast validator leaves to pydantic (a huge int...)
        return records.catalog_file(checked.model_dump())
    except records.Unsure:  # pragma: no cover - the models' attributes are the same
        return cast(CatalogFile, checked)


def read_catalog(path: str | Path) -> CatalogSource:
    """Read, parse and validate one catalogue file."""
    name = str(path)
    return parse_catalog(_read_text(Path(path), name), name)


@dataclass(frozen=True)
class Entry:
    """A sensor or profile with the file it came from and its index there."""

    source: CatalogSource
    index: int

    @property
    def unit(self) -> str:
        return self.source.model.units.rate


@dataclass(frozen=True)
class SensorEntry(Entry):
    sensor: Sensor


@dataclass(frozen=True)
class ProfileEntry(Entry):
    profile: Profile


@dataclass(frozen=True)
class Catalog:
    """Sensors and profiles merged from one or more files, ids unique."""

    sources: tuple[CatalogSource, ...]
    sensors: tuple[SensorEntry, ...]
    profiles: tuple[ProfileEntry, ...]
    allocation: Allocation | None

    def sensor_line(self, entry: SensorEntry) -> tuple[int, int] | None:
        return entry.source.locate(("sensors", entry.index, "id"))


def _unique(sources: Sequence[CatalogSource], section: str,
            problems: list[Problem]) -> list[tuple[CatalogSource, int, Any]]:
    """The items of ``section`` ("sensors" or "profiles") of every file, in order,
    keeping the first of each id; a repeated id becomes a problem at its place."""
    kept: list[tuple[CatalogSource, int, Any]] = []
    first: dict[str, tuple[CatalogSource, int]] = {}
    kind = section[:-1]
    for source in sources:
        for i, item in enumerate(getattr(source.model, section)):
            if item.id in first:
                other, index = first[item.id]
                place = other.locate((section, index, "id"))
                at = f"{other.name}:{place[0]}" if place else other.name
                problems.append(source.problem(
                    f"duplicate {kind} id {item.id!r} (first at {at})", (section, i, "id")))
                continue
            first[item.id] = (source, i)
            kept.append((source, i, item))
    return kept


def merge(sources: Sequence[CatalogSource]) -> Catalog:
    """Merge validated files; an id used twice (in one file or across files) is an error."""
    problems: list[Problem] = []
    sensors = [SensorEntry(s, i, x) for s, i, x in _unique(sources, "sensors", problems)]
    profiles = [ProfileEntry(s, i, x) for s, i, x in _unique(sources, "profiles", problems)]
    allocation: Allocation | None = None
    allocation_source: CatalogSource | None = None
    for source in sources:
        if source.model.allocation is not None:
            if allocation is not None and source.model.allocation != allocation:
                assert allocation_source is not None
                problems.append(
                    source.problem(
                        f"a different allocation is already given in {allocation_source.name}",
                        ("allocation",),
                    )
                )
            allocation, allocation_source = source.model.allocation, source
    if problems:
        raise CatalogError(problems)
    return Catalog(tuple(sources), tuple(sensors), tuple(profiles), allocation)


def load_catalog(paths: Sequence[str | Path]) -> Catalog:
    """Read every file (collecting the problems of all of them), then merge."""
    problems: list[Problem] = []
    sources: list[CatalogSource] = []
    for path in paths:
        try:
            sources.append(read_catalog(path))
        except CatalogError as exc:
            problems.extend(exc.problems)
    if problems:
        try:  # the files that did parse may still clash: report that too
            merge(sources)
        except CatalogError as exc:
            problems.extend(exc.problems)
        raise CatalogError(problems)
    return merge(sources)


def bundled_paths() -> list[Path]:
    """The catalogues shipped with gyrovib, in name order."""
    here = Path(__file__).parent.parent / "catalogs"
    if here.is_dir():  # installed as files: no need for importlib.resources (slow import)
        root: Any = here
    else:
        from importlib.resources import files

        root = files("gyrovib") / "catalogs"
    return sorted(Path(str(p)) for p in root.iterdir() if p.name.endswith((".yaml", ".yml")))
