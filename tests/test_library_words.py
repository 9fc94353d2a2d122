"""The library speaks of its arguments, the command line of its options.

A warning that advises an argument is a :class:`gyrovib.errors.Note`: as text it names
the library's argument (``strict=True``), and the command line words it with its option
(``--strict``) at the edge, as :func:`gyrovib.cli.options.as_option` does for errors.
A scan of every string the library and the kernels hold (not their docstrings or
comments) keeps command-line flags out of them.
"""

from __future__ import annotations

import ast
import pickle
import re
from dataclasses import dataclass
from pathlib import Path

import click
from click.testing import CliRunner

from gyrovib.cli.main import cli
from gyrovib.cli.options import as_options, option_words
from gyrovib.errors import Note, fill, headed, literal

SRC = Path(__file__).resolve().parents[1] / "src" / "gyrovib"

#: A flag: two dashes, a letter, not inside a word (``x--y``) nor a longer run of dashes.
FLAG = re.compile(r"(?<![\w-])--[a-z][a-z0-9-]*")

#: Options of other programs that a message may name: blackbox_decode writes the
#: accelerometer in g only when told ``--unit-acceleration g`` (the Betaflight preset).
FOREIGN = {"--unit-acceleration"}


def _docstrings(tree: ast.AST) -> set[int]:
    """The ids of the string constants that are documentation: a module's, class's or
    function's first statement, and a string standing alone as a statement (an
    attribute's docstring)."""
    return {id(node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)
            and isinstance(node.value.value, str)}


def flags_in(path: Path) -> list[tuple[int, str]]:
    """Each flag in a string constant or f-string piece of ``path`` that is not a
    docstring, with its line."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    docs = _docstrings(tree)
    return [(node.lineno, found) for node in ast.walk(tree)
            if isinstance(node, ast.Constant) and isinstance(node.value, str)
            and id(node) not in docs
            for found in FLAG.findall(node.value)]


def test_the_scan_finds_a_flag_in_a_string_and_none_in_a_docstring(tmp_path: Path) -> None:
    """A flag in a message (plain or f-string) is found; in a docstring or a comment,
    or inside a word or a rule of dashes, it is not."""
    source = tmp_path / "m.py"
    source.write_text(
        '"""Module: --strict is fine here."""\n'
        "def f(n):\n"
        '    """--yield in a docstring."""\n'
        "    # --breakpoints in a comment\n"
        '    a = f"{n} (raise --breakpoints)"\n'
        '    b = "x--y and ---- and -- alone"\n'
        "    return a + b + \"--yield: no lot\"\n", encoding="utf-8")
    assert flags_in(source) == [(5, "--breakpoints"), (7, "--yield")]


def _options(command: click.Command, ctx: click.Context) -> set[str]:
    found = {opt for p in command.params for opt in p.opts if opt.startswith("--")}
    if isinstance(command, click.Group):
        for name in command.list_commands(ctx):
            sub = command.get_command(ctx, name)
            assert sub is not None
            found |= _options(sub, click.Context(sub, parent=ctx, info_name=name))
    return found


#: The modules of words the library shares with the renderers: select's reasons are
#: worded there (its frame's ``reason``), at the bottom layer.
SHARED_WORDS = ("reasons.py",)


def test_api_and_core_hold_no_flag() -> None:
    """No string of gyrovib.api, gyrovib.core or the shared words (select's reasons)
    names a command-line flag: a library message names the argument (a Note, worded with
    the option by the command line). The few flags of other programs a message may name
    are none of gyrovib's options."""
    paths = [*(path for package in ("api", "core") for path in sorted((SRC / package).rglob(
        "*.py"))), *(SRC / name for name in SHARED_WORDS)]
    found = [(str(path.relative_to(SRC)), line, flag) for path in paths
             for line, flag in flags_in(path) if flag not in FOREIGN]
    assert found == []
    # the probe: the scan finds the option mission's renderer words its advice with
    assert "--assume-unknown" in [flag for _, flag in flags_in(SRC / "render" / "mission.py")]
    assert FOREIGN.isdisjoint(_options(cli, click.Context(cli, info_name="gyrovib")))


def test_a_note_names_arguments_in_the_library_and_options_on_the_command_line() -> None:
    note = Note("cut short ({strict} refuses such a file); give {accel_unit}, raise "
                "{breakpoints}; {yield_target}: none", ("strict", True), ("accel_unit", "g"),
                ("breakpoints", None), ("yield_target", None))
    assert note == ("cut short (strict=True refuses such a file); give accel_unit='g', "
                    "raise breakpoints; yield_target: none")
    assert note.worded(option_words) == ("cut short (--strict refuses such a file); give "
                                         "--accel-unit g, raise --breakpoints; --yield: none")
    copy = pickle.loads(pickle.dumps(note))  # a worker process hands its fit back pickled
    assert type(copy) is Note and copy == note and copy.arguments == note.arguments
    headed_note = headed("a.ulg: ", note)
    assert isinstance(headed_note, Note) and headed_note == "a.ulg: " + note
    assert headed_note.worded(option_words).startswith("a.ulg: cut short (--strict ")
    assert headed("a.ulg: ", "plain {strict}") == "a.ulg: plain {strict}"


@dataclass(frozen=True)
class _Inner:
    warnings: tuple[str, ...]


@dataclass(frozen=True)
class _Outer:
    inner: _Inner
    rows: dict[int, tuple[str, ...]]
    notes: list[str]
    count: int


def test_as_options_words_every_note_a_result_holds_and_keeps_the_rest() -> None:
    """Notes nested in results, tuples, dicts and lists come back worded with the
    options, plain strings as they were; a result without a note is the same object."""
    note = Note("raise {breakpoints}", ("breakpoints", None))
    result = _Outer(_Inner(("plain", note)), {3: (note,)}, [note], 7)
    worded = as_options(result)
    assert worded == _Outer(_Inner(("plain", "raise --breakpoints")),
                            {3: ("raise --breakpoints",)}, ["raise --breakpoints"], 7)
    assert not any(isinstance(w, Note) for w in worded.inner.warnings)
    assert result.inner.warnings[1] == "raise breakpoints"  # the library's result unchanged
    plain = _Outer(_Inner(("plain",)), {}, [], 1)
    assert as_options(plain) is plain


def test_the_users_text_in_a_note_is_never_read_as_an_argument() -> None:
    """A file named ``{strict}.bin`` heading a note that names ``strict``: only the note's
    own ``{strict}`` is worded; the name keeps its braces, in the library and on the
    command line alike; a doubled brace in a template is one brace."""
    note = headed("{strict}.bin: ", Note("cut short ({strict} refuses such a file)",
                                         ("strict", True)))
    assert note == "{strict}.bin: cut short (strict=True refuses such a file)"
    assert note.worded(option_words) == "{strict}.bin: cut short (--strict refuses such a file)"
    assert Note(f"{literal('a {b}} {{c')}: {{b}}", ("b", None)) == "a {b}} {{c: b"
    assert fill("{x} {y} {{x}} {", ("x",), str.upper) == "X {y} {x} {"
    assert fill("{x} {{x}}", (), str.upper) == "{x} {{x}}"  # no arguments: the text as is


def test_a_column_named_like_an_option_keeps_its_name(tmp_path: Path) -> None:
    """A CSV whose lone rate column is named ``{rate_columns}``: the message words the
    option it advises and shows the column's name as the file has it."""
    path = tmp_path / "one.csv"
    path.write_text("t,{rate_columns}\n" + "".join(f"{k / 100},0.5\n" for k in range(64)))
    r = CliRunner().invoke(cli, ["profile", str(path)])
    assert r.exit_code == 2
    assert "1 rate column(s) ('{rate_columns}') besides the time" in r.stderr
    assert "place them with --rate-columns X,Y,Z, e.g. --rate-columns -,-,{rate_columns}" \
        in r.stderr, r.stderr


def test_select_reasons_name_the_argument_in_the_library_and_the_option_in_the_cli(
        tmp_path: Path) -> None:
    """An unverified cell's reason advises taking the unknown figures as 0: the library's
    frame names the argument (``assume_unknown='zero'``), the command line's JSON and CSV
    its option (``--assume-unknown zero``), as it always has."""
    import json

    import gyrovib

    frame = gyrovib.select(budget="10deg/h", criterion="both").to_frame()
    reasons = [r for r in frame["reason"] if isinstance(r, str) and "unverified" in r]
    assert reasons  # the probe: the bundled catalogue has unverified cells
    assert all("or assume_unknown='zero' to take it as 0" in r and "--" not in r.replace(
        " -- ", "") for r in reasons)
    result = CliRunner().invoke(cli, ["select", "--budget", "10deg/h", "--criterion", "both",
                                      "--format", "json"])
    cells = [cell for sensor in json.loads(result.stdout)["sensors"]
             for cell in sensor["profiles"] if cell["status"] == "unverified"]
    assert len(cells) == len(reasons)
    assert all("or --assume-unknown zero to take it as 0" in c["reason"] for c in cells)
    csv = CliRunner().invoke(cli, ["select", "--budget", "10deg/h", "--criterion", "both",
                                   "--format", "csv"]).stdout
    assert csv.count("or --assume-unknown zero to take it as 0") == len(reasons)
    assert "assume_unknown=" not in result.stdout + csv
