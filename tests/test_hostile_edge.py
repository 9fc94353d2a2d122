"""Hostile input at the command line's edge (issue 26): every command validates
every file whole, output names and signals, standard error that cannot be
written, ``GYROVIB_DEBUG``; and the notebook API's checks of its arguments."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.conftest import invoke

HEADER = "gyrovib: 1\n"
#: One valid profile after the sensors, so that ``bounds`` has something to bound.
PROFILES = "profiles:\n  - id: p\n    random: {rms: [0, 0, 1]}\n"
SENSOR = HEADER + "sensors:\n  - id: a\n    coefficients:\n"

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
