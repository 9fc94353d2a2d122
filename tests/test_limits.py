"""Physical limits of the catalogue format (nothing that validate accepts
may analyze refuse): what ``gyrovib validate`` accepts every command computes
without overflow, and what it refuses every command refuses at the same
FILE:LINE:COL, exit 2.

The limits are the models' (gyrovib.models._types.MAX_MAGNITUDE and the rules
of profile.py, sensor.py, catalogue.py); the cases are the audit's.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from gyrovib.models import _types
from gyrovib.models.profile import correlation_problem
from tests.conftest import invoke

BASE = """\
gyrovib: 1
sensors:
  - id: s
    coefficients: {k2: 1.0e-4, A1: 1.0e-3, k3: 1.0e-6}
    vre: 4.0e-4
profiles:
  - id: p
    rate: [0, 0, 10]
    harmonic:
      - {frequency: 10, amplitude: [0.1, 0.1, 0.5]}
    random: {rms: [0.1, 0.1, 0.2]}
    acceleration:
      harmonic:
        - {frequency: 120, amplitude: [0.5, 0.5, 2.0]}
      random:
        psd:
          x1: [[20, 0.04], [2000, 0.04]]
        coherence: [0, 0, 0]
"""

PSD_BLOCK = "psd:\n          x1: [[20, 0.04], [2000, 0.04]]"
SPEC = "coefficients: {k2: 1.0e-4, A1: 1.0e-3, k3: 1.0e-6}"
ORDERS = ("rate: [0, 0, 10]\n    harmonics: {fundamental: 10, orders: "
          "[{order: 1, amplitude: [0, 0, 1]}, {order: 1000, amplitude: [0, 0, 1]}]}")

# (id, old, new, the text the message is located at, words the message must hold)
CASES = [
    ("acceleration-psd-1e300", "x1: [[20, 0.04]", "x1: [[20, 1.0e300]", "1.0e300",
     ("must not be greater than 1e+24", "PSD level")),
    ("acceleration-rms-1e200", PSD_BLOCK, "rms: [1.0e200, 1, 1]", "1.0e200",
     ("rms[0]", "must not be greater than 1e+12", "4th power")),
    ("acceleration-tone-1e200", "[0.5, 0.5, 2.0]", "[1.0e200, 0.5, 2.0]", "1.0e200",
     ("amplitude[0]", "must not be greater than 1e+12")),
    ("rate-tone-1e200", "[0.1, 0.1, 0.5]", "[0.1, 0.1, 1.0e200]", "1.0e200",
     ("amplitude[2]", "10th power")),
    ("carrier-rate-1e300", "rate: [0, 0, 10]", "rate: [0, 0, 1.0e300]", "1.0e300",
     ("rate[2]",)),
    ("psd-variance", PSD_BLOCK, "psd:\n          x1: [[1, 1.0e20], [1.0e10, 1.0e20]]",
     "[[1, 1.0e20]", ("variance", "1e+30")),
    ("mount-gain", "    random: {rms: [0.1, 0.1, 0.2]}\n",
     "    random: {rms: [0.1, 0.1, 0.2]}\n    mount: [[10, 1], [20, 1.0e100]]\n", "1.0e100",
     ("mount[1][1]", "80 dB")),
    ("g2-sensitivity-1e300", "vre: 4.0e-4", "g2_sensitivity: {G11: 1.0e300}", "1.0e300",
     ("G11", "must not be greater than 1e+12")),
    ("vre-1e300", "vre: 4.0e-4", "vre: -1.0e300", "-1.0e300", ("vre", "-1e+12")),
    ("spec-range-1e-300", SPEC,
     "specs: {range: 1.0e-300, nonlinearity: {value: 0.5, unit: '%FS'}}", "1.0e-300",
     ("range", "0.001 to 1e+07 deg/s")),
    ("spec-range-1e300", SPEC,
     "specs: {range: 1.0e300, nonlinearity: {value: 0.5, unit: '%FS'}}", "1.0e300",
     ("range", "0.001 to 1e+07 deg/s")),
    ("nonlinearity-1e300-FS", SPEC,
     "specs: {range: 100, nonlinearity: {value: 1.0e300, unit: '%FS'}}", "1.0e300",
     ("nonlinearity", "100 %FS")),
    ("nonlinearity-absolute", SPEC,
     "specs: {range: 100, nonlinearity: {value: 200, unit: deg/s}}", "200",
     ("more than the range",)),
    ("asymmetry-1e300", SPEC, "specs: {range: 100, nonlinearity: {value: 0.5, unit: '%FS'}, "
     "asymmetry: {value: 1.0e300, unit: ppm}}", "1.0e300", ("100 %",)),
    ("coherence-1-1-minus1", "coherence: [0, 0, 0]", "coherence: [1, 1, -1]", "[1, 1, -1]",
     ("not a valid correlation", "positive semi-definite")),
    ("coherence-09-09-minus09", "coherence: [0, 0, 0]", "coherence: [0.9, 0.9, -0.9]",
     "[0.9, 0.9, -0.9]", ("not a valid correlation",)),
    ("coherence-minus1-x3", "coherence: [0, 0, 0]", "coherence: [-1, -1, -1]",
     "[-1, -1, -1]", ("not a valid correlation",)),
    ("harmonic-order-1000", "rate: [0, 0, 10]", ORDERS, "1000",
     ("order", "must not be greater than 64", "cost grows")),
]

COMMANDS = {
    "validate": ["validate"],
    "analyze": ["analyze"],
    "bounds": ["bounds", "--budget", "0.01"],
    "select": ["select", "--budget", "0.01"],
    "sweep": ["sweep", "--rate-range", "0:1:3"],
}


def place(text: str, token: str) -> tuple[int, int]:
    """Line and column (1-based) of the first ``token`` in ``text``."""
    offset = text.index(token)
    line = text.count("\n", 0, offset) + 1
    return line, offset - (text.rfind("\n", 0, offset) + 1) + 1


def test_the_base_file_is_computed_by_every_command(tmp_path: Path) -> None:
    path = tmp_path / "base.yaml"
    path.write_text(BASE)
    for name, args in COMMANDS.items():
        result = invoke(args[0], str(path), *args[1:])
        assert result.exit_code in (0, 1), (name, result.stderr)


@pytest.mark.parametrize(("name", "old", "new", "token", "words"), CASES,
                         ids=[c[0] for c in CASES])
def test_refused_by_every_command_at_the_same_place(tmp_path: Path, name: str, old: str,
                                                   new: str, token: str,
                                                   words: tuple[str, ...]) -> None:
    assert old in BASE
    text = BASE.replace(old, new, 1)
    path = tmp_path / f"{name}.yaml"
    path.write_text(text)
    line, column = place(text, token)
    where = f"{path}:{line}:{column}: "
    for command, args in COMMANDS.items():
        result = invoke(args[0], str(path), *args[1:])
        assert result.exit_code == 2, (command, result.stdout, result.stderr)
        assert result.stdout == ""
        first = result.stderr.splitlines()[0]
        assert first.startswith(where), (command, first)
        for word in words:
            assert word in first, (command, first)


def test_the_limit_is_derived_from_the_float_range() -> None:
    # the largest rate at a sensor (models/_types.py): a magnitude through a mount and an
    # input-side response, rad/s to deg/s, 64 groups of 64 orders + 64 tones + random
    worst = _types.MAX_MAGNITUDE * _types.MAX_GAIN**2 * (180 / math.pi) * (64 * 64 + 64 + 1)
    assert worst**10 < 1e300  # the 10th power is the highest the model computes
    assert pytest.approx(_types.MAX_MAGNITUDE**2) == _types.MAX_VARIANCE


@pytest.mark.parametrize(("r12", "r13", "r23", "valid"), [
    ((1, 1, 1, True)), ((0, 0, 0, True)), ((1, 0.5, 0.5, True)),   # det = 0: the edge
    ((-1, -1, 1, True)), ((1, 1, -1, False)), ((0.9, 0.9, -0.9, False)),
    ((-1, -1, -1, False)), ((0.5, 0.5, -0.6, False)),
])
def test_correlation_matrix_rule(r12: float, r13: float, r23: float, valid: bool) -> None:
    # det [[1, a, b], [a, 1, c], [b, c, 1]] = 1 + 2abc - a² - b² - c², worked by hand:
    # (0.5, 0.5, -0.6): 1 - 0.3 - 0.25 - 0.25 - 0.36 = -0.16 < 0
    assert (correlation_problem(r12, r13, r23) is None) is valid


@pytest.mark.parametrize(("r31", "r32"), [(1, -1), (-1, -1), (0.3, -0.7), (1, 1)])
def test_rate_coherence_pair_is_always_a_correlation(r31: float, r32: float) -> None:
    # with rho12 = rho31·rho32 the determinant is (1 - rho31²)(1 - rho32²) >= 0
    assert correlation_problem(r31 * r32, r31, r32) is None


def test_rate_coherence_third_value_is_checked() -> None:
    """With a third value ρ12 (docs/model.md §12), [ρ31, ρ32, ρ12] = [1, 1, −1] is no
    correlation; where the format has two values only, the third is refused by count."""
    from pydantic import ValidationError

    from gyrovib.models import Random

    with pytest.raises(ValidationError) as info:
        Random(rms=(1, 1, 1), coherence=(1, 1, -1))  # type: ignore[arg-type]
    kinds = {e["type"] for e in info.value.errors()}
    assert kinds in ({"too_long"}, {"rule"}), kinds
    if kinds == {"rule"}:
        assert "not a valid correlation matrix" in str(info.value)
    assert Random(rms=(1, 1, 1), coherence=(1, -1)).coherence == (1, -1)  # ρ12 = −1: valid


# ---------------------------------------------------------------- differential

#: Hostile but well-formed files: values at, just inside and just past every limit.
HOSTILE = [
    ("rate-tone-at-cap", "[0.1, 0.1, 0.5]", "[1.0e12, 1.0e12, 1.0e12]"),
    ("rate-tone-past-cap", "[0.1, 0.1, 0.5]", "[1.0e12, 1.0e12, 1.0000001e12]"),
    ("rate-rms-at-cap", "rms: [0.1, 0.1, 0.2]", "rms: [1.0e12, 1.0e12, 1.0e12]"),
    ("carrier-at-cap", "rate: [0, 0, 10]", "rate: [-1.0e12, 1.0e12, 1.0e12]"),
    ("acc-tone-at-cap", "[0.5, 0.5, 2.0]", "[1.0e12, 1.0e12, 1.0e12]"),
    ("acc-rms-at-cap", PSD_BLOCK, "rms: [1.0e12, 1.0e12, 1.0e12]"),
    ("acc-psd-at-cap", PSD_BLOCK, "psd:\n          x1: [[1, 1.0e24], [1.99, 1.0e24]]"),
    ("acc-psd-past-variance", PSD_BLOCK, "psd:\n          x1: [[1, 1.0e24], [2.01, 1.0e24]]"),
    ("acc-psd-wide-band", PSD_BLOCK,
     "psd:\n          x1: [[1.0e-300, 1.0e-10], [1.0e300, 1.0e-10]]"),
    ("vre-at-cap", "vre: 4.0e-4", "vre: 1.0e12"),
    ("g2-at-cap", "vre: 4.0e-4", "g2_sensitivity: {G11: -1.0e12, G23: 1.0e12}"),
    ("mount-at-cap", "    random: {rms: [0.1, 0.1, 0.2]}\n",
     "    random: {rms: [1.0e12, 0.1, 0.2]}\n    mount: [[10, 1.0e4], [20, 1.0e4]]\n"),
    ("coherence-edge", "coherence: [0, 0, 0]", "coherence: [1, 1, 1]"),
    ("coherence-edge-2", "coherence: [0, 0, 0]", "coherence: [1, -1, -1]"),
    ("coherence-just-past", "coherence: [0, 0, 0]", "coherence: [1, 1, 0.999]"),
    ("order-64", "rate: [0, 0, 10]", ORDERS.replace("1000", "64")),
    ("order-65", "rate: [0, 0, 10]", ORDERS.replace("1000", "65")),
    ("spec-range-low", SPEC, "specs: {range: 0.001, nonlinearity: {value: 100, unit: '%FS'}}"),
    ("spec-range-high", SPEC, "specs: {range: 1.0e7, nonlinearity: {value: 1.0e7, unit: deg/s}}"),
    ("spec-range-under", SPEC, "specs: {range: 0.00099, nonlinearity: {value: 1, unit: '%FS'}}"),
    ("spec-vre-at-cap", SPEC,
     "specs: {range: 100, nonlinearity: {value: 1, unit: '%FS'}, vre: 1.0e12}"),
]


def _first_place(stderr: str) -> str:
    return ":".join(stderr.splitlines()[0].split(":")[:3])


@pytest.mark.parametrize(("name", "old", "new"), HOSTILE, ids=[h[0] for h in HOSTILE])
def test_validate_means_what_analyze_means(tmp_path: Path, name: str, old: str,
                                           new: str) -> None:
    assert old in BASE
    path = tmp_path / f"{name}.yaml"
    path.write_text(BASE.replace(old, new, 1))
    verdict = invoke("validate", str(path))
    assert verdict.exit_code in (0, 2), verdict.stderr
    for command in ("analyze", "bounds", "select"):
        args = COMMANDS[command]
        result = invoke(args[0], str(path), *args[1:], "--format", "json")
        if verdict.exit_code == 0:
            # computed, no overflow: exit 0 or 1 (requirement not met), finite JSON
            assert result.exit_code in (0, 1), (command, result.stderr)
            assert "Infinity" not in result.stdout and "NaN" not in result.stdout
            json.loads(result.stdout)
        else:
            assert result.exit_code == 2, (command, result.stderr)
            assert _first_place(result.stderr) == _first_place(verdict.stderr), command


@pytest.mark.parametrize(("table", "expected"), [
    # S = 0.04 flat over 20..2000 Hz: 0.04 × 1980
    ([(20, 0.04), (2000, 0.04)], 79.2),
    # S = f²/100 over 10..100 Hz: (100³ − 10³)/300
    ([(10, 1.0), (100, 100.0)], 3330.0),
    # S = 100/f² over 10..100 Hz: 100·(1/10 − 1/100)
    ([(10, 1.0), (100, 0.01)], 9.0),
    # S = 10/f over 10..100 Hz (B = −1): 10·ln 10
    ([(10, 1.0), (100, 0.1)], 10 * math.log(10)),
    # a zero end: bounded by the larger level × the width
    ([(10, 0.0), (20, 2.0)], 20.0),
    # 1e-10 over 1e-300..1e300 Hz: 1e290, no overflow on the way
    ([(1e-300, 1e-10), (1e300, 1e-10)], 1e290),
])
def test_psd_variance_closed_forms(table: list[tuple[float, float]], expected: float) -> None:
    assert _types.psd_variance(table) == pytest.approx(expected, rel=1e-12)


def test_psd_variance_overflow_is_inf() -> None:
    assert _types.psd_variance([(1, 1e24), (1e300, 1e24)]) == math.inf


def test_g2_units_are_every_rate_unit_per_every_acceleration_squared() -> None:
    from typing import get_args

    from gyrovib.models.sensor import G2_PER, G2Unit, RateUnit

    assert set(get_args(G2Unit)) == {f"{r}/{a}" for r in get_args(RateUnit) for a in G2_PER}
