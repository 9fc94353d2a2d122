"""``--bundled sensors|profiles|all`` on every command, and ``gyrovib catalog export``
(README, "Quick start")."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import gyrovib
from gyrovib.catalog.loader import bundled_files
from tests.conftest import invoke

OWN_PROFILES = """\
gyrovib: 1
units: {rate: deg/s}
profiles:
  - id: heli
    rate: [0, 0, 10]
    harmonic:
      - {frequency: 50, amplitude: [0.5, 0.5, 1.0]}
    acceleration:
      random: {rms: [3, 3, 3]}
"""


@pytest.fixture
def own(tmp_path: Path) -> str:
    path = tmp_path / "heli-profiles.yaml"
    path.write_text(OWN_PROFILES, encoding="utf-8")
    return str(path)


def bundled_ids(kind: str) -> list[str]:
    catalog = gyrovib.load()
    return [e.sensor.id for e in catalog.sensors] if kind == "sensors" else [
        e.profile.id for e in catalog.profiles]


def test_own_profiles_with_the_bundled_sensors(own: str) -> None:
    alone = invoke("analyze", own)
    assert alone.exit_code == 2 and "--bundled sensors" in alone.stderr
    done = invoke("analyze", own, "--bundled", "sensors", "--format", "json")
    assert done.exit_code == 0, done.stderr
    rows = json.loads(done.stdout)["results"]
    assert sorted({r["sensor"] for r in rows}) == sorted(bundled_ids("sensors"))
    assert {r["profile"] for r in rows} == {"heli"}  # the bundled profiles are not added
    # the same numbers as the library given both files
    sensors_file = next(f for f in bundled_files() if Path(f).name.startswith("sensors."))
    direct = gyrovib.analyze([own, sensors_file])
    # (an unknown total, a sensor without a g² figure under heli's linear vibration: null
    # in the JSON, NaN in the library)
    assert [r["total"] for r in rows] == [None if np.isnan(v) else float(v)
                                          for v in direct.error.total[:, 0]]


@pytest.mark.parametrize("command", [
    ("select", "--budget", "10deg/h", "--format", "json"),
    ("sweep", "--rate-range", "0:1:2", "--format", "json"),
    ("bounds", "--budget", "10deg/h", "--format", "json"),
])
def test_every_command_takes_it(own: str, command: tuple[str, ...]) -> None:
    extra = "profiles" if command[0] == "bounds" else "sensors"
    done = invoke(command[0], own, "--bundled", extra, *command[1:])
    assert done.exit_code in (0, 1), done.stderr
    doc = json.loads(done.stdout)
    if command[0] == "bounds":  # the bundled profiles beside heli
        assert [p["profile"] for p in doc["profiles"]] == ["heli", *bundled_ids("profiles")]


def test_report_and_validate_take_it(own: str, tmp_path: Path) -> None:
    out = tmp_path / "r.html"
    done = invoke("report", own, "--bundled", "sensors", "--budget", "10deg/h", "-o", str(out))
    assert done.exit_code == 0, done.stderr
    assert "adxrs645" in out.read_text(encoding="utf-8")
    checked = invoke("validate", own, "--bundled", "all")
    assert checked.exit_code == 0
    # the user's file and the three bundled ones (sensors, profiles, missions)
    assert (f"4 file(s) valid: {len(bundled_ids('sensors'))} sensor(s), "
            f"{len(bundled_ids('profiles')) + 1} profile(s)") in checked.stderr


def test_an_id_of_the_bundled_catalogue_twice_is_an_error(tmp_path: Path) -> None:
    clash = tmp_path / "clash.yaml"
    clash.write_text(OWN_PROFILES.replace("id: heli", "id: engine-harmonics"), encoding="utf-8")
    done = invoke("analyze", str(clash), "--bundled", "all")
    assert done.exit_code == 2 and "engine-harmonics" in done.stderr


def test_library_load_takes_it(own: str) -> None:
    catalog = gyrovib.load(own, bundled="sensors")
    assert [e.profile.id for e in catalog.profiles] == ["heli"]
    assert len(catalog.sensors) == len(bundled_ids("sensors"))


def test_catalog_export_writes_the_bundled_files(tmp_path: Path) -> None:
    target = tmp_path / "mine"
    done = invoke("catalog", "export", str(target))
    assert done.exit_code == 0, done.stderr
    for source in bundled_files():
        copy = target / Path(source).name
        assert copy.read_bytes() == Path(source).read_bytes()
        assert f"wrote {copy}" in done.stderr
    # the copies are a catalogue like the bundled one
    assert invoke("validate", *map(str, sorted(target.iterdir()))).exit_code == 0
    again = invoke("catalog", "export", str(target))
    assert again.exit_code == 2 and "exists; --force replaces it" in again.stderr
    (target / "sensors.gyrovib.yaml").write_text("edited", encoding="utf-8")
    assert invoke("catalog", "export", str(target), "--force").exit_code == 0
    assert (target / "sensors.gyrovib.yaml").read_text(encoding="utf-8") != "edited"
    only = tmp_path / "profiles-only"
    assert invoke("catalog", "export", str(only), "--bundled", "profiles").exit_code == 0
    assert [p.name for p in only.iterdir()] == ["profiles.gyrovib.yaml"]
