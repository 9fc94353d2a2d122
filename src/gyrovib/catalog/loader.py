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
from collections.abc import Iterable, Iterator, Sequence
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
                f"the YAML tag {current.tag!r} is not allowed in a catalogue; "
                "write plain values",
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
            if id(child) in sizes and sizes[id(child)] == 0 and child is not current:
                continue
            stack.append((child, False))


def _parse(text: str, name: str) -> Any:
    """Parse YAML text to plain Python data, raising located :class:`CatalogError`."""
    try:
        with _gc_paused():
            # the node tree is freed before the collector resumes: only the data is new
            return _construct(_Loader(text), text)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        message = exc.problem or "invalid YAML"
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
            except (_Unusual, RecursionError):
                pass
        return loader.construct_document(node)
    finally:
        loader.dispose()


def _read_text(path: Path, name: str) -> str:
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise CatalogError(Problem("no such file", name)) from None
    except IsADirectoryError:
        raise CatalogError(Problem("is a directory, not a catalogue file", name)) from None
    except OSError as exc:
        raise CatalogError(Problem(f"cannot read: {exc.strerror or exc}", name)) from None
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


def _locate(text: str, path: Sequence[Any], want_key: bool) -> tuple[int, int] | None:
    """Line and column (1-based) of the value at ``path`` in the YAML ``text``."""
    try:
        node = yaml.compose(text, Loader=_Loader)
    except yaml.YAMLError:
        return None
    if node is None:
        return None
    mark = node.start_mark
    for i, part in enumerate(path):
        last = i == len(path) - 1
        if isinstance(node, yaml.MappingNode):
            for key_node, value_node in reversed(node.value):
                if key_node.value == str(part):
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
    return mark.line + 1, mark.column + 1


_KNOWN_KEYS: dict[str, list[str]] = {}


def _friendly(error: Any, model_fields: Iterable[str] = ()) -> str:
    import difflib

    kind = error["type"]
    loc = error["loc"]
    where = ".".join(str(p) for p in loc)
    parent = ".".join(str(p) for p in loc[:-1])
    prefix = f"{parent}: " if parent else ""
    if kind == "extra_forbidden":
        key = str(loc[-1])
        message = f"{prefix}unknown key {key!r}"
        close = difflib.get_close_matches(key, list(model_fields), n=1)
        if close:
            message += f"; did you mean {close[0]!r}?"
        return message
    if kind == "missing":
        if loc and isinstance(loc[-1], int):
            return f"{prefix}too few values (item {loc[-1] + 1} is missing)"
        return f"{prefix}missing required key {str(loc[-1])!r}" if loc else "missing required key"
    if kind == "too_long":
        return f"{where}: too many values"
    msg = str(error["msg"])
    if msg.startswith("Value error, "):
        msg = msg[len("Value error, ") :]
    elif msg.startswith("Assertion failed, "):
        msg = msg[len("Assertion failed, ") :]
    if kind == "finite_number":
        msg = "must be a finite number (NaN, infinities and overflowing literals are refused)"
    elif kind in {"float_type", "int_type"}:
        msg = f"must be a number, not {type(error.get('input')).__name__}"
    else:
        msg = msg[0].lower() + msg[1:] if msg else msg
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
            schema.Sensor, schema.Profile, schema.Coefficients, schema.OutputCoefficients,
            schema.Tone, schema.Random, schema.PSD, schema.Units, schema.Allocation,
        ):
            if candidate.__name__ in annotation:
                model = candidate
                break
        else:
            return []
    return list(model.model_fields)


def _validation_problems(exc: ValidationError, text: str, name: str) -> list[Problem]:
    problems = []
    for error in exc.errors()[:MAX_PROBLEMS]:
        loc = tuple(error["loc"])
        message = _friendly(error, _fields_at(loc))
        place = _locate(text, loc, want_key=error["type"] == "extra_forbidden")
        if place is None:
            problems.append(Problem(message, name))
        else:
            problems.append(Problem(message, name, place[0], place[1]))
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
        raise CatalogError(_validation_problems(exc, text, name)) from None
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


def merge(sources: Sequence[CatalogSource]) -> Catalog:
    """Merge validated files; an id used twice (in one file or across files) is an error."""
    problems: list[Problem] = []
    sensors: list[SensorEntry] = []
    profiles: list[ProfileEntry] = []
    first_sensor: dict[str, SensorEntry] = {}
    first_profile: dict[str, ProfileEntry] = {}
    allocation: Allocation | None = None
    allocation_source: CatalogSource | None = None
    for source in sources:
        for i, sensor in enumerate(source.model.sensors):
            s_entry = SensorEntry(source, i, sensor)
            if sensor.id in first_sensor:
                other = first_sensor[sensor.id]
                place = other.source.locate(("sensors", other.index, "id"))
                at = f"{other.source.name}:{place[0]}" if place else other.source.name
                problems.append(
                    source.problem(f"duplicate sensor id {sensor.id!r} (first at {at})",
                                   ("sensors", i, "id"))
                )
                continue
            first_sensor[sensor.id] = s_entry
            sensors.append(s_entry)
        for i, profile in enumerate(source.model.profiles):
            p_entry = ProfileEntry(source, i, profile)
            if profile.id in first_profile:
                other_p = first_profile[profile.id]
                place = other_p.source.locate(("profiles", other_p.index, "id"))
                at = f"{other_p.source.name}:{place[0]}" if place else other_p.source.name
                problems.append(
                    source.problem(f"duplicate profile id {profile.id!r} (first at {at})",
                                   ("profiles", i, "id"))
                )
                continue
            first_profile[profile.id] = p_entry
            profiles.append(p_entry)
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
