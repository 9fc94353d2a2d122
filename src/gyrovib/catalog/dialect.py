"""The YAML dialect of catalogue files, and the guards around it.

The dialect is the safe subset, resolved the way people write numbers:
``1e-5`` is a float (plain YAML 1.1 reads it as a string), ``yes``/``no``,
dates and sexagesimal numbers are *not* special. Only plain mappings,
sequences and scalars are constructed; any tag that would build an object is
refused. libyaml's ``CSafeLoader`` is used when PyYAML was built with it.

Guards, all in the one pass that builds the data: control characters, object
tags, alias bombs and recursive aliases, and nesting deeper than
:data:`MAX_DEPTH`. Nesting is refused by whichever meets it first: libyaml's
own limit (1000 levels, "exceeded maximum nesting depth"), the node-tree walk
that builds the data, or, with PyYAML's pure-Python parser (which recurses and
has no limit of its own), the composer below. All give the same located
message. On the happy path the data is built straight from the node tree;
anything unusual (tags, anchors, merge keys, duplicate keys) goes through
PyYAML's own constructor.
"""

from __future__ import annotations

import gc
import math
import re
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import yaml

from gyrovib.errors import CatalogError, Problem

_BaseLoader: Any = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

#: Expanded size above which a document with aliases is refused (alias bombs).
MAX_EXPANDED_NODES = 2_000_000
#: Deepest nesting of mappings and sequences accepted (a catalogue needs 7).
MAX_DEPTH = 64

TOO_DEEP = f"values are nested more than {MAX_DEPTH} levels deep; a catalogue needs fewer than 10"

_YAML_PREFIX = "tag:yaml.org,2002:"


def _tag_name(tag: str) -> str:
    """A tag as it is written in the file: ``!!python/name:x`` rather than the URI."""
    return "!!" + tag[len(_YAML_PREFIX):] if tag.startswith(_YAML_PREFIX) else tag


_Mixin: Any = object  # typed as Any: the methods below extend PyYAML's loaders


class _Dialect(_Mixin):  # type: ignore[misc]
    """Safe loading with YAML 1.2-style scalars and duplicate-key detection
    (mixed into PyYAML's safe loader, libyaml's or the pure-Python one)."""

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

    def compose_node(self, parent: Any, index: Any) -> Any:
        """PyYAML's pure-Python composer recurses per level: stop it at MAX_DEPTH
        (libyaml composes in C and refuses deep nesting by itself)."""
        depth = self.__dict__.get("_depth", 0)
        if depth > MAX_DEPTH:
            raise yaml.composer.ComposerError(None, None, TOO_DEEP, self.peek_event().start_mark)
        self._depth = depth + 1
        try:
            return super().compose_node(parent, index)
        finally:
            self._depth = depth

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


def _resolvers(base: Any) -> dict[Any, list[tuple[str, re.Pattern[str]]]]:
    """The implicit resolvers of the dialect: null, merge, and YAML 1.2 core
    booleans, integers and floats (``1e-5`` is a float)."""
    keep = {"tag:yaml.org,2002:null", "tag:yaml.org,2002:merge"}
    resolvers: dict[Any, list[tuple[str, re.Pattern[str]]]] = {}
    for first, entries in base.yaml_implicit_resolvers.items():
        kept = [(tag, rx) for tag, rx in entries if tag in keep]
        if kept:
            resolvers[first] = kept
    added = (
        ("tag:yaml.org,2002:bool", r"^(?:true|True|TRUE|false|False|FALSE)$", "tTfF"),
        ("tag:yaml.org,2002:int", r"^[-+]?(?:0|[1-9][0-9]*)$", "-+0123456789"),
        ("tag:yaml.org,2002:float",
         r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?"
         r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$", "-+0123456789."),
    )
    for tag, pattern, firsts in added:
        regexp = re.compile(pattern)
        for first in firsts:
            resolvers.setdefault(first, []).append((tag, regexp))
    return resolvers


_STR = "tag:yaml.org,2002:str"
#: Implicit resolvers of a plain scalar by its first character ("" for empty).
_PLAIN_RESOLVERS = _resolvers(_BaseLoader)
assert None not in _PLAIN_RESOLVERS  # no wildcard resolver: dispatch on the first character


def loader_class(base: Any) -> Any:
    """The dialect's loader on top of one of PyYAML's safe loaders."""

    def resolve(self: Any, kind: Any, value: Any, implicit: Any) -> Any:
        """BaseResolver.resolve without its generality: there are no path resolvers."""
        if kind is yaml.ScalarNode:
            if implicit[0]:
                for tag, regexp in _PLAIN_RESOLVERS.get(value[:1], ()):
                    if regexp.match(value):
                        return tag
            return _STR
        return base.resolve(self, kind, value, implicit)

    return type("Loader", (_Dialect, base), {
        "yaml_implicit_resolvers": dict(_PLAIN_RESOLVERS), "resolve": resolve,
    })


#: The loader used: on libyaml's CSafeLoader when PyYAML has it.
Loader = loader_class(_BaseLoader)


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
_MERGE_TAG = "tag:yaml.org,2002:merge"


def _too_deep(mark: Any) -> yaml.MarkedYAMLError:
    return yaml.constructor.ConstructorError(None, None, TOO_DEEP, mark)


_NO_KEY: Any = object()


def _scalar(event: Any) -> Any:
    """The value of a plain or quoted scalar event without a tag."""
    value = event.value
    if event.implicit[0]:
        for tag, regexp in _PLAIN_RESOLVERS.get(value[:1], ()):
            if regexp.match(value):
                if tag == _MERGE_TAG:
                    raise _Unusual
                return _SCALARS[tag](value)
    return value


def _skip_value(get: Any) -> None:
    """Read past the events of one value (a scalar, an alias or a whole collection)
    without building it; nesting deeper than :data:`MAX_DEPTH` is still refused."""
    depth = 0
    while True:
        event = get()
        kind = type(event)
        if kind is yaml.MappingStartEvent or kind is yaml.SequenceStartEvent:
            depth += 1
            if depth >= MAX_DEPTH:
                raise _too_deep(event.start_mark)
        elif kind is yaml.MappingEndEvent or kind is yaml.SequenceEndEvent:
            depth -= 1
        if depth == 0:
            return


def _new_value(event: Any, kind: type, depth: int) -> Any:
    """The value a scalar event gives, or the empty container a collection starts
    (at ``depth`` open collections); a tag or an anchor is unusual."""
    if event.anchor is not None or event.tag is not None:
        raise _Unusual
    if kind is yaml.ScalarEvent:
        return _scalar(event)
    if depth >= MAX_DEPTH:
        raise _too_deep(event.start_mark)
    return {} if kind is yaml.MappingStartEvent else []


def _attach(stack: list[list[Any]], value: Any, get: Any, skip: frozenset[str]) -> None:
    """Put ``value`` into the innermost open collection: an item of a list, a key
    waiting for its value or the value of the waiting key. A top-level key in
    ``skip`` is read past with its value."""
    top = stack[-1]
    if not top[1]:
        top[0].append(value)
        return
    key = top[2]
    if key is not _NO_KEY:
        top[0][key] = value
        top[2] = _NO_KEY
        return
    if type(value) in (dict, list) or value in top[0]:
        raise _Unusual
    if skip and len(stack) == 1 and value in skip:
        _skip_value(get)
        return
    top[2] = value


#: The events that open a value (an alias, the one other kind of value, is unusual).
_VALUE_EVENTS = (yaml.ScalarEvent, yaml.MappingStartEvent, yaml.SequenceStartEvent)
_END_EVENTS = (yaml.MappingEndEvent, yaml.SequenceEndEvent)


def _stream(loader: Any, skip: frozenset[str] = frozenset()) -> Any:
    """Plain data of the single document of ``loader``, built from its events.

    No node tree is held: memory is that of the data only, whatever the size
    of the file. Anything unusual (a tag, an anchor or alias, a merge key, a
    duplicate or non-scalar key, a second document) raises :class:`_Unusual`
    and the node tree path takes over; nesting deeper than :data:`MAX_DEPTH`
    is refused at its place. The values of the top-level keys in ``skip`` are
    read past, neither built nor checked, and the keys left out.
    """
    get = loader.get_event
    get()  # StreamStartEvent
    if type(get()) is yaml.StreamEndEvent:  # no document at all
        return None
    scalar_event, map_start = yaml.ScalarEvent, yaml.MappingStartEvent
    # one entry per open collection: [container, is_mapping, key waiting for its value]
    stack: list[list[Any]] = []
    root: Any = None
    while True:
        event = get()
        kind = type(event)
        if kind in _END_EVENTS:
            stack.pop()
            continue
        if kind is yaml.DocumentEndEvent:
            if type(get()) is not yaml.StreamEndEvent:
                raise _Unusual  # a second document: the composer says so, located
            return root
        if kind not in _VALUE_EVENTS:  # an alias
            raise _Unusual
        value = _new_value(event, kind, len(stack))
        if stack:
            _attach(stack, value, get, skip)
        else:
            root = value
        if kind is not scalar_event:
            stack.append([value, kind is map_start, _NO_KEY])


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


def _children(node: Any) -> list[Any]:
    if isinstance(node, yaml.MappingNode):
        return [n for pair in node.value for n in pair]
    return node.value  # type: ignore[no-any-return]


def _check_nodes(node: Any) -> None:
    """Refuse object-building tags, alias bombs, recursive aliases and deep
    nesting (through aliases too) before anything is constructed."""
    sizes: dict[int, int] = {}
    heights: dict[int, int] = {}
    stack: list[tuple[Any, bool]] = [(node, False)]
    while stack:
        current, done = stack.pop()
        key = id(current)
        if done:
            children = _children(current)
            size = 1 + sum(sizes[id(c)] for c in children)
            if size > MAX_EXPANDED_NODES:
                raise yaml.constructor.ConstructorError(
                    None, None,
                    "the document expands to too many values through its aliases "
                    "(an alias bomb?); refusing it",
                    current.start_mark,
                )
            height = 1 + max((heights[id(c)] for c in children), default=0)
            if height > MAX_DEPTH:
                raise _too_deep(current.start_mark)
            sizes[key], heights[key] = size, height
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
            sizes[key], heights[key] = 1, 0
            continue
        sizes[key] = 0  # provisional: guards against recursive aliases
        stack.append((current, True))
        for child in _children(current):
            if sizes.get(id(child)) == 0:  # still being expanded: an ancestor
                raise yaml.constructor.ConstructorError(
                    None, None,
                    "an alias refers to a value that contains it (a recursive structure); "
                    "refusing it",
                    current.start_mark,
                )
            stack.append((child, False))


#: Characters YAML does not allow in a stream (C0/C1 controls other than tab/newlines, ...).
_NON_PRINTABLE = re.compile(
    "[^\x09\x0a\x0d\x20-\x7e\x85\xa0-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]"
)


def line_column(text: str, at: int) -> tuple[int, int]:
    """The 1-based line and column of character ``at`` of ``text`` (of byte ``at`` for
    bytes decoded as latin-1, one character a byte)."""
    return text.count("\n", 0, at) + 1, at - (text.rfind("\n", 0, at) + 1) + 1


def check_characters(text: str, name: str) -> None:
    bad = _NON_PRINTABLE.search(text)
    if bad is not None:
        raise CatalogError(Problem(
            f"the character U+{ord(bad.group()):04X} (a control character) is not allowed "
            "in YAML; remove it", name, *line_column(text, bad.start())))


def parse(text: str, name: str, skip: frozenset[str] = frozenset()) -> Any:
    """Parse YAML text to plain Python data, raising located :class:`CatalogError`.

    ``skip``: top-level keys whose values are not wanted (``"sensors"`` for a
    command that uses profiles only): left out of the data, and on the usual
    path never built, only read past by the parser (which still refuses what
    is not YAML).
    """
    check_characters(text, name)
    try:
        with _gc_paused():
            # any node tree is freed before the collector resumes: only the data is new
            return _construct(text, skip)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        message = exc.problem or "invalid YAML"
        if "nesting depth" in message:
            # libyaml (PyYAML >= 6.0.2) refuses 1000 levels itself: one message for all
            message = TOO_DEEP
        elif exc.context and exc.problem_mark is not None:
            message = f"{message} ({exc.context})"
        if mark is None:
            raise CatalogError(Problem(message, name)) from None
        raise CatalogError(Problem(message, name, mark.line + 1, mark.column + 1)) from None
    except yaml.YAMLError as exc:
        raise CatalogError(Problem(f"invalid YAML: {exc}", name)) from None


def _construct(text: str, skip: frozenset[str] = frozenset()) -> Any:
    """The single document of ``text`` as plain data: streamed from the parser's
    events when it is plain, else composed and checked (tags, aliases, merges);
    the top-level keys in ``skip`` left out."""
    if "&" not in text and "!" not in text and "<<" not in text:
        loader = Loader(text)
        try:
            return _stream(loader, skip)
        except (_Unusual, ValueError, OverflowError):
            pass  # PyYAML's composer and constructor build it, or place the error
        finally:
            loader.dispose()
    loader = Loader(text)
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        _check_nodes(node)
        data = loader.construct_document(node)
    finally:
        loader.dispose()
    if skip and isinstance(data, dict):
        for key in skip:
            data.pop(key, None)
    return data
