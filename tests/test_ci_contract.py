"""The CI contract: .ci/run runs exactly the test command README.md gives.

Source of the expectation: the project's rule that the README's Quick start
and CI agree, so that what a contributor runs is what CI runs.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _quick_start() -> list[str]:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    block = re.search(r"```sh\n(.*?)```", section, re.S)
    assert block, "README's Quick start has no sh block"
    return [line for line in block.group(1).splitlines() if line.strip()]


def test_quick_start_has_exactly_two_commands() -> None:
    commands = _quick_start()
    assert len(commands) == 2, commands
    assert "gyrovib analyze" in commands[0]
    assert "pytest" in commands[1]


def test_ci_runs_the_readme_test_command() -> None:
    run = (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines()
    assert _quick_start()[1] in run


def test_ci_installs_within_the_constraints() -> None:
    assert "-c constraints.txt" in _quick_start()[1]
    assert (ROOT / "constraints.txt").is_file()


def _requirement(lines: list[str], name: str) -> str:
    found = [line.split("#", 1)[0].strip().strip('",') for line in lines]
    found = [r for r in found if re.match(rf"{re.escape(name)}\s*[<>=!~]", r)]
    assert len(found) == 1, (name, found)
    return found[0].replace(" ", "")


def test_published_highspy_range_is_the_checked_one() -> None:
    # core/highs.py uses highspy's private base class _Highs: a user's install must not
    # resolve to a highspy release the suite has not run against
    import tomllib

    meta = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    published = _requirement(meta["project"]["dependencies"], "highspy")
    checked = _requirement((ROOT / "constraints.txt").read_text(encoding="utf-8").splitlines(),
                           "highspy")
    assert published == checked
    assert "<" in published


def test_the_test_command_runs_in_parallel_with_a_checked_xdist() -> None:
    # the README's test command uses pytest-xdist (-n auto), so the test extra installs it
    # and constraints.txt bounds it
    import tomllib

    assert " -n auto" in _quick_start()[1]
    meta = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert _requirement(meta["project"]["optional-dependencies"]["test"], "pytest-xdist")
    constraint = _requirement((ROOT / "constraints.txt").read_text(encoding="utf-8")
                              .splitlines(), "pytest-xdist")
    assert "<" in constraint


def test_hypothesis_profile_is_deterministic() -> None:
    # tests/conftest.py loads the "ci" profile unless GYROVIB_HYPOTHESIS_PROFILE asks
    # otherwise: the same examples on every run, no timing deadline
    import os

    from hypothesis import settings

    if os.environ.get("GYROVIB_HYPOTHESIS_PROFILE", "ci") != "ci":
        pytest.skip("another hypothesis profile was chosen")
    assert settings.default.derandomize
    assert settings.default.deadline is None
    # and no test opts out of it
    for path in (ROOT / "tests").glob("test_*.py"):
        assert not re.search(r"derandomize\s*=\s*False", path.read_text(encoding="utf-8")), path


def test_readme_example_table_is_what_gyrovib_prints() -> None:
    # the README's console example: every table line it shows is printed, verbatim,
    # by the command it shows (the bundled catalogues, current code)
    import shlex

    from tests.conftest import invoke

    text = (ROOT / "README.md").read_text(encoding="utf-8")
    block = re.search(r"```console\n\$ (gyrovib analyze [^\n]*)\n(.*?)```", text, re.S)
    assert block, "README has no analyze console example"
    args = shlex.split(block.group(1))[1:]
    result = invoke(*args, env={"COLUMNS": "160", "NO_COLOR": "1"})
    assert result.exit_code == 0, result.stderr
    shown = [line for line in block.group(2).splitlines() if line[:1] in "┏┃┡│└"]
    assert len(shown) >= 5
    for line in shown:
        assert line in result.stdout.splitlines(), line
