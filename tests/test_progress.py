"""Progress of long work: one mechanism, reported by the library, drawn on a
terminal only (gyrovib/progress.py, cli/progress.py)."""

from __future__ import annotations

import io
from pathlib import Path

import pytest

from gyrovib import progress
from tests.conftest import invoke


def test_advance_without_a_receiver_does_nothing_and_with_one_reaches_the_total() -> None:
    calls: list[tuple[str, int, int]] = []
    progress.advance("x", 1, 2)  # no receiver: nothing happens, nothing raised
    with progress.receiving(lambda label, done, total: calls.append((label, done, total))):
        progress.advance("x", 1, 2)
    progress.advance("x", 2, 2)  # the receiver is gone with the block
    assert calls == [("x", 1, 2)]


def test_datasheet_worst_cases_report_monotone_progress_to_the_end(tmp_path: Path) -> None:
    # 300 datasheet sensors of different ranges × 2 profiles: 600 programmes (more than
    # the envelope solver's SEEDED, so the windowed path); each solve's reports go
    # forward and end with done == total (select solves more than once: runs restart)
    from tests.test_hostile_cost import TWO_PROFILES, spec_catalogue

    (tmp_path / "s.yaml").write_text(spec_catalogue(300), encoding="utf-8")
    (tmp_path / "p.yaml").write_text(TWO_PROFILES, encoding="utf-8")
    import gyrovib

    calls: list[tuple[str, int, int]] = []
    with progress.receiving(lambda label, done, total: calls.append((label, done, total))):
        gyrovib.select(gyrovib.load([tmp_path / "s.yaml", tmp_path / "p.yaml"]), budget=1.0)
    mine = [(d, t) for label, d, t in calls if label == "datasheet worst cases"]
    assert len(mine) >= 3 and mine[-1][0] == mine[-1][1]
    runs: list[list[tuple[int, int]]] = [[]]
    for d, t in mine:
        runs[-1].append((d, t))
        if d == t:
            runs.append([])
    runs = [r for r in runs if r]
    assert max(len(r) for r in runs) >= 3  # the big solve reports as it goes
    for r in runs:
        assert [d for d, _ in r] == sorted(d for d, _ in r)
        assert len({t for _, t in r}) == 1 and r[-1][0] == r[-1][1]


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_a_bar_is_drawn_on_a_terminal_and_nothing_elsewhere(monkeypatch: pytest.MonkeyPatch
                                                            ) -> None:
    from gyrovib.cli import progress as cli_progress

    monkeypatch.setattr(cli_progress, "DELAY", 0.0)
    screen = _Terminal()
    monkeypatch.setattr("sys.stderr", screen)
    with cli_progress.terminal_progress():
        for i in range(5):
            progress.advance("datasheet worst cases", i, 4)
    assert "datasheet worst cases" in screen.getvalue()
    piped = io.StringIO()  # not a terminal: no receiver, nothing written
    monkeypatch.setattr("sys.stderr", piped)
    with cli_progress.terminal_progress():
        progress.advance("datasheet worst cases", 1, 4)
    assert piped.getvalue() == ""


def test_commands_under_a_runner_write_no_progress(tmp_path: Path) -> None:
    # CliRunner's stderr is not a terminal (like a pipe or CI): a select of datasheet
    # sensors long enough to report writes nothing but its own lines there
    from tests.test_hostile_cost import TWO_PROFILES, spec_catalogue

    (tmp_path / "s.yaml").write_text(spec_catalogue(60), encoding="utf-8")
    (tmp_path / "p.yaml").write_text(TWO_PROFILES, encoding="utf-8")
    result = invoke("select", tmp_path / "s.yaml", tmp_path / "p.yaml", "--budget", "1",
                    "--format", "csv")
    assert result.exit_code in (0, 1), result.stderr
    assert "worst cases" not in result.stderr and "\x1b" not in result.stderr
