"""Choosing catalogue entries, and where they are written.

The first step of every command: the merged catalogue in, the chosen sensors
and profiles out (in catalogue order), and the (file, line) of each for
messages and annotations.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import yaml

from gyrovib.catalog.loader import (
    Catalog,
    ProfileEntry,
    SensorEntry,
    Source,
    bundled_files,
    load_catalog,
)
from gyrovib.errors import OptionError, literal

if TYPE_CHECKING:
    from pathlib import Path

#: (file, 1-based line) of an entry's ``id:``; ``(None, None)`` when unknown.
Location = tuple[str | None, int | None]


#: What ``bundled`` may add: the bundled file(s) of each choice, by name.
BUNDLED_CHOICES = ("sensors", "profiles", "all")


def bundled_choice(which: str) -> list[str]:
    """The bundled catalogue files of ``which``: ``sensors``, ``profiles`` or ``all``."""
    if which not in BUNDLED_CHOICES:
        raise OptionError(f"unknown bundled catalogue {which!r}; use one of "
                          f"{', '.join(BUNDLED_CHOICES)}")
    found = bundled_files()
    if which == "all":
        return found
    return [f for f in found if os.path.basename(f).startswith(which + ".")]


def load(paths: Sequence[str | Path | Source] = (), *, sensors: bool = True,
         bundled: str | None = None) -> Catalog:
    """Load and merge catalogue files; no paths means the bundled catalogues.

    A :class:`~gyrovib.catalog.loader.Source` stands for a file or for bytes
    read elsewhere (standard input), read by the same loader.

    ``bundled`` (``"sensors"``, ``"profiles"`` or ``"all"``) adds those bundled
    catalogues after ``paths`` (e.g. your own profiles with the bundled
    sensors; ids must stay unique across the files). ``sensors=False``: the
    profiles only. The ``sensors:`` sections are read past by the YAML parser,
    neither built nor validated: a library shortcut for profiles alone. No
    command uses it; every command validates each file whole.
    """
    files: list[str | Path | Source] = [p if isinstance(p, Source) else str(p) for p in paths]
    if bundled is not None:
        files += [f for f in bundled_choice(bundled) if f not in files]
    return load_catalog(files if files else bundled_files(),
                        skip=() if sensors else ("sensors",))


def select_entries(
    catalog: Catalog, sensors: Sequence[str] = (), profiles: Sequence[str] = (),
    need: Sequence[str] = ("sensors", "profiles"),
) -> tuple[tuple[SensorEntry, ...], tuple[ProfileEntry, ...]]:
    """The sensors and profiles named (all when none are named), in catalogue order.

    A catalogue without any of the kinds in ``need`` is an error: a check run
    on nothing would pass vacuously (a CI gate given only the sensors file).
    """
    missing = [kind for kind in need if not getattr(catalog, kind)]
    if missing:
        files = ", ".join(s.name for s in catalog.sources) or "the catalogue"
        raise OptionError(reason=(
            f"no {' and no '.join(missing)} in {literal(files)}: give a file that has them too, "
            "or add the bundled ones ({bundled} "
            f"{missing[0] if len(missing) == 1 else 'all'}), "
            "or no FILE at all for the bundled catalogues"), others=("bundled",))
    s_ids = [e.sensor.id for e in catalog.sensors]
    p_ids = [e.profile.id for e in catalog.profiles]
    s_idx = _pick(s_ids, sensors, "sensor")
    p_idx = _pick(p_ids, profiles, "profile")
    return (tuple(catalog.sensors[i] for i in s_idx), tuple(catalog.profiles[i] for i in p_idx))


def _pick(ids: list[str], wanted: Sequence[str], what: str) -> tuple[int, ...]:
    if not wanted:
        return tuple(range(len(ids)))
    known_ids = set(ids)
    unknown = [w for w in dict.fromkeys(wanted) if w not in known_ids]
    if unknown:
        known = ", ".join(ids) if len(ids) <= 20 else ", ".join(ids[:20]) + ", ..."
        raise OptionError(
            f"unknown {what} id {', '.join(map(repr, unknown))}; the catalogue has: {known}"
        )
    chosen = set(wanted)
    return tuple(i for i, x in enumerate(ids) if x in chosen)


# ----------------------------------------------------------------- locations


def sensor_locations(catalog: Catalog, ids: Sequence[str]) -> list[Location]:
    """The (file, line) of each sensor id's ``id:``, all in one pass.

    Each file is composed once, whatever the number of sensors: the cost is
    linear in the size of the catalogue (a per-sensor lookup re-parsing the
    file was quadratic: 2,000 sensors took minutes). Unknown ids give
    ``(None, None)``.
    """
    by_id = {e.sensor.id: e for e in catalog.sensors}
    return _locations([by_id.get(i) for i in ids], "sensors")


def profile_locations(catalog: Catalog, ids: Sequence[str]) -> list[Location]:
    """As :func:`sensor_locations`, for profiles."""
    by_id = {e.profile.id: e for e in catalog.profiles}
    return _locations([by_id.get(i) for i in ids], "profiles")


def sensor_location(catalog: Catalog, sensor_id: str) -> Location:
    """The file and 1-based line where a sensor is defined (its ``id:``).

    ``(None, None)`` for an id the catalogue does not have; the line is None
    when it cannot be found. For many sensors use :func:`sensor_locations`.
    """
    return sensor_locations(catalog, [sensor_id])[0]


def profile_location(catalog: Catalog, profile_id: str) -> Location:
    """The file and 1-based line where a profile is defined (its ``id:``)."""
    return profile_locations(catalog, [profile_id])[0]


def _locations(entries: Sequence[SensorEntry | ProfileEntry | None],
               section: str) -> list[Location]:
    out: list[Location] = [(None, None)] * len(entries)
    by_source: dict[int, list[int]] = {}
    for k, entry in enumerate(entries):
        if entry is not None:
            by_source.setdefault(id(entry.source), []).append(k)
    for positions in by_source.values():
        source = entries[positions[0]].source  # type: ignore[union-attr]
        lines = _id_lines(source.text, section)
        for k in positions:
            entry = entries[k]
            assert entry is not None
            line = lines.get(entry.index)
            if line is None:  # not a plain `id:` of its own (e.g. merged in): ask the file
                place = source.locate((section, entry.index, "id"))
                line = place[0] if place else None
            out[k] = (source.name, line)
    return out


def _id_lines(text: str, section: str) -> dict[int, int]:
    """Item index → 1-based line of its own ``id:`` value, from one compose of ``text``.

    The text is a catalogue that already passed validation, so composing it is
    safe; an item whose ``id`` is not a key of its own is left out.
    """
    loader: Any = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    try:
        root = yaml.compose(text, Loader=loader)
    except (yaml.YAMLError, RecursionError):
        return {}
    items = _value(root, section)
    if not isinstance(items, yaml.SequenceNode):
        return {}
    lines: dict[int, int] = {}
    for index, item in enumerate(items.value):
        node = _value(item, "id")
        if node is not None:
            lines[index] = node.start_mark.line + 1
    return lines


def _value(node: Any, key: str) -> Any:
    """The value node of ``key`` in a mapping node (the last one, as YAML loads it)."""
    if not isinstance(node, yaml.MappingNode):
        return None
    found = None
    for key_node, value_node in node.value:
        if isinstance(key_node, yaml.ScalarNode) and key_node.value == key:
            found = value_node
    return found
