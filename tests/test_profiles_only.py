"""Loading profiles only (``api.load(paths, sensors=False)``, a library shortcut):
the ``sensors:`` sections are read past by the YAML parser, neither built nor
validated; what is not YAML at all is still refused, located. No command uses
it: ``bounds`` validates the whole file as ``validate`` does."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from gyrovib import api
from gyrovib.catalog.dialect import MAX_DEPTH, TOO_DEEP, parse
from gyrovib.errors import CatalogError
from tests.conftest import invoke

PROFILES = textwrap.dedent("""\
    profiles:
      - id: tone
        rate: [0, 0, 1]
        harmonic: [{frequency: 100, amplitude: [0, 0, 2.0]}]
      - id: random
        random: {rms: [0, 0, 1.5]}
    """)

#: Two sensors the validator refuses (a text where a number goes; a list where an
#: entry goes), between the header and the profiles.
BAD_SENSORS = textwrap.dedent("""\
    gyrovib: 1
    sensors:
      - id: bad
        coefficients: {k2: abc}
      - [[1, 2], [3]]
    """) + PROFILES


def write(tmp_path: Path, text: str, name: str = "cat.yaml") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_the_bundled_profiles_are_the_same_loaded_alone() -> None:
    whole, alone = api.load(), api.load(sensors=False)
    assert alone.sensors == ()
    assert [p.profile for p in alone.profiles] == [p.profile for p in whole.profiles]
    assert [p.index for p in alone.profiles] == [p.index for p in whole.profiles]


def test_invalid_sensors_are_skipped_by_the_shortcut_but_refused_by_bounds_and_validate(
        tmp_path: Path) -> None:
    path = write(tmp_path, BAD_SENSORS)
    assert api.load([path], sensors=False).profiles[1].profile.id == "random"
    with pytest.raises(CatalogError):
        api.load([path])
    for command in (["bounds", path, "--budget", "0.01", "--format", "csv"],
                    ["validate", path]):
        result = invoke(*command)
        assert result.exit_code == 2, result.stderr
        assert result.stdout == ""
        assert f"{path}:4:24:" in result.stderr


def test_bounds_equals_bounds_of_the_profiles_alone(tmp_path: Path) -> None:
    good_sensors = BAD_SENSORS.replace("{k2: abc}", "{k2: 1.0e-7}").replace(
        "  - [[1, 2], [3]]\n", "")
    with_sensors = write(tmp_path, good_sensors, "a.yaml")
    alone = write(tmp_path, "gyrovib: 1\n" + PROFILES, "b.yaml")
    first = invoke("bounds", with_sensors, "--budget", "0.01", "--format", "json")
    second = invoke("bounds", alone, "--budget", "0.01", "--format", "json")
    assert first.exit_code == second.exit_code == 0
    assert first.stdout == second.stdout


def test_what_is_not_yaml_in_the_skipped_sensors_is_still_refused(tmp_path: Path) -> None:
    broken = BAD_SENSORS.replace("[[1, 2], [3]]", "[[1, 2], [3]")  # an unclosed list
    path = write(tmp_path, broken)
    with pytest.raises(CatalogError) as caught:
        api.load([path], sensors=False)
    assert caught.value.problems[0].line == 6  # where the parser found the list unclosed


def test_nesting_too_deep_in_the_skipped_sensors_is_refused_at_its_place() -> None:
    deep = "[" * (MAX_DEPTH + 1) + "]" * (MAX_DEPTH + 1)
    text = f"gyrovib: 1\nsensors:\n  - {deep}\n" + PROFILES
    with pytest.raises(CatalogError) as caught:
        parse(text, "deep.yaml", frozenset({"sensors"}))
    problem = caught.value.problems[0]
    assert problem.message == TOO_DEEP
    assert problem.line == 3


@pytest.mark.parametrize("text", [
    BAD_SENSORS,
    # anchors and aliases: composed as a node tree, the sensors dropped after
    BAD_SENSORS.replace("coefficients: {k2: abc}", "coefficients: &c {k2: abc}")
    + "  - id: aliased\n    random: {rms: [0, 0, 1.5]}\n    extra: *c\n",
    # a scalar, and an empty value, in place of the list
    "gyrovib: 1\nsensors: 5\n" + PROFILES,
    "gyrovib: 1\nsensors:\n" + PROFILES,
])
def test_skipping_leaves_the_rest_of_the_data_as_parsed(text: str) -> None:
    whole = parse(text, "cat.yaml")
    skipped = parse(text, "cat.yaml", frozenset({"sensors"}))
    del whole["sensors"]
    assert skipped == whole
