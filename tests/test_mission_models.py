"""The `missions:` format (docs/model.md section 12, docs/missions.md): models,
located errors (an unknown profile across files, a mirror-image placement, a bad
duration), unique ids, and the third coherence ρ12."""

from __future__ import annotations

from pathlib import Path

import pytest

from gyrovib.catalog.loader import load_catalog
from gyrovib.errors import CatalogError
from gyrovib.models import Catalogue, Mission
from tests.conftest import invoke

PROFILES = """\
gyrovib: 1
profiles:
  - id: hover
    rate: [0, 0, 2]
    random: {rms: [1, 2, 3], coherence: [0.5, 0.4, 0.2]}
  - id: cruise
    random: {rms: [1, 1, 1]}
"""

MISSIONS = """\
gyrovib: 1
units: {rate: deg/h}
missions:
  - id: flight
    placement: {x1: +Y, x2: +Z, x3: +X}
    segments:
      - {profile: hover, duration: 10 min}
      - {profile: cruise, duration: 2 h, rate: [0, 0, 36]}
      - {profile: hover, duration: 30.5}
"""


def _write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_durations_in_seconds_and_profiles_from_another_file(tmp_path: Path) -> None:
    catalog = load_catalog([_write(tmp_path, "p.yaml", PROFILES),
                            _write(tmp_path, "m.yaml", MISSIONS)])
    (entry,) = catalog.missions
    m = entry.mission
    # 10 min = 600 s, 2 h = 7200 s, 30.5 s as written
    assert [s.duration for s in m.segments] == [600.0, 7200.0, 30.5]
    assert m.segments[1].rate == (0.0, 0.0, 36.0)
    assert entry.unit == "deg/h"
    assert m.placement_text == "x1=+Y,x2=+Z,x3=+X"
    assert catalog.profiles[0].profile.random.coherence == (0.5, 0.4, 0.2)


def test_triad_and_default_placements() -> None:
    triad = Mission(id="m", placement="triad", segments=[{"profile": "p", "duration": 1}])
    assert triad.placement_text == "triad"
    plain = Mission(id="m", segments=[{"profile": "p", "duration": "1 h"}])
    assert plain.placement_text == "default" and plain.segments[0].duration == 3600.0


def test_an_unknown_profile_is_located_at_the_segment(tmp_path: Path) -> None:
    # only the missions file: 'hover' and 'cruise' are defined nowhere
    path = _write(tmp_path, "m.yaml", MISSIONS)
    with pytest.raises(CatalogError) as info:
        load_catalog([path])
    text = [str(p) for p in info.value.problems]
    # line 7 col 19 is 'hover' in "      - {profile: hover, ..."
    assert text[0] == (f"{path}:7:19: mission 'flight', segment 1: unknown profile 'hover' "
                       "(give the file that defines it too)")
    assert len(text) == 3


def test_a_typo_in_a_profile_suggests_the_near_id(tmp_path: Path) -> None:
    path = _write(tmp_path, "m.yaml", MISSIONS.replace("profile: cruise", "profile: cruse"))
    result = invoke("validate", _write(tmp_path, "p.yaml", PROFILES), path)
    assert result.exit_code == 2
    assert f"{path}:8:19: mission 'flight', segment 2: unknown profile 'cruse' " \
           "(did you mean 'cruise'?)" in result.stderr


@pytest.mark.parametrize(("placement", "fragment"), [
    ("{x1: +Y, x2: +X, x3: +Z}", "has determinant -1: it is a mirror image"),
    ("{x1: -X, x2: +Y, x3: +Z}", "has determinant -1: it is a mirror image"),
    ("{x1: +X, x2: +X, x3: +Z}", "three different vehicle axes"),
    ("{x1: +X, x2: +Y, x3: up}", "x3"),
    ("sideways", "placement"),
])
def test_bad_placements_are_located(tmp_path: Path, placement: str, fragment: str) -> None:
    text = MISSIONS.replace("{x1: +Y, x2: +Z, x3: +X}", placement)
    path = _write(tmp_path, "m.yaml", text)
    result = invoke("validate", _write(tmp_path, "p.yaml", PROFILES), path)
    assert result.exit_code == 2
    assert f"{path}:5:" in result.stderr and fragment in result.stderr


@pytest.mark.parametrize(("duration", "fragment"), [
    ("10 fortnights", "cannot read the duration '10 fortnights'"),
    ("-3", "must be positive"),
    ("0 min", "must be positive"),
    ("true", "number"),
])
def test_bad_durations_are_located(tmp_path: Path, duration: str, fragment: str) -> None:
    text = MISSIONS.replace("duration: 30.5", f"duration: {duration}")
    path = _write(tmp_path, "m.yaml", text)
    result = invoke("validate", _write(tmp_path, "p.yaml", PROFILES), path)
    assert result.exit_code == 2
    assert f"{path}:9:" in result.stderr and fragment in result.stderr, result.stderr


def test_mission_ids_are_unique_across_files(tmp_path: Path) -> None:
    a = _write(tmp_path, "a.yaml", MISSIONS)
    b = _write(tmp_path, "b.yaml", MISSIONS)
    result = invoke("validate", _write(tmp_path, "p.yaml", PROFILES), a, b)
    assert result.exit_code == 2
    assert f"{b}:4:9: duplicate mission id 'flight' (first at {a}:4)" in result.stderr


def test_a_fourth_coherence_is_refused() -> None:
    from pydantic import ValidationError

    with pytest.raises(ValidationError):
        Catalogue.model_validate({"gyrovib": 1, "profiles": [
            {"id": "p", "random": {"rms": [1, 1, 1], "coherence": [0.1, 0.2, 0.3, 0.4]}}]})
