"""Absurd mission durations: a warning past 100 years, a refusal where the result overflows.

The bound is gyrovib.models.mission.MAX_DURATION (100 Julian years, 3.15576e9 s). The
sensor here has k2 = 1 (deg/s)^-1 alone under a random vibration about x3 of σ3² =
1e-3 (deg/s)²/Hz × 2000 Hz = 2 (deg/s)², so Δ_V = k2·σ3² = 2 deg/s (eq. 14); the angle
θ_V = T·Δ_V overflows double precision (about 1.8e308) for T above about 9e307 s.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gyrovib.models.mission import MAX_DURATION
from tests.conftest import invoke

CATALOGUE = """\
gyrovib: 1
sensors:
  - id: k2-only
    coefficients: {{k2: 1.0}}
profiles:
  - id: random-x3
    rate: [0, 0, 0]
    random:
      psd:
        x3: [[20, 1.0e-3], [2020, 1.0e-3]]
missions:
  - id: trip
    segments:
      - {{profile: random-x3, duration: 60}}
      - {{profile: random-x3, duration: {duration}}}
"""


def run(tmp_path: Path, duration: str) -> tuple[int, str, str]:
    path = tmp_path / "trip.yaml"
    path.write_text(CATALOGUE.format(duration=duration), encoding="utf-8")
    result = invoke("mission", path, "--format", "json")
    return result.exit_code, result.stdout, result.stderr


def test_the_bound_is_a_hundred_years() -> None:
    assert MAX_DURATION == 100 * 365.25 * 86400.0


@pytest.mark.parametrize("duration", ["1e300", f"{MAX_DURATION * 1.01!r}", "877000 h"])
def test_a_duration_beyond_the_bound_is_read_with_a_warning(tmp_path: Path,
                                                            duration: str) -> None:
    """877000 h is 100.04 years; the warning is placed at the segment's duration
    (line 15 of the file, column 40)."""
    code, stdout, stderr = run(tmp_path, duration)
    assert code == 0 and '"mission": "trip"' in stdout
    assert stderr.startswith(f"gyrovib: warning: {tmp_path / 'trip.yaml'}:15:40: mission "
                             "'trip', segment 2: ")
    assert "is longer than 100 years: a typo?" in stderr


@pytest.mark.parametrize("duration", ["3e9", "10 min"])  # 3e9 s is 95 years
def test_a_plausible_duration_says_nothing(tmp_path: Path, duration: str) -> None:
    code, _, stderr = run(tmp_path, duration)
    assert code == 0 and stderr == ""


def test_an_angle_that_overflows_is_refused(tmp_path: Path) -> None:
    """1.7e308 s × 2 deg/s is beyond double precision: exit 2, no inf printed, placed at
    the mission's first duration (line 14, column 40)."""
    code, stdout, stderr = run(tmp_path, "1.7e308")
    assert code == 2 and stdout == ""
    assert f"{tmp_path / 'trip.yaml'}:14:40: mission 'trip', sensor 'k2-only': the angle" in (
        stderr)


def test_durations_whose_sum_overflows_are_refused(tmp_path: Path) -> None:
    path = tmp_path / "trip.yaml"
    text = CATALOGUE.format(duration="1.7e308").replace("duration: 60", "duration: 1.7e308")
    path.write_text(text, encoding="utf-8")
    result = invoke("mission", path)
    assert result.exit_code == 2
    assert "mission 'trip': its durations add up to more than double precision" in (
        result.stderr)
