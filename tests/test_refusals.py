"""Inputs that used to slip through or crash: each must be refused with exit 2,
located where a file is at fault."""

from __future__ import annotations

import pytest


@pytest.mark.parametrize(
    ("text", "place", "fragment"),
    [
        # dividing by a subnormal K1 overflows: refused at output_coefficients
        ("gyrovib: 1\nsensors:\n  - id: s\n    output_coefficients: {K1: 1e-320, K2: 1}\n",
         ":4:26:", "overflows"),
        # a PSD with one frequency (or only a step) spans no band: σ would be 0
        ("gyrovib: 1\nprofiles:\n  - id: p\n    random: {psd: {x3: [[100, 1.0]]}}\n",
         ":4:24:", "two different frequencies"),  # column of the x3 table
        ("gyrovib: 1\nprofiles:\n  - id: p\n    random: {psd: {x3: [[100, 1], [100, 2]]}}\n",
         ":4:24:", "two different frequencies"),
        ("gyrovib: 1\nprofiles:\n  - id: p\n    random: {psd: {}}\n", ":4:19:",
         "at least one axis"),
        # scalars PyYAML cannot convert
        ("gyrovib: 1\nsensors:\n  - id: s\n    coefficients: {k2: !!float abc}\n", ":4:24:",
         "'abc' is not a valid float"),
        ("gyrovib: 1\nsensors:\n  - id: s\n    coefficients: {k2: 1" + "0" * 5000 + "}\n",
         ":4:24:", "too many digits"),
    ],
)
def test_refused_with_place(run, write, text, place, fragment):
    path = write(text)
    result = run("validate", path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith(f"{path}{place}"), result.output
    assert fragment in result.output


def test_select_without_profiles_is_an_error_not_a_pass(run, write):
    # a CI gate given only the sensors file must not pass vacuously
    path = write("gyrovib: 1\nsensors:\n  - id: bad\n    coefficients: {A1: 1000, k2: 1000}\n")
    result = run("select", path, "--budget", "1e-9", "--require", "all")
    assert result.exit_code == 2
    assert "no profiles" in result.output
    profiles_only = write("gyrovib: 1\nprofiles:\n  - id: p\n    random: {rms: [0, 0, 1]}\n",
                          "profiles.yaml")
    result = run("select", profiles_only, "--budget", "1")
    assert result.exit_code == 2
    assert "no sensors" in result.output
    # bounds needs only profiles
    result = run("bounds", profiles_only, "--budget", "1", "--format", "csv")
    assert result.exit_code == 0, result.stderr
    assert [row.split(",")[0] for row in result.stdout.splitlines()[1:]] == ["p"]


def test_unwritable_output_directory(run, tmp_path, monkeypatch):
    # a directory we may not create files in (simulated: the tests may run as root)
    import tempfile

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(tempfile, "mkstemp", refuse)
    result = run("schema", "-o", tmp_path / "schema.json")
    assert result.exit_code == 2
    assert "cannot write in" in result.output and "Permission denied" in result.output


def test_output_into_a_missing_special_directory(run):
    # /proc cannot hold a temporary file: an input problem (2), not a crash (3)
    result = run("schema", "-o", "/proc/gyrovib-schema.json")
    assert result.exit_code == 2
    assert "--output" in result.output


def test_empty_output_name(run):
    result = run("schema", "-o", "")
    assert result.exit_code == 2
    assert "give a file name" in result.output


def test_sweep_limits(run):
    assert "at most 20000" in run("sweep", "--rate-range", "0:1:20001").output
    assert "finite span" in run("sweep", "--rate-range", "-1e308:1e308:3").output


def test_a_method_refusal_is_structured_and_located(write):
    # core's ModelError gives the reason in the model's words; the library places it at the
    # profile's id (line 5, column 9) and adds the advice, and keeps which profile it was
    from gyrovib import api
    from gyrovib.errors import ModelError

    path = write("gyrovib: 1\nsensors:\n  - id: s\n    coefficients: {k2: 1}\nprofiles:\n"
                 "  - id: ok\n    random: {rms: [0, 0, 1]}\n"
                 "  - id: two\n    harmonic: [{frequency: 10, amplitude: [0, 0, 1]},"
                 " {frequency: 20, amplitude: [0, 0, 1]}]\n")
    with pytest.raises(ModelError) as info:
        api.analyze(api.load([path]), method="paper")
    error = info.value
    assert error.profile == 1
    assert error.reason == ("the paper's formulas cover one harmonic tone or purely random "
                            "vibration, not 2 tones")
    (problem,) = error.problems
    assert (problem.file, problem.line, problem.column) == (str(path), 8, 9)
    # the library names its arguments; the command line, from the same problem, its options
    assert problem.message == f"profile 'two': {error.reason}; use method exact, or choose " \
                              "other profiles with profiles"
    from gyrovib.cli.options import as_option

    (worded,) = as_option(error).problems
    assert (worded.file, worded.line, worded.column) == (str(path), 8, 9)
    assert worded.message == f"profile 'two': {error.reason}; use --method exact, or choose " \
                             "other profiles with --profile"


def test_a_recording_error_names_the_argument_and_the_command_line_the_option(run, tmp_path):
    # a CSV recording with no time column and no sample rate: the library asks for its
    # argument fs, the command line for the option --fs, in the same located message
    from gyrovib.api.recordings.located import RecordingError
    from gyrovib.api.recordings.reading import read_recording

    path = tmp_path / "log.csv"
    path.write_text("gx,gy,gz\n" + "0.1,0.2,0.3\n" * 64, encoding="utf-8")
    with pytest.raises(RecordingError) as info:
        read_recording(str(path))
    (problem,) = info.value.problems
    assert problem.message.endswith("give the sample rate with fs HZ")
    assert "--" not in problem.message
    result = run("profile", str(path))
    assert result.exit_code == 2
    assert result.output.startswith(f"{path}: ") and "give the sample rate with --fs HZ" in \
        result.output, result.output


def test_a_rate_table_error_names_the_argument(run, tmp_path):
    from gyrovib.api.ratetable.reading import RateTableError, output_unit_label

    with pytest.raises(RateTableError) as info:
        output_unit_label("x" * 40)
    assert str(info.value).startswith("output_unit 'xxx")
    table = tmp_path / "t.csv"
    table.write_text("unit,rate,output\na,1,1\n", encoding="utf-8")
    result = run("fit", str(table), "--output-unit", "x" * 40)
    assert result.exit_code == 2 and "--output-unit 'xxx" in result.output, result.output
