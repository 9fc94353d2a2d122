"""GitHub annotations, --format github, --color and the pre-commit hook."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from gyrovib import api
from gyrovib.cli.common import resolve_color
from gyrovib.errors import Problem
from gyrovib.render.github import (
    annotation,
    annotations,
    escape_data,
    escape_property,
    problems_to_github,
)
from tests.conftest import invoke

ROOT = Path(__file__).parent.parent


def test_escape_data() -> None:
    assert escape_data("100% done\r\nnext") == "100%25 done%0D%0Anext"
    assert escape_data("a: b, c") == "a: b, c"


def test_escape_property() -> None:
    assert escape_property("C:\\dir,x%\n") == "C%3A\\dir%2Cx%25%0A"


def test_annotation_fields() -> None:
    assert annotation("bad: value", file="a,b.yaml", line=3, column=7, title="t:1") == (
        "::error file=a%2Cb.yaml,line=3,col=7,title=t%3A1::bad: value")
    assert annotation("m") == "::error::m"
    assert annotation("m", level="warning", file="f.yaml") == "::warning file=f.yaml::m"
    assert annotation("m", file="f", column=4) == "::error file=f::m"  # no col without a line
    with pytest.raises(ValueError, match="level"):
        annotation("m", level="fatal")


def test_annotations_items() -> None:
    text = annotations([
        ("s.yaml", 12, "mems-a fails", "k2 = 3e-4 exceeds 1e-4\nsecond line", "error"),
        (None, None, None, "no place", "notice"),
    ])
    assert text == ("::error file=s.yaml,line=12,title=mems-a fails::k2 = 3e-4 exceeds "
                    "1e-4%0Asecond line\n::notice::no place\n")


def test_problems_to_github() -> None:
    text = problems_to_github([Problem("x 100%", "a.yaml", 2, 5), Problem("no file")])
    assert text == ("::error file=a.yaml,line=2,col=5,title=gyrovib::x 100%25\n"
                    "::error title=gyrovib::no file\n")


def test_validate_format_github(tmp_path: Path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text("gyrovib: 1\nsensors:\n  - id: a\n    coefficients:\n      k_2: 1\n")
    result = invoke("validate", "--format", "github", str(path))
    assert result.exit_code == 2
    assert result.stdout == (
        f"::error file={escape_property(str(path))},line=5,col=7,title=gyrovib::"
        "sensor 'a': coefficients: unknown key 'k_2'; did you mean 'k2'?\n")
    # the plain FILE:LINE:COL line is still on stderr
    assert result.stderr.startswith(f"{path}:5:7: ")


def test_validate_format_github_valid(valid_file: Path) -> None:
    result = invoke("validate", "--format", "github", str(valid_file))
    assert result.exit_code == 0
    assert result.stdout == ""


def test_validate_format_text_has_no_annotations(tmp_path: Path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text("gyrovib: 3\n")
    result = invoke("validate", str(path))
    assert result.exit_code == 2
    assert result.stdout == ""


def test_sensor_location(valid_file: Path) -> None:
    catalog = api.load([valid_file])
    assert api.sensor_location(catalog, "fog-a") == (str(valid_file), 5)
    assert api.sensor_location(catalog, "mems-a") == (str(valid_file), 15)
    assert api.sensor_location(catalog, "nope") == (None, None)
    assert api.profile_location(catalog, "cruise") == (str(valid_file), 22)


@pytest.mark.parametrize(("mode", "env", "tty", "expected"), [
    ("always", {"NO_COLOR": "1"}, False, True),
    ("never", {"FORCE_COLOR": "1"}, True, False),
    ("auto", {}, True, True),
    ("auto", {}, False, False),
    ("auto", {"NO_COLOR": "1"}, True, False),
    ("auto", {"NO_COLOR": ""}, True, True),
    ("auto", {"FORCE_COLOR": "1"}, False, True),
    ("auto", {"FORCE_COLOR": "0"}, False, False),
    ("auto", {"NO_COLOR": "1", "FORCE_COLOR": "1"}, False, False),
])
def test_resolve_color(mode: str, env: dict[str, str], tty: bool, expected: bool) -> None:
    assert resolve_color(mode, env, tty) is expected


ESC = "\x1b["


def test_color_option_reaches_table(valid_file: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("NO_COLOR", raising=False)
    monkeypatch.delenv("FORCE_COLOR", raising=False)
    plain = invoke("analyze", str(valid_file))
    assert plain.exit_code == 0 and ESC not in plain.stdout
    colored = invoke("--color", "always", "analyze", str(valid_file))
    assert colored.exit_code == 0 and ESC in colored.stdout
    monkeypatch.setenv("FORCE_COLOR", "1")
    forced = invoke("analyze", str(valid_file))
    assert ESC in forced.stdout
    never = invoke("--color", "never", "analyze", str(valid_file))
    assert ESC not in never.stdout
    monkeypatch.setenv("NO_COLOR", "1")
    off = invoke("analyze", str(valid_file))
    assert ESC not in off.stdout


def test_color_never_in_json(valid_file: Path) -> None:
    result = invoke("--color", "always", "analyze", str(valid_file),
                                      "--format", "json")
    assert result.exit_code == 0 and ESC not in result.stdout


def test_pre_commit_hook() -> None:
    hooks = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())
    hook = next(h for h in hooks if h["id"] == "gyrovib-validate")
    assert hook["entry"] == "gyrovib validate"
    assert hook["language"] == "python"
    import re

    pattern = re.compile(hook["files"])
    assert pattern.search("catalogs/procurement.gyrovib.yaml")
    assert pattern.search("x.gyrovib.yml")
    assert not pattern.search("other.yaml")


def test_help_documents_exit_codes() -> None:
    result = invoke("--help")
    assert result.exit_code == 0
    assert "3 an internal error" in result.stdout
    assert "--color" in result.stdout


def test_select_github_annotations_point_at_the_failing_sensor(write):
    # k2 = 1 (deg/s)^-1 under a 1 deg/s tone: Δ0(2) = k2·a²/2 = 0.5 deg/s ≫ Δ* = 0.01,
    # so 'bad' fails; 'good' has no nonlinearity at all and passes
    path = write("""
        gyrovib: 1
        sensors:
          - id: good
            coefficients: {}
          - id: bad
            coefficients: {k2: 1.0}
        profiles:
          - id: tone
            harmonic: [{frequency: 50, amplitude: [0, 0, 1]}]
    """)
    result = invoke("select", str(path), "--budget", "0.01", "--format",
                                      "github", "--require", "all")
    assert result.exit_code == 1
    lines = result.stdout.splitlines()
    # line 6 of the dedented file holds "  - id: bad" (the file starts with a blank line)
    assert lines[1].startswith(f"::error file={path},line=6,title=bad fails the budget::")
    assert "|k2| = 1 exceeds its bound" in lines[1]
    assert lines[0].startswith(f"::notice file={path},line=4,title=good passes::")
    assert lines[-1].startswith("::notice title=gyrovib select::")


def test_select_github_reports_bad_input_as_annotation(write):
    path = write("gyrovib: 1\nsensors:\n  - id: s\n    coefficients: {k_2: 1}\n")
    result = invoke("select", str(path), "--budget", "0.01", "--format",
                                      "github")
    assert result.exit_code == 2
    assert f"::error file={path},line=4,col=20" in result.stdout


def test_sensor_locations_compose_each_file_once(tmp_path: Path,
                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    # 300 sensors in one file: their lines come from one compose of the file, with no
    # per-sensor lookup (that re-parsed the file each time: quadratic, minutes at 2,000)
    from gyrovib.catalog.loader import CatalogSource

    body = "".join(f"  - id: s{i}\n    coefficients: {{k2: 1.0e-4}}\n" for i in range(300))
    path = tmp_path / "many.yaml"
    path.write_text("gyrovib: 1\nsensors:\n" + body)
    catalog = api.load([path])
    composed: list[int] = []
    real_compose = yaml.compose

    def counting_compose(*args: object, **kwargs: object) -> object:
        composed.append(1)
        return real_compose(*args, **kwargs)

    monkeypatch.setattr(yaml, "compose", counting_compose)
    monkeypatch.setattr(CatalogSource, "locate", lambda *a: pytest.fail("per-sensor lookup"))
    ids = [f"s{i}" for i in range(300)]
    # sensor i's id is on line 3 + 2·i (two lines per sensor after the two header lines)
    assert api.sensor_locations(catalog, ids) == [(str(path), 3 + 2 * i) for i in range(300)]
    assert len(composed) == 1
    assert api.sensor_locations(catalog, ["nope"]) == [(None, None)]


def test_sensor_locations_of_a_merged_id(tmp_path: Path) -> None:
    # an id that comes only through a merge key is located by the file's own locator
    path = tmp_path / "merged.yaml"
    path.write_text("gyrovib: 1\nsensors:\n  - id: a\n    coefficients: {k2: 1.0e-4}\n"
                    "  - <<: {id: b}\n    coefficients: {}\n")
    catalog = api.load([path])
    assert api.sensor_locations(catalog, ["a", "b"]) == [(str(path), 3), (str(path), 5)]
