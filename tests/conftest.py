"""Shared fixtures: a small valid catalogue, a catalogue writer and the one CLI runner."""

from __future__ import annotations

import os
import signal
import textwrap
from collections.abc import Mapping
from pathlib import Path

import pytest
from click.testing import CliRunner, Result
from hypothesis import settings

# Hypothesis profiles. "ci", loaded by default, makes every property test deterministic:
# derandomize draws the same examples on every run and machine (so a red CI is a real
# regression, never an unlucky draw), deadline=None because timing on a shared 2-core
# runner under pytest-xdist is not a property, and print_blob prints the reproduction
# blob of a failure. A test's own @settings(max_examples=…) still chooses its count.
# GYROVIB_HYPOTHESIS_PROFILE=explore draws fresh random examples (and keeps failures in
# the local example database) for a deeper search before a release; a failure found
# that way is pinned in the test with @example.
settings.register_profile("ci", derandomize=True, deadline=None, max_examples=50,
                          print_blob=True, database=None)
settings.register_profile("explore", derandomize=False, deadline=None, max_examples=500,
                          print_blob=True)
settings.load_profile(os.environ.get("GYROVIB_HYPOTHESIS_PROFILE", "ci"))

# The suite's subprocesses answer SIGINT, SIGTERM and SIGHUP as a program started from a
# terminal does, whatever the shell that started pytest set to be ignored: a background
# job (`cmd &` in a script) ignores SIGINT and `nohup` ignores SIGHUP, children inherit
# an ignored signal, and gyrovib rightly keeps a signal its parent ignores ignored, so a
# test that interrupts gyrovib with it would wait for a run that never hears it. The
# test of that rule sets the ignore itself in the child.
for _signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
    if signal.getsignal(_signum) is signal.SIG_IGN:
        signal.signal(_signum, signal.default_int_handler if _signum == signal.SIGINT
                      else signal.SIG_DFL)

VALID = """\
gyrovib: 1
units:
  rate: deg/s
sensors:
  - id: fog-a
    name: FOG A
    range: 490
    coefficients:
      k2: 2.0e-7
      A1: 1.0e-4
      m31: 1.0e-6
    response:
      - [10, 1.0]
      - [500, 0.7]
  - id: mems-a
    output_coefficients:
      unit: mV
      K1: 25.0
      A1: 2.0e-3
      K2: 1.0e-4
profiles:
  - id: cruise
    rate: [0, 0, 30]
    harmonic:
      - frequency: 120
        amplitude: [0.5, 0.5, 0.8]
    random:
      psd:
        x3: [[20, 1.0e-4], [2000, 1.0e-4]]
      coherence: [1.0, 1.0]
    mount:
      - [20, 1.0]
      - [200, 0.3]
"""


# One tone a3 = 2 deg/s (a1 = 1, a2 = ½) at 100 Hz, Ω̄ = 0.5 deg/s, and Gaussian
# σ = (0.5, 0.5, 1) deg/s at Ω̄ = 2 deg/s: the two angular profiles shared by the
# selection tests (test_select_cli.py, test_specs.py).
TONE_AND_NOISE = """
profiles:
  - id: tone
    rate: [0, 0, 0.5]
    harmonic:
      - frequency: 100
        amplitude: [1.0, 0.5, 2.0]
  - id: noise
    rate: [0, 0, 2.0]
    random:
      rms: [0.5, 0.5, 1.0]
"""

# The linear profile 'lin' (one list item, indented to sit under ``profiles:``), shared
# by test_linear_api.py and test_specs_linear.py. Tones A = (1, 2, 3) g at 100 Hz with
# phases (0, 90, 0)°, random σ = (1, 2, 0.5) g, ρ = (0.5, −0.2, 0): Σ⟨a_j²⟩ = 1.5 + 6 +
# 4.75 = 12.25 g² (worked in test_linear_api.py, docs/model.md section 8).
#: Three sensors of different forms (coefficients with a range, cross-axis only,
#: output coefficients with a response) under a tone and a random profile: the
#: renderers' tests check every cell of their output against it.
MIXED_FORMS = """
gyrovib: 1
units: {rate: deg/h}
sensors:
  - id: small
    range: 10
    coefficients: {A1: 1e-3, k2: 1e-4, k3: 1e-6, k5: -1e-12}
  - id: odd.id_2
    coefficients: {k2: -2e-4, m31: 1e-5}
  - id: big
    range: 1e6
    output_coefficients: {K1: 3, K2: 1e-3, M32: 2e-5}
    response: [[10, 1], [100, 0.5]]
profiles:
  - id: tone
    rate: [0, 0, 5]
    harmonic: [{frequency: 100, amplitude: [0, 0, 20000]}]
  - id: random
    random: {rms: [0, 0, 2]}
"""


LINEAR_PROFILE = """\
  - id: lin
    rate: [0, 0, 10]
    random: {rms: [0.5, 0.5, 1.0]}
    acceleration:
      harmonic:
        - {frequency: 100, amplitude: [1.0, 2.0, 3.0], phase: [0, 90, 0]}
      random:
        rms: [1.0, 2.0, 0.5]
        coherence: [0.5, -0.2, 0.0]
"""


def invoke(*args: object, input: str | bytes | None = None,
           env: Mapping[str, str | None] | None = None, crash_ok: bool = False) -> Result:
    """Run the gyrovib CLI in-process with ``args``; click's Result (stdout, stderr apart).

    Unless ``crash_ok``, an exception escaping the command (anything but the
    exit) or a traceback on either stream fails the test: every outcome a user
    can cause is an exit status and a message.
    """
    from gyrovib.cli.main import cli

    result = CliRunner().invoke(cli, [str(a) for a in args], input=input, env=env,
                                catch_exceptions=True)
    if not crash_ok:
        assert result.exception is None or isinstance(result.exception, SystemExit), (
            f"unexpected exception {result.exception!r}\n{result.stderr}")
        assert "Traceback" not in result.stdout and "Traceback" not in result.stderr
    return result


#: The terminal settings gyrovib reads from the environment. pytest-xdist's workers run
#: with COLUMNS=80 and a developer's shell may export any of them, so every test starts
#: without them (a test that needs one sets it) and prints the same under any runner.
TERMINAL_ENV = ("COLUMNS", "LINES", "NO_COLOR", "FORCE_COLOR")


@pytest.fixture(autouse=True)
def _terminal_neutral_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in TERMINAL_ENV:
        monkeypatch.delenv(name, raising=False)


@pytest.fixture
def valid_text() -> str:
    return VALID


@pytest.fixture
def valid_file(tmp_path: Path) -> Path:
    path = tmp_path / "good.yaml"
    path.write_text(VALID, encoding="utf-8")
    return path


@pytest.fixture
def write(tmp_path: Path):
    """Write a dedented catalogue into tmp_path and return its path."""

    def _write(text: str, name: str = "catalog.yaml") -> Path:
        path = tmp_path / name
        path.write_text(textwrap.dedent(text), encoding="utf-8")
        return path

    return _write


@pytest.fixture
def run():
    """:func:`invoke`, as a fixture."""
    return invoke
