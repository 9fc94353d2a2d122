"""Loading catalogues: read a file, parse it, validate it, merge several.

Each file is read and parsed once (:mod:`gyrovib.catalog.dialect`) and the
whole document is validated into the models of :mod:`gyrovib.models` in one
call. When something is wrong, pydantic's errors are turned into sentences by
:mod:`gyrovib.catalog.messages` and placed by the file's
:class:`~gyrovib.catalog.locate.Index`, composed once per file and reused
(for every error, every duplicate id and every later ``locate``), so errors
read ``FILE:LINE:COL: message`` at a cost linear in the file.
"""

from __future__ import annotations

import os
from collections.abc import Collection, Sequence
from dataclasses import dataclass, field
from difflib import get_close_matches
from pathlib import Path
from types import SimpleNamespace
from typing import Any, NamedTuple, cast

from pydantic import ValidationError

from gyrovib.catalog import messages
from gyrovib.catalog.dialect import _gc_paused, line_column
from gyrovib.catalog.dialect import parse as _parse
from gyrovib.catalog.locate import Index
from gyrovib.catalog.messages import ID_KEY, SECTIONS, SHARED_KEY, VERSION_KEY, Error
from gyrovib.errors import CatalogError, Problem
from gyrovib.frozen import Frozen
from gyrovib.models import Allocation, Catalogue, Mission, Profile, Sensor, validate_document

#: Most problems reported for one file; the rest are summarised.
MAX_PROBLEMS = 50
#: Largest catalogue file read, in bytes.
MAX_FILE_BYTES = 16 * 1024 * 1024


def _capped(problems: list[Problem]) -> list[Problem]:
    """At most :data:`MAX_PROBLEMS` problems per file, in file order, then a summary."""
    by_file: dict[str | None, list[Problem]] = {}  # in order of first appearance
    for p in problems:
        by_file.setdefault(p.file, []).append(p)
    out: list[Problem] = []
    for name, found in by_file.items():
        out.extend(found[:MAX_PROBLEMS])
        if len(found) > MAX_PROBLEMS:
            out.append(Problem(f"... and {len(found) - MAX_PROBLEMS} more problems", name))
    return out


# ---------------------------------------------------------------- one file


@dataclass(frozen=True, eq=False, repr=False)
class CatalogSource(Frozen):
    """One validated file: its name as given, its text and its model
    (:class:`gyrovib.models.Catalogue`)."""

    name: str
    text: str
    model: Catalogue
    index: Index = field(default=None, compare=False, repr=False)  # type: ignore[assignment]

    def __post_init__(self) -> None:
        if self.index is None:
            object.__setattr__(self, "index", Index(self.text))

    def locate(self, path: Sequence[Any]) -> tuple[int, int] | None:
        """Line and column of the value at ``path`` (e.g. ``("sensors", 3, "id")``)."""
        return self.index.place(path)

    def problem(self, message: str, path: Sequence[Any]) -> Problem:
        """A :class:`Problem` placed at ``path`` in this file."""
        place = self.locate(path)
        if place is None:
            return Problem(message, self.name)
        return Problem(message, self.name, *place)


def _error_problems(errors: list[Error], data: Any, index: Index, name: str) -> list[Problem]:
    problems = []
    for error in errors:
        node, place = index.find(error.loc, want_key=error.kind in ("unknown_key", "bad_key"))
        text = node.value if error.kind == "finite" and isinstance(node.value, str) else None
        message = messages.message(error, data, text)
        problems.append(Problem(message, name, *place) if place else Problem(message, name))
    return problems


def _raw_duplicates(data: dict[str, Any], index: Index, name: str) -> list[Problem]:
    """Repeated ids in a file that is otherwise invalid (read from the raw data);
    only the first :data:`MAX_PROBLEMS` are placed in the file."""
    problems: list[Problem] = []
    for section, kind in SECTIONS:
        items = data.get(section)
        if not isinstance(items, list):
            continue
        first: dict[str, int] = {}
        for i, item in enumerate(items):
            ident = item.get(ID_KEY) if isinstance(item, dict) else None
            if not isinstance(ident, str):
                continue
            if ident in first:
                place = index.place((section, first[ident], ID_KEY))
                at = f"{name}:{place[0]}" if place else name
                message = f"duplicate {kind} id {ident!r} (first at {at})"
                here = index.place((section, i, ID_KEY)) if len(problems) < MAX_PROBLEMS else None
                problems.append(Problem(message, name, *here) if here else Problem(message, name))
            else:
                first[ident] = i
    return problems


def parse_catalog(text: str, name: str = "<string>",
                  skip: Collection[str] = ()) -> CatalogSource:
    """Parse and validate one catalogue given as text.

    ``skip``: top-level sections (``"sensors"``, ``"profiles"``) not wanted:
    read past by the parser, neither built nor validated, and empty in the
    model.
    """
    data = _parse(text, name, frozenset(skip))
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
    if VERSION_KEY not in data:
        raise CatalogError(
            Problem("missing 'gyrovib: 1' (the format version) at the top level", name, 1, 1)
        )
    try:
        with _gc_paused():
            model = validate_document(data)
    except ValidationError as exc:
        found = messages.errors(exc, data)
        index = Index(text)
        shown = _error_problems(found[:MAX_PROBLEMS], data, index, name)
        shown.extend(_raw_duplicates(data, index, name))
        hidden = len(found) - len(found[:MAX_PROBLEMS])
        shown.sort(key=lambda p: (p.line is None, p.line or 0, p.column or 0))
        hidden += len(shown[MAX_PROBLEMS:])
        problems = shown[:MAX_PROBLEMS]
        if hidden:
            problems.append(Problem(f"... and {hidden} more problems", name))
        raise InvalidCatalog(problems, _ids_only(data, name, text, index)) from None
    return CatalogSource(name=name, text=text, model=model)


class InvalidCatalog(CatalogError):
    """A file that is not valid; ``ids`` still lets its ids clash with other files'."""

    def __init__(self, problems: list[Problem], ids: CatalogSource) -> None:
        super().__init__(problems)
        self.ids = ids


class _Id(NamedTuple):
    id: Any


def _ids_only(data: dict[str, Any], name: str, text: str, index: Index) -> CatalogSource:
    """A stand-in source of an invalid file holding only its items' ids (None where an
    item has none), at their indices, for the duplicate-id check across files."""
    sections: dict[str, Any] = {}
    for section, _ in SECTIONS:
        items = data.get(section)
        sections[section] = [_Id(x.get(ID_KEY) if isinstance(x, dict) else None)
                             for x in (items if isinstance(items, list) else ())]
    model = cast(Catalogue, SimpleNamespace(**sections, allocation=None))
    return CatalogSource(name=name, text=text, model=model, index=index)


def model_source(model: Catalogue, name: str = "<gyrovib.models.Catalogue>") -> CatalogSource:
    """A catalogue built in Python as a source: its text is the model as JSON (a YAML
    document; it identifies the content in a study's digest), and nothing is placed
    in it (a problem names ``name`` alone)."""
    import json  # not at import time: a first analyze does without it

    text = json.dumps(model.model_dump(mode="json", exclude_defaults=True), indent=1) + "\n"
    return CatalogSource(name=name, text=text, model=model, index=Index(""))


@dataclass(frozen=True, slots=True)
class Source:
    """Where a catalogue comes from: a file at ``path``, or ``data`` already read
    (standard input, a download) under ``name``. Both go through one loader
    (:func:`read_source`): the same bytes give the same message either way."""

    name: str
    path: str | Path | None = None
    data: bytes | None = None

    @classmethod
    def file(cls, path: str | Path) -> Source:
        return cls(str(path), path=path)

    @classmethod
    def of_bytes(cls, data: bytes, name: str) -> Source:
        return cls(name, data=data)


def read_source(source: Source, skip: Collection[str] = ()) -> CatalogSource:
    """Read, parse and validate one catalogue (``skip``: as :func:`parse_catalog`)."""
    if source.path is not None:
        raw = _read_bytes(_native(source.path), source.name)
    else:
        raw = source.data if source.data is not None else b""
    return parse_catalog(_decode(raw, source.name), source.name, skip)


def read_catalog(path: str | Path | Source, skip: Collection[str] = ()) -> CatalogSource:
    """Read, parse and validate one catalogue file (``skip``: as :func:`parse_catalog`)."""
    return read_source(path if isinstance(path, Source) else Source.file(path), skip)


def _native(path: str | Path) -> str:
    """The name :meth:`pathlib.Path.open` would open for ``path``: ``path`` itself when
    pathlib would not change it (a POSIX name without empty or ``.`` parts, nor a
    trailing slash), else ``str(Path(path))``: a plain name is not rebuilt."""
    if isinstance(path, str) and os.sep == "/" and os.altsep is None:
        parts = path.split("/")
        if path and "." not in parts and "" not in parts[1:]:
            return path
    return str(Path(path))


def _read_bytes(path: str, name: str) -> bytes:
    try:
        with open(path, "rb") as handle:
            return handle.read(MAX_FILE_BYTES + 1)
    except FileNotFoundError:
        raise CatalogError(Problem("no such file or directory", name)) from None
    except IsADirectoryError:
        raise CatalogError(
            Problem("is a directory; give the catalogue files in it (e.g. DIR/*.yaml)", name)
        ) from None
    except OSError as exc:
        raise CatalogError(Problem(f"cannot read: {exc.strerror or exc}", name)) from None


def _decode(raw: bytes, name: str) -> str:
    """A catalogue's bytes as text: UTF-8 (a BOM allowed), located refusals otherwise."""
    if len(raw) > MAX_FILE_BYTES:
        raise CatalogError(
            Problem(f"larger than {MAX_FILE_BYTES // 2**20} MiB; "
                    "that is not a catalogue", name)
        )
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise CatalogError(Problem("UTF-16 text, not UTF-8; save the catalogue as UTF-8",
                                   name, 1, 1))
    if b"\0" in raw:
        at = raw.index(b"\0")
        raise CatalogError(
            Problem("binary data (a NUL byte), not a YAML text file", name,
                    *line_column(raw[:at].decode("latin-1"), at))
        )
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise CatalogError(
            Problem(
                f"not UTF-8 text (byte 0x{raw[exc.start]:02x}); save the catalogue as UTF-8",
                name, *line_column(raw[:exc.start].decode("latin-1"), exc.start),
            )
        ) from None


# ---------------------------------------------------------------- several files


@dataclass(frozen=True, eq=False, repr=False)
class Entry(Frozen):
    """A sensor or profile with the file it came from and its index there."""

    source: CatalogSource
    index: int

    @property
    def unit(self) -> str:
        return self.source.model.rate_unit

    @property
    def acceleration_unit(self) -> str:
        """``"g"`` or ``"m/s^2"``: the unit of the file's accelerations (not converted)."""
        return self.source.model.acceleration_unit


@dataclass(frozen=True, eq=False, repr=False)
class SensorEntry(Entry):
    sensor: Sensor


@dataclass(frozen=True, eq=False, repr=False)
class ProfileEntry(Entry):
    profile: Profile


@dataclass(frozen=True, eq=False, repr=False)
class MissionEntry(Entry):
    """A mission with its file (whose ``units.rate`` its segments' rates are in)."""

    mission: Mission


@dataclass(frozen=True, eq=False, repr=False)
class Catalog(Frozen):
    """Sensors, profiles and missions merged from one or more files, ids unique."""

    sources: tuple[CatalogSource, ...]
    sensors: tuple[SensorEntry, ...]
    profiles: tuple[ProfileEntry, ...]
    allocation: Allocation | None
    missions: tuple[MissionEntry, ...] = ()

    @property
    def models(self) -> tuple[Catalogue, ...]:
        """The model of each file (:class:`gyrovib.models.Catalogue`), in order."""
        return tuple(s.model for s in self.sources)

    @property
    def sensor_models(self) -> tuple[Sensor, ...]:
        """The merged sensors as :class:`gyrovib.models.Sensor` (in the units of their
        files: see :attr:`Entry.unit`)."""
        return tuple(e.sensor for e in self.sensors)

    @property
    def profile_models(self) -> tuple[Profile, ...]:
        """The merged profiles as :class:`gyrovib.models.Profile` (file units)."""
        return tuple(e.profile for e in self.profiles)

    def __repr__(self) -> str:
        """One line: how many sensors, profiles and missions, from which files (not
        their contents)."""
        files = ", ".join(os.path.basename(s.name) for s in self.sources)
        missions = len(self.missions)
        return (f"Catalog({len(self.sensors)} sensors, {len(self.profiles)} profiles"
                + (f", {missions} mission{'s' if missions != 1 else ''}" if missions else "")
                + (f" from {files}" if files else "") + ")")


def _unique(sources: Sequence[CatalogSource], section: str, problems: list[Problem],
            reported_within: frozenset[int] = frozenset()
            ) -> list[tuple[CatalogSource, int, Any]]:
    """The items of ``section`` ("sensors" or "profiles") of every file, in order,
    keeping the first of each id; a repeated id becomes a problem at its place
    (each file's index is composed once, whatever the number of repeats).
    ``reported_within``: ids of sources whose own repeats are already reported."""
    kept: list[tuple[CatalogSource, int, Any]] = []
    first: dict[str, tuple[CatalogSource, int]] = {}
    kind = dict(SECTIONS)[section]
    for source in sources:
        reported = 0
        here: set[str] | None = set() if id(source) in reported_within else None
        for i, item in enumerate(getattr(source.model, section)):
            if not isinstance(item.id, str):
                continue
            if here is not None:
                if item.id in here:  # a repeat within the file: already reported
                    continue
                here.add(item.id)
            if item.id in first:
                reported += 1
                if reported > MAX_PROBLEMS:  # not shown: counted in the summary only
                    problems.append(Problem(f"duplicate {kind} id", source.name))
                    continue
                other, index = first[item.id]
                place = other.locate((section, index, ID_KEY))
                at = f"{other.name}:{place[0]}" if place else other.name
                problems.append(source.problem(
                    f"duplicate {kind} id {item.id!r} (first at {at})", (section, i, ID_KEY)))
                continue
            first[item.id] = (source, i)
            kept.append((source, i, item))
    return kept


def merge(sources: Sequence[CatalogSource],
          _reported_within: frozenset[int] = frozenset()) -> Catalog:
    """Merge validated files; an id used twice (in one file or across files) is an error."""
    problems: list[Problem] = []
    (sensor_key, _), (profile_key, _), (mission_key, _) = SECTIONS
    sensors = [SensorEntry(s, i, x)
               for s, i, x in _unique(sources, sensor_key, problems, _reported_within)]
    profiles = [ProfileEntry(s, i, x)
                for s, i, x in _unique(sources, profile_key, problems, _reported_within)]
    missions = [MissionEntry(s, i, x)
                for s, i, x in _unique(sources, mission_key, problems, _reported_within)]
    problems.extend(_unknown_profiles(missions, {p.profile.id for p in profiles}))
    allocation: Allocation | None = None
    allocation_source: CatalogSource | None = None
    for source in sources:
        if source.model.allocation is not None:
            if allocation is not None and source.model.allocation != allocation:
                assert allocation_source is not None
                problems.append(
                    source.problem(
                        f"a different allocation is already given in {allocation_source.name}",
                        (SHARED_KEY,),
                    )
                )
            allocation, allocation_source = source.model.allocation, source
    if problems:
        raise CatalogError(_capped(problems))
    return Catalog(tuple(sources), tuple(sensors), tuple(profiles), allocation,
                   tuple(missions))


def _unknown_profiles(missions: Sequence[MissionEntry], known: set[str]) -> list[Problem]:
    """A segment naming a profile that no file given defines, at its ``profile`` key.

    Checked after merging: a mission may fly profiles of another file."""
    problems: list[Problem] = []
    for entry in missions:
        if not isinstance(getattr(entry.mission, "segments", None), list):
            continue  # an invalid file's stand-in: its own problems are reported
        for k, segment in enumerate(entry.mission.segments):
            if segment.profile in known:
                continue
            near = get_close_matches(segment.profile, sorted(known), n=1)
            hint = f" (did you mean {near[0]!r}?)" if near else (
                " (give the file that defines it too)" if not known else "")
            problems.append(entry.source.problem(
                f"mission {entry.mission.id!r}, segment {k + 1}: unknown profile "
                f"{segment.profile!r}{hint}",
                ("missions", entry.index, "segments", k, "profile")))
            if len(problems) >= MAX_PROBLEMS:
                return problems
    return problems


def load_catalog(paths: Sequence[str | Path | Source], skip: Collection[str] = ()) -> Catalog:
    """Read every file (collecting the problems of all of them), then merge.

    ``skip``: sections not loaded nor validated (:func:`parse_catalog`).
    """
    problems: list[Problem] = []
    sources: list[CatalogSource] = []
    everything: list[CatalogSource] = []  # with the ids of the invalid files, in order
    for path in paths:
        try:
            sources.append(read_catalog(path, skip))
            everything.append(sources[-1])
        except InvalidCatalog as exc:
            problems.extend(exc.problems)
            everything.append(exc.ids)
        except CatalogError as exc:
            problems.extend(exc.problems)
    if problems:
        try:  # the files may still clash, valid or not: report that too
            valid = {id(s) for s in sources}
            merge(everything, frozenset(id(s) for s in everything if id(s) not in valid))
        except CatalogError as exc:
            problems.extend(exc.problems)
        raise CatalogError(problems)
    return merge(sources)


def bundled_paths() -> list[Path]:
    """The catalogues shipped with gyrovib, in name order."""
    return [Path(p) for p in bundled_files()]


def bundled_files() -> list[str]:
    """:func:`bundled_paths` as strings, found with :mod:`os.path` when gyrovib is
    installed as files (importlib.resources and pathlib are slow imports)."""
    here = os.path.join(os.path.dirname(os.path.dirname(__file__)), "catalogs")
    if os.path.isdir(here):
        return sorted(os.path.join(here, name) for name in os.listdir(here)
                      if name.endswith((".yaml", ".yml")))
    from importlib.resources import files  # a zipped install only: a slow import

    root = files("gyrovib") / "catalogs"
    return [str(p) for p in
            sorted(Path(str(p)) for p in root.iterdir() if p.name.endswith((".yaml", ".yml")))]


__all__ = [
    "Catalog",
    "CatalogError",
    "CatalogSource",
    "Entry",
    "MissionEntry",
    "Profile",
    "ProfileEntry",
    "Sensor",
    "SensorEntry",
    "bundled_files",
    "bundled_paths",
    "load_catalog",
    "merge",
    "model_source",
    "parse_catalog",
    "read_catalog",
]
