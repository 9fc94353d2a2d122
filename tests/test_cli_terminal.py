"""The command line in pipelines and terminals: exit statuses, signals, broken and
failing output, colour, narrow terminals, ASCII streams, standard input.

The statuses are the contract of src/gyrovib/cli/main.py and README.md
("Exit status"): 0, 1, 2, 3, 74 (output not written, EX_IOERR of sysexits.h),
130 (128 + SIGINT), 141 (128 + SIGPIPE), 143 (128 + SIGTERM).
"""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from rich.table import Table

from gyrovib.cli.common import printable, resolve_color
from gyrovib.cli.main import cli
from gyrovib.render.common import rich_text, to_ascii

ANSI = re.compile(r"\x1b\[[0-9;]*m")
#: A command that runs for minutes: 10^8 samples of eq. (2) per sensor × profile.
LONG = ["analyze", "--method", "numeric", "--samples", "100000000", "--format", "json"]


def gyrovib(*args: str, env: dict[str, str] | None = None, **kwargs: object
            ) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "gyrovib", *args], capture_output=True,
                          text=True, timeout=120, env=env, check=False, **kwargs)  # type: ignore[call-overload]


def clean_env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items()
           if k not in ("NO_COLOR", "FORCE_COLOR", "COLUMNS", "GYROVIB_DEBUG",
                        "PYTHONIOENCODING")}
    env.update(extra)
    return env


# ---------------------------------------------------------------- signals


def _interrupt(args: list[str], sig: int, after: float, cwd: Path) -> tuple[int, str]:
    """Start gyrovib, wait ``after`` seconds once Python runs, send ``sig``."""
    # as the console script: its one import (gyrovib.cli, two tiny modules) done, then main().
    # 'ready' is written from inside main(), as it starts importing the CLI (an audit hook on
    # that import), so a signal sent at once lands in main() or its imports, never before it
    code = "\n".join([
        "import sys",
        "from gyrovib.cli import main",
        f"sys.argv = ['gyrovib', *{args!r}]",
        "def ready(event, arg):",
        "    if event == 'import' and arg[0] == 'gyrovib.cli.main':",
        "        sys.stderr.write('ready\\n'); sys.stderr.flush()",
        "sys.addaudithook(ready)",
        "main()",
    ])
    process = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, cwd=cwd, env=clean_env())
    try:
        assert process.stderr is not None
        assert process.stderr.readline() == "ready\n"
        time.sleep(after)
        process.send_signal(sig)
        _, err = process.communicate(timeout=60)
    finally:  # a run that did not stop must not outlive its test (it computes for minutes)
        if process.poll() is None:
            process.kill()
            process.communicate()
    return process.returncode, err


def test_a_signal_the_parent_ignores_stays_ignored(tmp_path: Path) -> None:
    # under nohup a hang-up must not end the run (the parent's choice stands); the
    # terminate that follows still does, in one line with its status
    code = "\n".join([
        "import os, signal, subprocess, sys, time",
        f"args = [sys.executable, '-m', 'gyrovib', *{LONG!r}]",
        "child = subprocess.Popen(args, stderr=subprocess.PIPE, text=True,",
        "                         preexec_fn=lambda: signal.signal(signal.SIGHUP, signal.SIG_IGN))",
        "time.sleep(3.0)",
        "child.send_signal(signal.SIGHUP)",
        "time.sleep(1.0)",
        "alive = child.poll() is None",
        "child.send_signal(signal.SIGTERM)",
        "err = child.communicate(timeout=60)[1]",
        "print(alive, child.returncode, repr(err.strip()))",
    ])
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=tmp_path, env=clean_env(), timeout=120, check=False)
    assert run.stdout.strip() == "True 143 'gyrovib: terminated'", run.stderr


def test_ctrl_c_exits_130_in_one_line_and_leaves_output_untouched(tmp_path: Path) -> None:
    target = tmp_path / "result.json"
    target.write_text("previous result\n")
    code, err = _interrupt([*LONG, "-o", str(target)], signal.SIGINT, 2.0, tmp_path)
    assert code == 130, err
    assert err.strip() == "gyrovib: interrupted"
    assert "Traceback" not in err and "Aborted" not in err
    assert target.read_text() == "previous result\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["result.json"]  # no .tmp left


def test_ctrl_c_during_start_up_imports_exits_130_without_traceback(tmp_path: Path) -> None:
    # sent as soon as the interpreter runs: lands while click, numpy... are imported
    code, err = _interrupt(["analyze"], signal.SIGINT, 0.0, tmp_path)
    assert code == 130, err
    assert "Traceback" not in err
    assert err.strip() == "gyrovib: interrupted"


@pytest.mark.parametrize(("sig", "code", "word"), [(signal.SIGTERM, 143, "terminated"),
                                                  (signal.SIGHUP, 129, "hung up")])
def test_sigterm_or_hangup_during_start_up_imports_exits_in_one_line(
        tmp_path: Path, sig: int, code: int, word: str) -> None:
    # sent as soon as main() starts importing the command line: before the command's
    # own handlers exist, the default action would kill the process (exit -15 / -1).
    # The command runs for minutes, so on a loaded machine, wherever the signal lands
    # (the imports, the hand-over of the handlers, the command), it finds the run going
    status, err = _interrupt(LONG, sig, 0.0, tmp_path)
    assert status == code, err
    assert "Traceback" not in err
    assert err.strip() == f"gyrovib: {word}"


#: The console script with ``signal.signal`` wrapped: right after the N-th change of
#: the handler of signal S (other than to ignore it), the process sends itself S.
#: Deterministic: every hand-over from the default action to the command's own handler
#: is hit, not just those a timed signal happens to land in.
_AT_HANDLER_CHANGE = "\n".join([
    "import os, signal, sys",
    "target, nth = int(sys.argv[1]), int(sys.argv[2])",
    "real, seen = signal.signal, [0]",
    "def changed(signum, handler):",
    "    previous = real(signum, handler)",
    "    if signum == target and handler is not signal.SIG_IGN:",
    "        seen[0] += 1",
    "        if seen[0] == nth:",
    "            os.kill(os.getpid(), target)",
    "    return previous",
    "signal.signal = changed",
    "try:",
    "    from gyrovib.cli import main",
    "    sys.argv = ['gyrovib', 'analyze', '--format', 'json']",
    "    main()",
    "finally:",
    "    if seen[0] < nth:",
    "        sys.stderr.write('no such change\\n')",
])


@pytest.mark.parametrize(("sig", "code", "word"), [(signal.SIGINT, 130, "interrupted"),
                                                  (signal.SIGTERM, 143, "terminated"),
                                                  (signal.SIGHUP, 129, "hung up")])
def test_a_signal_at_every_change_of_its_handler_exits_in_one_line(
        tmp_path: Path, sig: int, code: int, word: str) -> None:
    # the console script's start-up handler, then the command's: a signal right after
    # either is answered in one line with its status, never by the default action
    changes = 0
    for nth in range(1, 10):
        done = subprocess.run([sys.executable, "-c", _AT_HANDLER_CHANGE, str(int(sig)),
                               str(nth)], capture_output=True, text=True, cwd=tmp_path,
                              env=clean_env(), timeout=120, check=False)
        if "no such change" in done.stderr:
            assert done.returncode == 0, done.stderr
            break
        changes += 1
        assert done.returncode == code, (nth, done.returncode, done.stderr)
        assert done.stderr.strip() == f"gyrovib: {word}", nth
        assert done.stdout == ""
    assert changes >= 2  # the start-up handler and the command's at least


def test_sigterm_exits_143_and_leaves_no_temporary_file(tmp_path: Path) -> None:
    target = tmp_path / "result.json"
    target.write_text("previous result\n")
    code, err = _interrupt([*LONG, "-o", str(target)], signal.SIGTERM, 2.0, tmp_path)
    assert code == 143, err
    assert err.strip() == "gyrovib: terminated"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["result.json"]
    assert target.read_text() == "previous result\n"


def test_interrupt_in_the_middle_of_the_write_removes_the_temporary_file(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # SIGINT/SIGTERM arrive as exceptions (KeyboardInterrupt, Terminated); the one
    # moment the temporary file exists is simulated by raising from fsync
    from gyrovib.cli import output
    from gyrovib.cli.main import Terminated

    target = tmp_path / "out.csv"
    target.write_text("old\n")
    for exc in (KeyboardInterrupt, Terminated):
        def interrupted(fd: int, exc: type[BaseException] = exc) -> None:
            raise exc

        monkeypatch.setattr(os, "fsync", interrupted)
        with pytest.raises(exc):
            output.write_output("new\n" * 100_000, str(target))
        assert sorted(p.name for p in tmp_path.iterdir()) == ["out.csv"]
        assert target.read_text() == "old\n"


# ---------------------------------------------------------------- pipes and failing output


@pytest.mark.parametrize("unbuffered", ["", "1"])
def test_reader_gone_before_the_end_exits_141_quietly(unbuffered: str) -> None:
    # a sweep CSV of 9 sensors × 401 rates (~460 KB) is far
    # larger than a pipe's buffer: the writer sees the closed pipe. With
    # PYTHONUNBUFFERED=1 the short write used to be dropped silently (exit 0).
    env = clean_env(PYTHONUNBUFFERED=unbuffered)
    process = subprocess.Popen([sys.executable, "-m", "gyrovib", "sweep", "--format", "csv",
                                "--profile", "flat-random-hover"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    assert process.stdout is not None and process.stderr is not None
    assert process.stdout.readline().startswith(b"sensor,")
    process.stdout.close()
    err = process.stderr.read()
    assert process.wait(timeout=60) == 141
    assert err == b""


def test_github_errors_to_a_closed_pipe_still_exit_2_with_the_messages(tmp_path: Path) -> None:
    bad = tmp_path / "bad.gyrovib.yaml"
    bad.write_text("gyrovib: 1\nsensors: 3\n")
    done = subprocess.run(
        f"{sys.executable} -m gyrovib validate --format github {bad} | true; "
        "exit ${PIPESTATUS[0]}", shell=True, executable="bash", capture_output=True,
        text=True, env=clean_env(), check=False, timeout=60)
    assert done.returncode == 2, done.stderr
    assert f"{bad}:2:" in done.stderr  # the located message on stderr despite the pipe
    assert "Traceback" not in done.stderr


def test_stdout_closed_is_a_write_failure_74() -> None:
    done = subprocess.run([sys.executable, "-m", "gyrovib", "analyze", "--format", "csv"],
                          stdout=None, stderr=subprocess.PIPE, text=True, env=clean_env(),
                          preexec_fn=lambda: os.close(1), check=False, timeout=60)
    assert done.returncode == 74
    assert done.stderr.strip() == "gyrovib: error: cannot write standard output: it is closed"


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
def test_stdout_on_a_full_disk_is_a_write_failure_74() -> None:
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-m", "gyrovib", "analyze"], stdout=full,
                              stderr=subprocess.PIPE, text=True, env=clean_env(), check=False,
                              timeout=60)
    assert done.returncode == 74
    assert done.stderr.strip() == ("gyrovib: error: cannot write standard output: "
                                   "No space left on device")


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
def test_output_to_a_full_device_is_74_not_a_bug(tmp_path: Path) -> None:
    result = CliRunner().invoke(cli, ["schema", "-o", "/dev/full"])
    assert result.exit_code == 74
    assert "--output: cannot write '/dev/full': No space left on device" in result.stderr


def test_output_through_a_symlink_writes_the_target_and_keeps_the_link(tmp_path: Path) -> None:
    real = tmp_path / "real.json"
    real.write_text("old\n")
    os.chmod(real, 0o640)
    link = tmp_path / "link.json"
    link.symlink_to(real.name)
    result = CliRunner().invoke(cli, ["schema", "-o", str(link)])
    assert result.exit_code == 0, result.stderr
    assert link.is_symlink() and os.readlink(link) == "real.json"
    assert real.read_text().startswith("{")
    assert real.stat().st_mode & 0o777 == 0o640
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.json", "real.json"]


def test_no_environment_variable_changes_an_exit_status(tmp_path: Path) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text("gyrovib: 1\nsensors: 3\n")
    for extra in ({}, {"GYROVIB_DEBUG": "1"}, {"NO_COLOR": "1", "TERM": "dumb"}):
        env = clean_env(**extra)
        assert gyrovib("validate", str(bad), env=env).returncode == 2
        assert gyrovib("analyze", "--samples", "1e85", "--method", "numeric",
                       env=env).returncode == 2


@pytest.mark.parametrize("samples", ["10000000000", "100000001", "1e85", "31"])
def test_samples_has_a_documented_range(samples: str) -> None:
    # gyrovib.limits.MAX_SAMPLES = 10^8, shown in --help
    result = CliRunner().invoke(cli, ["analyze", "--method", "numeric", "--samples", samples])
    assert result.exit_code == 2
    assert "--samples" in result.stderr and "Traceback" not in result.stderr
    assert "32 to 100,000,000" in CliRunner().invoke(cli, ["analyze", "--help"]).stdout


# ---------------------------------------------------------------- colour


@pytest.mark.parametrize(("mode", "env", "tty", "expected"), [
    ("always", {"NO_COLOR": "1"}, False, True),   # the explicit flag wins (no-color.org)
    ("never", {"FORCE_COLOR": "1"}, True, False),
    ("auto", {"NO_COLOR": "1"}, True, False),
    ("auto", {"FORCE_COLOR": "1"}, False, True),
    ("auto", {"NO_COLOR": "1", "FORCE_COLOR": "1"}, True, False),
    ("auto", {"TERM": "dumb"}, True, False),       # a dumb terminal gets none by default
    ("auto", {"TERM": "xterm"}, True, True),
    ("auto", {}, False, False),
])
def test_resolve_color(mode: str, env: dict[str, str], tty: bool, expected: bool) -> None:
    assert resolve_color(mode, env, tty) is expected


def test_color_always_beats_no_color_on_the_command_line() -> None:
    coloured = gyrovib("--color", "always", "analyze", "--profile", "engine-harmonics",
                       env=clean_env(NO_COLOR="1"))
    assert coloured.returncode == 0
    assert ANSI.search(coloured.stdout)
    plain = gyrovib("analyze", "--profile", "engine-harmonics", env=clean_env(NO_COLOR="1"))
    assert not ANSI.search(plain.stdout)
    # colour adds escapes only: stripped, the two tables are the same text
    assert ANSI.sub("", coloured.stdout) == plain.stdout


# ---------------------------------------------------------------- width, ASCII


@pytest.mark.parametrize("command", [["analyze"], ["select", "--budget", "0.001"],
                                     ["bounds", "--budget", "0.001"],
                                     ["sweep", "--rate-range", "0:10:3"]])
def test_tables_fit_an_80_column_terminal(command: list[str]) -> None:
    wide = gyrovib(*command, env=clean_env())
    assert max(len(line) for line in wide.stdout.splitlines()) > 80 or command[0] == "sweep"
    narrow = gyrovib(*command, env=clean_env(COLUMNS="80"))
    assert narrow.returncode in (0, 1), narrow.stderr
    assert max(len(line) for line in narrow.stdout.splitlines()) <= 80


def test_narrow_table_keeps_every_value_and_repeats_the_key_column() -> None:
    table = Table(title="t")
    table.add_column("sensor", no_wrap=True)
    for k in range(12):
        table.add_column(f"col{k}", justify="right", no_wrap=True)
    table.add_row("s1", *(f"{k}.{k}e-05" for k in range(12)))
    text = rich_text([table], width=60)
    lines = text.splitlines()
    assert max(len(line) for line in lines) <= 60
    for k in range(12):  # every cell is somewhere
        assert f"{k}.{k}e-05" in text
    groups = sum(1 for line in lines if line.startswith("┃ sensor"))
    assert groups >= 2 and text.count("│ s1 ") == groups


@pytest.mark.parametrize("encoding", ["ascii", "latin-1"])
def test_ascii_stream_gets_an_ascii_table(encoding: str) -> None:
    # latin-1 has ± and µ but neither Δ nor the box glyphs: the whole table falls back
    done = gyrovib("analyze", "--profile", "engine-harmonics",
                   env=clean_env(PYTHONIOENCODING=encoding))
    assert done.returncode == 0, done.stderr
    assert done.stdout.isascii()
    assert "Delta_V" in done.stdout and "Omega_K3" in done.stdout
    rows = [line for line in done.stdout.splitlines() if line.startswith(("+", "|"))]
    assert rows and len({len(line) for line in rows}) == 1  # laid out after transliteration
    # rich's box.ASCII: "+---+" above and below (no column dividers), "|---+---|" under
    # the header
    assert rows[0].strip("+-") == "" and rows[-1].strip("+-") == ""
    assert re.fullmatch(r"\|-+(\+-+)+\|", rows[2])
    if encoding != "ascii":
        return
    # (unknown figures taken as 0: cells that pass, rather than unverified ones)
    marks = gyrovib("select", "--budget", "0.001", "--assume-unknown", "zero",
                    env=clean_env(PYTHONIOENCODING="ascii"))
    assert marks.returncode == 0 and marks.stdout.isascii()
    assert re.search(r"\| +x [0-9][0-9.e+-]* +\|", marks.stdout)  # ✗ of a failing cell
    assert re.search(r"\| +v [0-9][0-9.e+-]* +\|", marks.stdout)  # ✓ of a passing one
    # adis16460 (its datasheet range ±100 deg/s) saturates under manoeuvre-saturation
    # (Ω_K3 = 96 deg/s + 3σ3 > 100 deg/s, docs/model.md section 9): x SAT, in ASCII too
    assert re.search(r"\| +x SAT ", marks.stdout)
    csv = gyrovib("analyze", "--format", "markdown", env=clean_env(PYTHONIOENCODING="ascii"))
    assert csv.returncode == 0 and csv.stdout.isascii() and "Delta_V" in csv.stdout


def test_color_flags_and_variables_on_the_command_line() -> None:
    # resolve_color's rules end to end (the output is a pipe, not a terminal): FORCE_COLOR
    # colours even with TERM=dumb, --color never beats it, --color always beats NO_COLOR
    # and TERM=dumb together
    args = ["analyze", "--profile", "engine-harmonics"]
    forced = gyrovib(*args, env=clean_env(FORCE_COLOR="1", TERM="dumb"))
    assert ANSI.search(forced.stdout)
    never = gyrovib("--color", "never", *args, env=clean_env(FORCE_COLOR="1"))
    assert not ANSI.search(never.stdout)
    always = gyrovib("--color", "always", *args, env=clean_env(NO_COLOR="1", TERM="dumb"))
    assert ANSI.search(always.stdout)
    assert ANSI.sub("", always.stdout) == ANSI.sub("", forced.stdout) == never.stdout


def test_a_long_table_says_once_that_csv_and_json_are_the_fast_path() -> None:
    # a sweep table is a row per rate: 2,001 rates of one sensor × profile is past
    # SLOW_TABLE_ROWS (2,000); 2,000 is not; csv and json never say it
    one = ["sweep", "--sensor", "adxrs453", "--profile", "flat-random-hover"]
    long = CliRunner().invoke(cli, [*one, "--rate-range", "0:10:2001"])
    assert long.exit_code == 0, long.stderr
    note = ("gyrovib: note: 2,001 table rows take a while to draw; "
            "--format csv or --format json is the fast path\n")
    assert long.stderr == note  # once, on stderr only
    assert "fast path" not in long.stdout
    assert long.stdout.count("│") > 2001  # the table is still drawn
    short = CliRunner().invoke(cli, [*one, "--rate-range", "0:10:2000"])
    assert short.exit_code == 0 and short.stderr == ""
    for fmt in ("csv", "json"):
        fast = CliRunner().invoke(cli, [*one, "--rate-range", "0:10:2001", "--format", fmt])
        assert fast.exit_code == 0 and fast.stderr == ""


def test_to_ascii() -> None:
    assert to_ascii("Δ_V ± 2 ✓ ✗ ┏━┳┓ │ └─┘ Ω²") == "Delta_V +/- 2 v x +=++ | +-+ Omega^2"
    assert to_ascii("é") == "?"


# ---------------------------------------------------------------- standard input, names


def test_validate_dash_reads_standard_input(valid_text: str) -> None:
    ok = CliRunner().invoke(cli, ["validate", "-"], input=valid_text)
    assert ok.exit_code == 0, ok.stderr
    assert "1 file(s) valid: 2 sensor(s), 1 profile(s)" in ok.stderr
    bad = CliRunner().invoke(cli, ["validate", "-"], input="gyrovib: 1\nsensors: 3\n")
    assert bad.exit_code == 2
    assert bad.stderr.startswith("<stdin>:2:")


def test_stdin_and_files_merge_and_clash(valid_text: str, valid_file: Path) -> None:
    clash = CliRunner().invoke(cli, ["validate", "-", str(valid_file)], input=valid_text)
    assert clash.exit_code == 2
    assert "<stdin>" in clash.stderr or str(valid_file) in clash.stderr
    twice = CliRunner().invoke(cli, ["validate", "-", "-"], input=valid_text)
    assert twice.exit_code == 2 and "only once" in twice.stderr


def test_printable_escapes_control_characters() -> None:
    assert printable("a\nb\x1b[31mc\rd\te\x7f\x9b") == "a\\nb\\x1b[31mc\\rd\\te\\x7f\\x9b"
    assert printable("Δ_V sensör") == "Δ_V sensör"


def test_hostile_file_names_are_escaped_in_messages_and_annotations(tmp_path: Path) -> None:
    name = tmp_path / "evil\n\x1b[31mname.yaml"
    name.write_text("gyrovib: 1\nsensors: 3\n")
    result = CliRunner().invoke(cli, ["validate", "--format", "github", str(name)])
    assert result.exit_code == 2
    assert "\x1b" not in result.stderr and "\x1b" not in result.stdout
    assert len(result.stderr.strip().splitlines()) == 1
    assert "evil\\n\\x1b[31mname.yaml:2:" in result.stderr
    annotation = result.stdout.strip()
    assert len(annotation.splitlines()) == 1
    assert "evil%0A\\x1b[31mname.yaml" in annotation
