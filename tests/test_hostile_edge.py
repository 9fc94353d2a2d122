"""Hostile input at the command line's edge: every command validates
every file whole, output names and signals, standard error that cannot be
written, ``GYROVIB_DEBUG``; and the notebook API's checks of its arguments."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from gyrovib.cli.common import printable
from tests.conftest import invoke
from tests.test_cli_terminal import LONG, _interrupt, clean_env

HEADER = "gyrovib: 1\n"
#: One valid profile after the sensors, so that ``bounds`` has something to bound.
PROFILES = "profiles:\n  - id: p\n    random: {rms: [0, 0, 1]}\n"
SENSOR = HEADER + "sensors:\n  - id: a\n    coefficients:\n"
#: One sensor under one profile: what `report` reads in the tests of its output name,
#: signals and standard error. These test the write of the file and the status, which do
#: not depend on what the report holds; the bundled catalogues (the default) cost 3 s of
#: CPU a run for the same write.
SMALL = SENSOR + "      k2: 1.0e-7\n" + PROFILES


@pytest.fixture(scope="module")
def small(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """SMALL in a file outside each test's tmp_path (whose listing the tests check)."""
    path = tmp_path_factory.mktemp("small") / "small.yaml"
    path.write_text(SMALL, encoding="utf-8")
    return path

# (id, sensors part of the file, line, column of the first problem, words it contains)
BAD_SENSORS: list[tuple[str, str, int, int, tuple[str, ...]]] = [
    ("nan-coefficient", SENSOR + "      k2: .nan\n", 5, 11, ("NaN",)),
    ("duplicate-key", SENSOR + "      k2: 1.0\n      k2: 2.0\n", 6, 7, ("duplicate key 'k2'",)),
    ("unknown-key", SENSOR + "      k_2: 1.0e-7\n", 5, 7, ("unknown key 'k_2'",)),
    ("k1-zero", HEADER + "sensors:\n  - id: s\n    output_coefficients:\n      K1: 0\n", 5, 11,
     ("K1",)),
    ("id-201-characters", HEADER + "sensors:\n  - id: " + "x" * 201
     + "\n    coefficients: {k2: 1.0e-7}\n", 3, 9, ()),
    ("both-coefficient-forms", HEADER + "sensors:\n  - id: s\n    coefficients: {k2: 1.0e-7}\n"
     "    output_coefficients: {K1: 1, K2: 1.0e-4}\n", 3, 5, ()),
]


@pytest.mark.parametrize(("sensors", "line", "column", "needles"),
                         [c[1:] for c in BAD_SENSORS], ids=[c[0] for c in BAD_SENSORS])
def test_bounds_refuses_what_validate_refuses(tmp_path: Path, sensors: str, line: int,
                                              column: int, needles: tuple[str, ...]) -> None:
    # bounds used to skip the sensors: exit 0 on a broken file, a green CI step
    path = tmp_path / "cat.yaml"
    path.write_text(sensors + PROFILES, encoding="utf-8")
    checked = invoke("validate", path)
    assert checked.exit_code == 2, checked.stderr
    first = checked.stderr.splitlines()[0]
    assert re.match(rf"^{re.escape(str(path))}:\d+:\d+: ", first), first
    assert first.startswith(f"{path}:{line}:{column}: "), first
    for needle in needles:
        assert needle in first, first
    for fmt in ("table", "json", "csv", "markdown"):
        bounded = invoke("bounds", path, "--budget", "0.01", "--format", fmt)
        assert bounded.exit_code == 2, bounded.stdout
        assert bounded.stdout == ""
        assert bounded.stderr == checked.stderr  # the same lines, at the same places


# ---------------------------------------------------------------- signals and the output


def _run_with(patch: str, args: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    """Run the console script's ``main()`` with ``args`` after the Python lines ``patch``
    (which replace a step of the write with one that also signals the process itself:
    the signal then lands at a known moment, not at a chosen time that a loaded
    machine would shift)."""
    code = "\n".join(["import os, signal, sys", "from gyrovib.cli import main", patch,
                      f"sys.argv = ['gyrovib', *{args!r}]", "main()"])
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=cwd, env=clean_env(), timeout=120, check=False)


#: fsync runs while the temporary file exists, before the rename.
DURING_THE_WRITE = """
real = os.fsync
def fsync(fd):
    os.kill(os.getpid(), {sig})
    real(fd)
os.fsync = fsync
"""

#: Right after the rename: the output is in place.
AFTER_THE_RENAME = """
real = os.replace
def replace(a, b):
    real(a, b)
    os.kill(os.getpid(), {sig})
os.replace = replace
"""

SIGNALS = {signal.SIGHUP: (129, "hung up"), signal.SIGTERM: (143, "terminated"),
           signal.SIGINT: (130, "interrupted")}
COMMANDS = {"analyze": ["analyze", "--format", "json"],
            "report": ["report", "{small}", "--budget", "0.01"], "schema": ["schema"]}
#: Every signal with the quickest command, and the hang-up (the case found) with the others.
CASES = [("schema", s) for s in SIGNALS] + [("analyze", signal.SIGHUP),
                                            ("report", signal.SIGHUP)]


@pytest.mark.parametrize(("command", "sig"), CASES, ids=[f"{c}-{s.name}" for c, s in CASES])
def test_a_signal_during_the_write_leaves_no_temporary_file(
        tmp_path: Path, small: Path, command: str, sig: signal.Signals) -> None:
    # SIGHUP used to kill the process at once: its temporary file stayed behind
    status, word = SIGNALS[sig]
    target = tmp_path / "out.txt"
    target.write_text("previous\n")
    args = [a.format(small=small) for a in COMMANDS[command]]
    done = _run_with(DURING_THE_WRITE.format(sig=int(sig)), [*args, "-o", str(target)],
                     tmp_path)
    assert done.returncode == status, done.stderr
    assert done.stderr.strip() == f"gyrovib: {word}"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.txt"]
    assert target.read_text() == "previous\n"


LATE = [("schema", s) for s in SIGNALS] + [("analyze", signal.SIGTERM),
                                           ("report", signal.SIGINT)]


@pytest.mark.parametrize(("command", "sig"), LATE, ids=[f"{c}-{s.name}" for c, s in LATE])
def test_a_signal_once_the_output_is_in_place_is_a_success(
        tmp_path: Path, small: Path, command: str, sig: signal.Signals) -> None:
    # it used to exit 130/143 with the new output already in place
    target = tmp_path / "out.txt"
    target.write_text("previous\n")
    args = [a.format(small=small) for a in COMMANDS[command]]
    done = _run_with(AFTER_THE_RENAME.format(sig=int(sig)), [*args, "-o", str(target)],
                     tmp_path)
    assert done.returncode == 0, done.stderr
    assert SIGNALS[sig][1] not in done.stderr
    assert target.read_text() != "previous\n" and len(target.read_text()) > 100
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.txt"]


@pytest.mark.parametrize("sig", list(SIGNALS), ids=[s.name for s in SIGNALS])
def test_a_signal_as_python_shuts_down_does_not_change_the_status(
        tmp_path: Path, sig: signal.Signals) -> None:
    # Python's shutdown puts back the default action of the signals it handled: a
    # SIGTERM then killed a run whose output was in place (-15, shown as 143 by a
    # shell). Once main() has decided, the signals are ignored: sent right after
    # it, the status stays the run's.
    target = tmp_path / "out.json"
    code = "\n".join([
        "import os, signal, sys", "from gyrovib.cli import main",
        f"sys.argv = ['gyrovib', 'schema', '-o', {str(target)!r}]",
        "try:", "    main()", "except SystemExit as done:", f"    os.kill(os.getpid(), {int(sig)})",
        "    raise"])
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=tmp_path, env=clean_env(), timeout=120, check=False)
    assert done.returncode == 0, done.stderr
    assert target.read_text().startswith("{")


def test_a_hang_up_during_a_long_computation_exits_129(tmp_path: Path) -> None:
    code, err = _interrupt([*LONG, "-o", str(tmp_path / "r.json")], signal.SIGHUP, 1.0,
                           tmp_path)
    assert code == 129, err
    assert err.strip() == "gyrovib: hung up"
    assert list(tmp_path.iterdir()) == []


# ---------------------------------------------------------------- --output failures


@pytest.mark.parametrize("command", [["schema"], ["analyze", "--format", "csv"],
                                     ["report", "{small}", "--budget", "0.01"],
                                     ["bounds", "--budget", "0.01"]],
                         ids=lambda c: c[0])
def test_an_output_name_too_long_is_bad_usage_with_the_name(tmp_path: Path, small: Path,
                                                           command: list[str]) -> None:
    # used to be an internal error, exit 3: "OSError: File name too long"
    name = str(tmp_path / ("x" * 300))
    result = invoke(*(a.format(small=small) for a in command), "-o", name)
    assert result.exit_code == 2, result.stderr
    assert result.stderr == f"gyrovib: error: --output: cannot write {name!r}: " \
        "File name too long\n"
    assert list(tmp_path.iterdir()) == []


def test_a_plot_name_too_long_is_bad_usage_with_the_name(tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    name = str(tmp_path / ("x" * 300 + ".png"))
    result = invoke("sweep", "--rate-range", "0:1:3", "--profile", "flat-random-hover",
                    "--plot", name)
    assert result.exit_code == 2, result.stderr
    assert result.stderr.endswith(f"cannot write {name!r}: File name too long\n")


def test_the_longest_output_name_is_written(tmp_path: Path) -> None:
    # 250 characters is a legal name; the temporary name must not outgrow 255
    target = tmp_path / ("y" * 250)
    result = invoke("schema", "-o", target)
    assert result.exit_code == 0, result.stderr
    assert target.read_text().startswith("{")
    assert [p.name for p in tmp_path.iterdir()] == [target.name]


@pytest.mark.parametrize("where", ["missing/out.json", "file/out.json"])
def test_an_output_in_no_directory_is_bad_usage_with_the_name(tmp_path: Path,
                                                             where: str) -> None:
    (tmp_path / "file").write_text("a file, not a directory\n")
    target = str(tmp_path / where)
    result = invoke("analyze", "--format", "json", "-o", target)
    assert result.exit_code == 2, result.stderr
    assert repr(target) in result.stderr and result.stdout == ""


@pytest.mark.skipif(os.access("/sys", os.W_OK) and not os.path.ismount("/sys"),
                    reason="needs /sys, where no file can be created")
def test_an_output_where_no_file_can_be_created_is_bad_usage_with_the_name() -> None:
    result = invoke("schema", "-o", "/sys/gyrovib-out.json")
    assert result.exit_code in (2, 74), result.stderr
    assert "'/sys/gyrovib-out.json'" in result.stderr
    assert not os.path.exists("/sys/gyrovib-out.json")


# ---------------------------------------------------------------- names in messages


FORGED = "x\ngyrovib: error: forged\x1b[31m\u2028y"


def test_a_name_with_a_newline_cannot_forge_a_line(tmp_path: Path, small: Path) -> None:
    # report's "wrote NAME" printed the name as it is: two lines, the second forged
    target = tmp_path / f"{FORGED}.html"
    result = invoke("report", small, "--budget", "0.01", "-o", target)
    assert result.exit_code == 0, result.stderr
    assert target.exists()
    assert result.stderr.count("\n") == 1 and len(result.stderr.splitlines()) == 1
    assert "\x1b" not in result.stderr and "\\n" in result.stderr
    missing = invoke("analyze", "-o", tmp_path / FORGED / "out.json")
    assert missing.exit_code == 2
    assert len(missing.stderr.splitlines()) == 1, missing.stderr


def test_printable_escapes_line_separators_and_bidirectional_controls() -> None:
    assert printable("a\u2028b\u2029c\u202ed\u2066e") == "a\\u2028b\\u2029c\\u202ed\\u2066e"
    assert printable("plain é ✓") == "plain é ✓"


# ---------------------------------------------------------------- standard error


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
@pytest.mark.parametrize(("args", "status"), [
    (["validate", "{bad}"], 2),
    (["validate", "{good}"], 0),
    (["analyze", "--no-such-option"], 2),
    (["bounds", "{bad}", "--budget", "0.01"], 2),
    (["report", "{small}", "--budget", "0.01", "-o", "{out}"], 0),
    (["analyze", "-o", "{out}", "--sensor", "nope"], 2),
])
def test_an_unwritable_standard_error_keeps_the_status(tmp_path: Path, small: Path,
                                                       args: list[str], status: int) -> None:
    # a message that could not be written used to end in exit 1 ("requirement not met")
    bad = tmp_path / "bad.yaml"
    bad.write_text(HEADER + "sensors: 3\n" + PROFILES)
    good = tmp_path / "good.yaml"
    good.write_text(HEADER + PROFILES)
    filled = [a.format(bad=bad, good=good, out=tmp_path / "out.html", small=small)
              for a in args]
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-m", "gyrovib", *filled], stdout=subprocess.PIPE,
                              stderr=full, env=clean_env(), timeout=120, check=False)
    assert done.returncode == status


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
def test_an_internal_error_with_an_unwritable_standard_error_is_still_3(
        tmp_path: Path) -> None:
    code = "\n".join([
        "import sys", "from gyrovib import api",
        "def boom(*a, **k): raise ZeroDivisionError('simulated bug')",
        "api.analyze = boom", "from gyrovib.cli import main",
        "sys.argv = ['gyrovib', 'analyze']", "main()"])
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-c", code], stdout=subprocess.PIPE,
                              stderr=full, env=clean_env(GYROVIB_DEBUG="1"), timeout=120,
                              check=False)
    assert done.returncode == 3


# ---------------------------------------------------------------- GYROVIB_DEBUG


@pytest.mark.parametrize(("value", "traceback"), [
    ("1", True), ("true", True), ("TRUE", True), ("yes", True), ("Yes", True),
    ("0", False), ("false", False), ("False", False), ("", False), ("no", False),
    ("off", False),
])
def test_debug_shows_tracebacks_only_when_asked(monkeypatch: pytest.MonkeyPatch, value: str,
                                                traceback: bool) -> None:
    from gyrovib import api

    def boom(*args: object, **kwargs: object) -> None:
        raise ZeroDivisionError("simulated bug")

    monkeypatch.setattr(api, "analyze", boom)
    monkeypatch.setenv("GYROVIB_DEBUG", value)
    result = invoke("analyze", crash_ok=True)
    assert result.exit_code == 3
    assert ("Traceback (most recent call last)" in result.stderr) is traceback
    assert result.stderr.rstrip().splitlines()[-1].startswith(
        "gyrovib: internal error: ZeroDivisionError: simulated bug")


def test_a_late_signal_never_contradicts_the_output(tmp_path: Path) -> None:
    # the audit's case: SIGTERM sent in the last moments of `analyze -o` (8 of 32
    # tries exited 143 with the new file already in place). Whenever the signal
    # lands, the status and the file must agree: 0 and the new output, or 143
    # (or killed before main() took the signal) and the old file, no temporary file.
    target = tmp_path / "out.json"
    args = ["analyze", "--format", "json", "-o", str(target)]
    started = time.perf_counter()
    assert _run_with("", args, tmp_path).returncode == 0
    whole = time.perf_counter() - started
    new = target.read_text()
    outcomes = set()
    for k in range(8):
        target.write_text("previous\n")
        process = subprocess.Popen([sys.executable, "-m", "gyrovib", *args], cwd=tmp_path,
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                   env=clean_env())
        time.sleep(whole * (0.6 + 0.08 * k))  # from mid-run to just past the end
        process.send_signal(signal.SIGTERM)
        _, err = process.communicate(timeout=120)
        text = target.read_text()
        assert sorted(p.name for p in tmp_path.iterdir()) == ["out.json"]
        if process.returncode == 0:
            assert text == new, err
        else:
            assert process.returncode in (143, -signal.SIGTERM), err
            assert text == "previous\n", process.returncode
        outcomes.add(process.returncode)
    assert outcomes  # at least one run; which outcomes depends on the machine's speed


def test_a_signal_a_library_turned_into_another_error_is_still_the_signal(
        monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    # pydantic, building its models, may catch the exception a SIGTERM raised and raise
    # another in its place: the run was terminated (143), not an internal error (3)
    from gyrovib import api
    from gyrovib.cli import main as cli_main

    def swallowing(*args: object, **kwargs: object) -> None:
        try:
            cli_main._on_signal(signal.SIGTERM, None)
        except BaseException as exc:
            raise RuntimeError("wrapped by a library") from exc

    monkeypatch.setattr(api, "analyze", swallowing)
    monkeypatch.setattr(cli_main, "_received", [])
    handlers = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}
    try:
        with pytest.raises(SystemExit) as done:
            cli_main.main(["analyze", "--format", "json"])
    finally:  # main() leaves the signals it caught ignored, as the process ends
        for s, handler in handlers.items():
            signal.signal(s, handler)
    assert done.value.code == 143
    err = capsys.readouterr().err
    assert err.strip() == "gyrovib: terminated"
    assert "internal error" not in err
