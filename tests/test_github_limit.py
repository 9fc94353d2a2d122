"""GitHub shows at most 10 annotations of each level per step (the runner drops the
rest silently): past that, the worst 10 are annotated and one notice counts the
rest. Usage errors are annotated too when --format github was asked for."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from gyrovib.cli.main import cli
from gyrovib.errors import Problem
from gyrovib.render.github import GITHUB_LIMIT, annotations, capped, problems_to_github


def levels(text: str) -> list[str]:
    return [line.split(" ", 1)[0].split("::")[1] for line in text.splitlines()
            if line.startswith("::")]


def test_the_limit_is_githubs() -> None:
    # docs.github.com, "Workflow commands": 10 error, 10 warning and 10 notice
    # annotations per step are shown
    assert GITHUB_LIMIT == 10


def test_ten_problems_are_ten_annotations_and_no_notice() -> None:
    problems = [Problem(f"problem {k}", "c.yaml", k + 1, 1) for k in range(10)]
    assert levels(problems_to_github(problems)) == ["error"] * 10


def test_past_ten_the_first_ten_and_one_notice_counting_the_rest() -> None:
    problems = [Problem(f"problem {k}", "c.yaml", k + 1, 1) for k in range(23)]
    text = problems_to_github(problems)
    assert levels(text) == ["error"] * 10 + ["notice"]
    assert "line=10," in text and "line=11," not in text  # in the order given: file order
    assert "13 more error(s) not annotated" in text.splitlines()[-1]


def test_capped_keeps_the_worst_of_each_level_in_the_given_order() -> None:
    # rank: the lower the worse; 15 errors ranked 14..0, 12 notices ranked 0..11
    items = [("f", k, None, f"e{k}", "error") for k in range(15)]
    items += [("f", 100 + k, None, f"n{k}", "notice") for k in range(12)]
    rank = [float(14 - k) for k in range(15)] + [float(k) for k in range(12)]
    kept, dropped = capped(items, rank=rank)
    errors = [item[3] for item in kept if item[4] == "error"]
    assert errors == [f"e{k}" for k in range(5, 15)]  # the 10 lowest ranks, file order kept
    notices = [item[3] for item in kept if item[4] == "notice"]
    assert notices[:-1] == [f"n{k}" for k in range(9)]  # 9 + the closing notice = 10
    assert "5 error(s), 3 notice(s) more not annotated" in notices[-1]
    assert len(dropped) == 5 + 3


def test_left_out_annotations_stay_in_the_log_as_plain_lines() -> None:
    items = [("f.yaml", k, "t", f"message {k}", "error") for k in range(12)]
    lines = annotations(items).splitlines()
    assert [line.startswith("::error") for line in lines].count(True) == 10
    assert lines[-2:] == ["error: f.yaml:10: t: message 10", "error: f.yaml:11: t: message 11"]


def test_select_annotates_the_ten_worst_failures(tmp_path: Path) -> None:
    # 14 sensors all failing, k2 growing with the index: the margin Δ*/Δ_V(RMS)
    # falls as k2 grows, so the worst are the last 10 (s04 ... s13)
    sensors = "".join(f"  - id: s{k:02d}\n    coefficients: {{k2: {1e-3 * (k + 1)}}}\n"
                      for k in range(14))
    path = tmp_path / "many.gyrovib.yaml"
    path.write_text("gyrovib: 1\nsensors:\n" + sensors
                    + "profiles:\n  - id: p\n    random: {rms: [0, 0, 10]}\n")
    result = CliRunner().invoke(cli, ["select", str(path), "--budget", "1e-9",
                                      "--require", "all", "--format", "github"])
    assert result.exit_code == 1, result.stderr
    annotated = [line for line in result.stdout.splitlines() if line.startswith("::error")]
    assert len(annotated) == 10
    named = sorted(line.split("title=")[1].split(" ")[0] for line in annotated)
    assert named == [f"s{k:02d}" for k in range(4, 14)]
    notices = [line for line in result.stdout.splitlines() if line.startswith("::notice")]
    assert len(notices) == 2  # the select summary and the count of the rest
    assert "4 error(s) more not annotated" in result.stdout
    assert sum(line.startswith("error: ") for line in result.stdout.splitlines()) == 4


def test_usage_errors_are_annotated_with_format_github() -> None:
    result = CliRunner().invoke(cli, ["select", "--budget", "1", "--format", "github",
                                      "--require", "some"])
    assert result.exit_code == 2
    assert result.stdout.startswith("::error title=gyrovib usage::")
    assert "--require" in result.stdout
    plain = CliRunner().invoke(cli, ["select", "--budget", "1", "--require", "some"])
    assert plain.exit_code == 2 and plain.stdout == ""
