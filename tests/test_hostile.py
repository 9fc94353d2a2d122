"""Bad input, exhaustively: every malformed catalogue or option exits 2 with
one located line per problem on standard error, and no traceback."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from click.testing import Result

from gyrovib.catalog import loader
from tests.conftest import invoke

HEADER = "gyrovib: 1\n"


def run(args: list[str]) -> Result:
    """:func:`tests.conftest.invoke` (no escaped exception, no traceback); how long the
    hostile cases take is benchmarks/bench_hostile.py's, not a test's."""
    return invoke(*args)


ANY = -1


def bad(path: Path, line: int | None, column: int | None,
        *needles: str) -> str:
    """Validate ``path``, expect exit 2 and a located problem; return stderr.

    ``line`` None: the problem names the file only; ANY: some line and column.
    """
    result = run(["validate", str(path)])
    assert result.exit_code == 2, result.stderr
    lines = result.stderr.strip().splitlines()
    assert lines, "no message"
    first = lines[0]
    if line is None:
        assert first.startswith(f"{path}: "), first
    elif line == ANY:
        assert re.match(rf"^{re.escape(str(path))}:\d+:\d+: ", first), first
    elif column is None:
        assert first.startswith(f"{path}:{line}:"), first
    else:
        assert first.startswith(f"{path}:{line}:{column}: "), first
    for needle in needles:
        assert needle in first, first
    return result.stderr


def write(tmp_path: Path, text: str | bytes, name: str = "cat.yaml") -> Path:
    path = tmp_path / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text, encoding="utf-8")
    return path


SENSOR = HEADER + "sensors:\n  - id: a\n    coefficients:\n"
PROFILE = HEADER + "profiles:\n  - id: p\n"

# (id, text, line, column, words the message must contain)
CASES: list[tuple[str, str | bytes, int | None, int | None, tuple[str, ...]]] = [
    ("yaml-syntax", HEADER + "sensors: [\n  - id: x\n", 3, 3, ("expected",)),
    ("yaml-bad-indent", HEADER + "sensors:\n  - id: a\n   coefficients: {}\n", 4, None, ()),
    ("yaml-tab", HEADER + "sensors:\n\t- id: a\n", 3, None, ()),
    ("empty", "", 1, 1, ("empty",)),
    ("only-comments", "# nothing here\n", 1, 1, ("empty",)),
    ("top-level-list", "- a\n- b\n", 1, 1, ("mapping", "list")),
    ("top-level-scalar", "hello\n", 1, 1, ("mapping",)),
    ("non-utf8", b"gyrovib: 1\nsensors:\n  - id: caf\xe9\n", 3, 12, ("UTF-8",)),
    ("binary-nul", b"gyrovib: 1\n\x00\x01\x02", 2, 1, ("binary",)),
    ("utf16", "gyrovib: 1\n".encode("utf-16"), 1, 1, ("UTF-16",)),
    ("control-char", "gyrovib: 1\nsensors: \x07\n", 2, None, ()),
    ("missing-version", "sensors: []\n", 1, 1, ("gyrovib: 1",)),
    ("unknown-version", "gyrovib: 2\n", 1, 10, ("version 2",)),
    ("version-as-text", 'gyrovib: "1"\n', 1, 10, ("number 1",)),
    ("version-float", "gyrovib: 1.5\n", 1, 10, ("number 1",)),
    ("typo-k_2", SENSOR + "      k_2: 1.0e-7\n", 5, 7, ("unknown key 'k_2'", "did you mean 'k2'")),
    ("typo-case", SENSOR + "      K2: 1.0e-7\n", 5, 7, ("did you mean 'k2'",)),
    ("typo-top", HEADER + "sensor: []\n", 2, 1, ("did you mean 'sensors'",)),
    ("typo-profile", PROFILE + "    harmonik: []\n", 4, 5, ("did you mean 'harmonic'",)),
    ("duplicate-key", SENSOR + "      k2: 1.0\n      k2: 2.0\n", 6, 7,
     ("duplicate key 'k2'", "line 5")),
    ("duplicate-top-key", HEADER + "gyrovib: 1\n", 2, 1, ("duplicate key",)),
    ("nan", SENSOR + "      k2: .nan\n", 5, 11, ("NaN",)),
    ("inf", SENSOR + "      k2: .inf\n", 5, 11, ("infinit",)),
    ("minus-inf", SENSOR + "      k3: -.Inf\n", 5, 11, ("infinit",)),
    ("overflow-1e400", SENSOR + "      k2: 1e400\n", 5, 11, ("1e400 overflows",)),
    ("overflow-int", SENSOR + "      k2: 1" + "0" * 400 + "\n", 5, 11, ("overflows",)),
    ("string-for-number", SENSOR + "      k2: abc\n", 5, 11, ("must be a number", "'abc'")),
    ("bool-for-number", SENSOR + "      k2: true\n", 5, 11, ("must be a number", "boolean")),
    ("list-for-number", SENSOR + "      k2: [1]\n", 5, 11, ("must be a number", "list")),
    ("yaml11-yes-not-bool", PROFILE + "    rate: [yes, 0, 0]\n", 4, 12, ("'yes'",)),
    ("rate-too-short", PROFILE + "    rate: [0, 1]\n", 4, 11, ("too few",)),
    ("rate-too-long", PROFILE + "    rate: [0, 1, 2, 3]\n", 4, 11, ("too many",)),
    ("amplitude-too-short",
     PROFILE + "    harmonic:\n      - frequency: 10\n        amplitude: [1, 1]\n", 6, 20,
     ("too few",)),
    ("breakpoint-three", PROFILE + "    mount: [[10, 1, 2]]\n", 4, 13, ("too many",)),
    ("coherence-one", PROFILE + "    random:\n      rms: [1, 1, 1]\n      coherence: [1]\n",
     6, 18, ("too few",)),
    ("negative-amplitude",
     PROFILE + "    harmonic:\n      - frequency: 10\n        amplitude: [0, -1, 0]\n", 6, 24,
     ("amplitude[1]", "negative")),
    ("negative-psd",
     PROFILE + "    random:\n      psd:\n        x3: [[20, -1.0e-4], [2000, 1.0e-4]]\n", 6, 19,
     ("negative",)),
    ("negative-rms", PROFILE + "    random:\n      rms: [0, 0, -0.1]\n", 5, 19, ("negative",)),
    ("negative-gain", PROFILE + "    mount:\n      - [20, 1]\n      - [30, -0.5]\n", 6, 14,
     ("mount[1][1]", "negative")),
    ("negative-response", HEADER + "sensors:\n  - id: s\n    coefficients: {}\n"
     "    response: [[10, -1]]\n", 5, 21, ("negative",)),
    ("zero-frequency",
     PROFILE + "    harmonic:\n      - frequency: 0\n        amplitude: [0, 1, 0]\n", 5, 20,
     ("positive",)),
    ("negative-frequency",
     PROFILE + "    harmonic:\n      - frequency: -5\n        amplitude: [0, 1, 0]\n", 5, 20,
     ("positive",)),
    ("zero-breakpoint-frequency", PROFILE + "    mount: [[0, 1], [30, 1]]\n", 4, 14,
     ("positive",)),
    ("non-increasing", PROFILE + "    mount:\n      - [20, 1]\n      - [30, 1]\n"
     "      - [10, 1]\n", 7, 9, ("must increase", "10 Hz follows 30 Hz")),
    ("triple-step", PROFILE + "    mount:\n      - [20, 1]\n      - [20, 1]\n"
     "      - [20, 0.5]\n", 7, 9, ("more than twice",)),
    ("psd-non-increasing", PROFILE + "    random:\n      psd:\n"
     "        x1: [[200, 1.0e-4], [20, 1.0e-4]]\n", 6, 29, ("must increase",)),
    ("coherence-above", PROFILE + "    random:\n      rms: [1, 1, 1]\n"
     "      coherence: [1.5, 0]\n", 6, 19, ("coherence", "[-1, 1]")),
    ("coherence-below", PROFILE + "    random:\n      rms: [1, 1, 1]\n"
     "      coherence: [0, -1.01]\n", 6, 22, ("[-1, 1]",)),
    ("psd-and-rms", PROFILE + "    random:\n      rms: [1, 1, 1]\n"
     "      psd: {x3: [[1, 1], [2, 1]]}\n", 5, 7, ("exactly one",)),
    ("k1-zero", HEADER + "sensors:\n  - id: s\n    output_coefficients:\n      K1: 0\n", 5, 11,
     ("K1", "zero")),
    ("k1-missing", HEADER + "sensors:\n  - id: s\n    output_coefficients:\n      K2: 1\n",
     5, 7, ("missing required key 'K1'",)),
    ("no-conversion", HEADER + "sensors:\n  - id: s\n    name: x\n", 3, 5,
     ("'coefficients'",)),
    ("unknown-unit", HEADER + "units:\n  rate: deg/min\n", 3, 9,
     ("unknown rate unit 'deg/min'", "deg/s, deg/h, rad/s, rpm")),
    ("id-with-space", HEADER + "sensors:\n  - id: my sensor\n    coefficients: {}\n", 3, 9,
     ("'my sensor'", "no spaces or slashes")),
    ("id-with-slash", HEADER + "profiles:\n  - id: a/b\n", 3, 9, ("'a/b'",)),
    ("id-number", HEADER + "profiles:\n  - id: 12\n", 3, 9, ("must be text",)),
    ("id-empty", HEADER + "profiles:\n  - id: ''\n", 3, 9, ("empty",)),
    ("id-missing", HEADER + "profiles:\n  - name: x\n", 3, 5, ("missing required key 'id'",)),
    ("duplicate-id-in-file", HEADER + "profiles:\n  - id: p\n  - id: p\n", 4, 9,
     ("duplicate profile id 'p'",)),
    ("sensors-not-list", HEADER + "sensors: {a: 1}\n", 2, 10, ("must be a list",)),
    ("sensor-not-mapping", HEADER + "sensors: [5]\n", 2, 11, ("mapping",)),
    ("non-string-key", HEADER + "5: x\n", 2, 1, ("key",)),
    ("two-documents", HEADER + "---\ngyrovib: 1\n", 2, 1, ("single document",)),
    ("tag-python-apply",
     HEADER + 'sensors: !!python/object/apply:os.system ["echo pwned"]\n', 2, 10,
     ("!!python/object/apply:os.system", "not allowed")),
    ("tag-python-name", HEADER + "x: !!python/name:os.system\n", 2, 4, ("not allowed",)),
    ("tag-custom", HEADER + "sensors:\n  - !foo {id: a}\n", 3, 5, ("'!foo'",)),
    ("tag-set", HEADER + "sensors: !!set {a, b}\n", 2, 10, ("!!set",)),
    ("recursive-alias", HEADER + "sensors: &a [*a]\n", 2, None, ("recursive",)),
    ("deep-flow", HEADER + "x: " + "[" * 20000 + "]" * 20000 + "\n", 2, None, ("nested",)),
    ("deep-block", HEADER + "x:\n" + "".join("  " * i + "- \n" for i in range(1, 80))
     + "  " * 80 + "- 1\n", ANY, None, ("nested",)),
    ("deep-compact", HEADER + "x:\n  " + "- " * 5000 + "1\n", 3, None, ("nested",)),
]


@pytest.mark.parametrize(("text", "line", "column", "needles"),
                         [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_catalogue(tmp_path: Path, text: str | bytes, line: int | None,
                       column: int | None, needles: tuple[str, ...]) -> None:
    bad(write(tmp_path, text), line, column, *needles)


def test_every_problem_is_one_line(tmp_path: Path) -> None:
    path = write(tmp_path, SENSOR + "      k2: .nan\n      k_3: 1\n      k4: abc\n")
    result = run(["validate", str(path)])
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 3
    assert all(re.match(rf"^{re.escape(str(path))}:\d+:\d+: ", x) for x in lines), lines
    assert [x.split(":")[1] for x in lines] == ["5", "6", "7"]


def test_many_problems_are_capped(tmp_path: Path) -> None:
    items = "".join(f"  - id: 'bad id {i}'\n" for i in range(300))
    result = run(["validate", str(write(tmp_path, HEADER + "profiles:\n" + items))])
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == loader.MAX_PROBLEMS + 1
    assert "more problems" in lines[-1]


@pytest.mark.parametrize("tag", [
    '!!python/object/apply:os.system ["touch {marker}"]',
    '!!python/object/apply:subprocess.call [["touch", "{marker}"]]',
    '!!python/object/new:os.system ["touch {marker}"]',
    "!!python/name:os.system",
    '!!python/module:os',
])
def test_code_execution_tags_run_nothing(tmp_path: Path, tag: str) -> None:
    marker = tmp_path / "PWNED"
    path = write(tmp_path, HEADER + "sensors: " + tag.format(marker=marker) + "\n")
    result = run(["validate", str(path)])
    assert result.exit_code == 2
    assert "not allowed" in result.stderr
    assert not marker.exists()
    # the same through analyze, where the catalogue is used, not only validated
    result = run(["analyze", str(path)])
    assert result.exit_code == 2 and result.stdout == ""
    assert "not allowed" in result.stderr
    assert not marker.exists()


def _bomb(levels: int, width: int = 9) -> str:
    lines = [HEADER.rstrip(), 'a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]']
    prev = "a"
    for i in range(levels):
        name = f"l{i}"
        lines.append(f"{name}: &{name} [" + ", ".join([f"*{prev}"] * width) + "]")
        prev = name
    return "\n".join(lines) + "\n"


def test_billion_laughs_refused_fast(tmp_path: Path) -> None:
    stderr = bad(write(tmp_path, _bomb(9)), ANY, None, "alias bomb")
    assert stderr.count("\n") == 1


def test_bomb_under_a_known_key_refused(tmp_path: Path) -> None:
    text = _bomb(8).replace("l7: &l7", "sensors: &l7")
    bad(write(tmp_path, text), ANY, None, "alias bomb")


def test_small_alias_use_allowed(tmp_path: Path) -> None:
    text = HEADER + "profiles:\n  - id: a\n    mount: &m [[20, 1], [200, 0.3]]\n" \
        "  - id: b\n    mount: *m\n"
    result = run(["validate", str(write(tmp_path, text))])
    assert result.exit_code == 0, result.stderr


def test_merge_keys_allowed(tmp_path: Path) -> None:
    text = HEADER + (
        "sensors:\n"
        "  - &base\n    id: a\n    coefficients: &c {k2: 1.0e-7, A1: 1.0e-4}\n"
        "  - <<: *base\n    id: b\n"
        "  - id: c\n    coefficients:\n      <<: *c\n      k3: 1.0e-9\n"
    )
    path = write(tmp_path, text)
    result = run(["validate", str(path)])
    assert result.exit_code == 0, result.stderr
    assert "3 sensor(s)" in result.stderr
    source = loader.read_catalog(path)
    assert source.model.sensors[1].coefficients == source.model.sensors[0].coefficients
    assert source.model.sensors[2].coefficients is not None
    assert source.model.sensors[2].coefficients.k3 == 1.0e-9
    assert source.model.sensors[2].coefficients.k2 == 1.0e-7


def test_merge_key_error_located_in_merged_mapping(tmp_path: Path) -> None:
    text = HEADER + ("sensors:\n  - &base\n    id: a\n    coefficients: {k2: 1.0e-7}\n"
                     "  - <<: *base\n    id: b c\n")
    bad(write(tmp_path, text), 7, 9, "'b c'")


def test_duplicate_ids_across_files(tmp_path: Path, valid_text: str) -> None:
    one = write(tmp_path, valid_text, "one.yaml")
    two = write(tmp_path, HEADER + "sensors:\n  - id: fog-a\n    coefficients: {}\n", "two.yaml")
    result = run(["validate", str(one), str(two)])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{two}:3:9: duplicate sensor id 'fog-a' (first at {one}:5)")


def test_all_files_reported(tmp_path: Path, valid_text: str) -> None:
    one = write(tmp_path, valid_text, "one.yaml")
    broken = write(tmp_path, HEADER + "sensors: [\n", "broken.yaml")
    clash = write(tmp_path, HEADER + "profiles:\n  - id: cruise\n", "clash.yaml")
    result = run(["validate", str(one), str(broken), str(clash), "missing.yaml"])
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert [x.split(":")[0] for x in lines] == [str(broken), "missing.yaml", str(clash)]


@pytest.mark.parametrize("command", ["validate", "analyze"])
def test_missing_file(tmp_path: Path, command: str) -> None:
    result = run([command, str(tmp_path / "nope.yaml")])
    assert result.exit_code == 2 and result.stdout == ""
    assert result.stderr == f"{tmp_path / 'nope.yaml'}: no such file or directory\n"


def test_directory(tmp_path: Path) -> None:
    result = run(["analyze", str(tmp_path)])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{tmp_path}: is a directory")


def test_file_too_large(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(loader, "MAX_FILE_BYTES", 1000)
    path = write(tmp_path, HEADER + "# " + "x" * 2000 + "\n")
    bad(path, None, None, "larger than")


def test_validate_needs_a_file() -> None:
    result = run(["validate"])
    assert result.exit_code == 2
    assert "Missing argument" in result.stderr


# ---------------------------------------------------------------- options


@pytest.mark.parametrize(("args", "needle"), [
    (["--profile", "nope"], "unknown profile id 'nope'; the catalogue has: cruise"),
    (["--sensor", "nope"], "unknown sensor id 'nope'; the catalogue has: fog-a, mems-a"),
    (["--unit", "furlong/fortnight"], "unknown rate unit 'furlong/fortnight'; use one of deg/s, "
     "deg/h, rad/s, rpm"),
    (["--unit", ""], "unknown rate unit"),
    (["--method", "magic"], "Invalid value for '--method'"),
    (["--format", "yaml"], "Invalid value for '--format'"),
    (["--rate", "abc"], "--rate"),
    (["--rate", "nan"], "--rate"),
    (["--rate", "1e400"], "not a finite rate"),
    (["--rate", "1,2"], "give one number (Ω_K3) or three"),
    (["--rate", "x"], "--rate"),
    (["--method", "guess"], "Invalid value for '--method'"),
    (["--rate", "1 furlong"], "unknown rate unit"),
    (["--output", "/nonexistent-dir/x.json"], "does not exist"),
])
def test_bad_option(valid_file: Path, args: list[str], needle: str) -> None:
    result = run(["analyze", str(valid_file), *args])
    assert result.exit_code == 2, result.stderr
    assert needle in result.stderr
    assert result.stdout == ""


def test_bad_color_option(valid_file: Path) -> None:
    result = run(["--color", "sometimes", "validate", str(valid_file)])
    assert result.exit_code == 2
    assert "Invalid value for '--color'" in result.stderr


@pytest.mark.parametrize(("text", "needle"), [
    ("36deg/h", None), ("0.01 deg/s", None), ("0", "positive"), ("-1", "positive"),
    ("abc", "cannot read"), ("nan", "cannot read"), ("1e999", "not a finite"),
    ("5 parsecs", "unknown rate unit"),
])
def test_budget_parsing(text: str, needle: str | None) -> None:
    from gyrovib.cli.options import parse_budget
    from gyrovib.errors import OptionError

    if needle is None:
        assert parse_budget(text, "deg/s") > 0
    else:
        with pytest.raises(OptionError, match=needle):
            parse_budget(text, "deg/s")


# ---------------------------------------------------------------- results


# a coefficient the model cannot bound (its product with the vibration overflows) is
# refused by the pipeline at the profile; an absurd vibration already by the catalogue
# model, at the value (gyrovib.models._types.MAX_MAGNITUDE, MAX_VARIANCE)
@pytest.mark.parametrize(("edit", "needle"), [
    (("amplitude: [0.5, 0.5, 0.8]", "amplitude: [1e200, 1e200, 1e200]"),
     "amplitude[0]: must not be greater than 1e+12"),
    (("k2: 2.0e-7", "k2: 1.0e300"), "overflows"),
    (("x3: [[20, 1.0e-4], [2000, 1.0e-4]]", "x3: [[20, 1e300], [1e300, 1e300]]"),
     "x3[0][1]: must not be greater than 1e+24"),
])
@pytest.mark.parametrize("fmt", ["json", "csv", "table", "markdown"])
def test_overflowing_results_refused(tmp_path: Path, valid_text: str,
                                     edit: tuple[str, str], needle: str, fmt: str) -> None:
    assert edit[0] in valid_text
    path = write(tmp_path, valid_text.replace(*edit))
    result = run(["analyze", str(path), "--format", fmt])
    assert result.exit_code == 2
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert re.match(rf"^{re.escape(str(path))}:\d+:\d+: .*{re.escape(needle)}", lines[0]), lines
    assert "Warning" not in result.stderr  # no numpy RuntimeWarnings
    assert "NaN" not in result.stdout and "Infinity" not in result.stdout


def test_overflowing_rate_option(valid_file: Path) -> None:
    result = run(["analyze", str(valid_file), "--rate", "1e300", "--format", "json"])
    assert result.exit_code == 2
    assert "overflows" in result.stderr
    assert result.stdout == ""


def test_failed_run_leaves_output_untouched(tmp_path: Path,
                                           valid_text: str) -> None:
    out = tmp_path / "out.json"
    out.write_text("previous\n")
    broken = write(tmp_path, valid_text.replace("k2: 2.0e-7", "k2: 2.0e-7\n      k2: 1"))
    result = run(["analyze", str(broken), "--format", "json", "--output", str(out)])
    assert result.exit_code == 2
    huge = write(tmp_path, valid_text.replace("amplitude: [0.5, 0.5, 0.8]",
                                              "amplitude: [1e200, 1, 1]"), "huge.yaml")
    result = run(["analyze", str(huge), "--format", "json", "--output", str(out)])
    assert result.exit_code == 2
    result = run(["analyze", str(huge), "--profile", "nope", "--output", str(out)])
    assert result.exit_code == 2
    assert out.read_text() == "previous\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cat.yaml", "huge.yaml", "out.json"]
    # and a successful run does replace it
    good = write(tmp_path, valid_text, "good.yaml")
    result = run(["analyze", str(good), "--format", "json", "--output", str(out)])
    assert result.exit_code == 0
    assert out.read_text().startswith('{"tool": "gyrovib"')


def test_valid_catalogue_passes(valid_file: Path) -> None:
    result = run(["validate", str(valid_file)])
    assert result.exit_code == 0
    assert result.stderr == "1 file(s) valid: 2 sensor(s), 1 profile(s)\n"
    result = run(["analyze", str(valid_file), "--format", "json"])
    assert result.exit_code == 0 and result.stderr == ""
    # 2 sensors × 1 profile (conftest.VALID)
    assert [(r["sensor"], r["profile"]) for r in json.loads(result.stdout)["results"]] == [
        ("fog-a", "cruise"), ("mems-a", "cruise")]


def test_bundled_catalogues_validate() -> None:
    paths = [str(p) for p in loader.bundled_paths()]
    assert paths
    result = run(["validate", *paths])
    assert result.exit_code == 0, result.stderr
    assert re.fullmatch(rf"{len(paths)} file\(s\) valid: \d+ sensor\(s\), \d+ profile\(s\)\n",
                        result.stderr), result.stderr


# ---------------------------------------------------------------- internal errors


def test_internal_error_is_exit_3_without_traceback(valid_file: Path,
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    from gyrovib import api

    def boom(*args: object, **kwargs: object) -> None:
        raise ZeroDivisionError("simulated bug")

    monkeypatch.setattr(api, "analyze", boom)
    monkeypatch.delenv("GYROVIB_DEBUG", raising=False)
    result = run(["analyze", str(valid_file)])
    assert result.exit_code == 3
    assert result.stderr.startswith("gyrovib: internal error: ZeroDivisionError: simulated bug")
    assert "please report" in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1


def test_internal_error_debug_shows_it(valid_file: Path,
                                       monkeypatch: pytest.MonkeyPatch) -> None:
    # GYROVIB_DEBUG adds the traceback; the exit status stays 3 (no variable changes it)
    from gyrovib import api

    def boom(*args: object, **kwargs: object) -> None:
        raise ZeroDivisionError("simulated bug")

    monkeypatch.setattr(api, "analyze", boom)
    monkeypatch.setenv("GYROVIB_DEBUG", "1")
    result = invoke("analyze", valid_file, crash_ok=True)
    assert result.exit_code == 3
    assert "Traceback (most recent call last)" in result.stderr
    assert "ZeroDivisionError: simulated bug" in result.stderr


@pytest.mark.parametrize("raw", [
    pytest.param("gyrovib: 1\n".encode("utf-16"), id="utf16"),
    pytest.param(b"gyrovib: 1\n\x00\x01\x02", id="binary-nul"),
    pytest.param(b"gyrovib: 1\nsensors:\n  - id: caf\xe9\n", id="non-utf8"),
    pytest.param(b"gyrovib: 1\nsensors: [\n", id="yaml-syntax"),
])
def test_standard_input_and_a_file_give_the_same_message(tmp_path, raw):
    # one loader for both (catalog.loader.Source): the same bytes, the same refusal,
    # located the same way; only the name differs. (Standard input used to be read
    # by a second path, which called UTF-16 "binary data (a NUL byte)".)
    path = tmp_path / "bad.gyrovib.yaml"
    path.write_bytes(raw)
    from_file = invoke("validate", str(path))
    from_stdin = invoke("validate", "-", input=raw)
    assert from_file.exit_code == from_stdin.exit_code == 2
    assert from_file.stderr.replace(str(path), "<stdin>") == from_stdin.stderr
    assert "<stdin>:" in from_stdin.stderr  # located: <stdin>:LINE:COL
