"""Every command refuses what overflows floating point: exit 2, one located line per
profile at fault (FILE:LINE:COL of its ``id:``), nothing on standard output.

Each case is an input whose arithmetic leaves the float range (max ≈ 1.8e308,
smallest normal ≈ 2.2e-308, docs: numpy.finfo(float)). A vibration itself is
bounded by the catalogue models (amplitudes and rms ≤ 1e12, so its moments stay
finite: tests/test_limits.py); what overflows here is its product with a
coefficient the models cannot bound against every profile:
- k5 = 1e200 at Ω = 1: the multiplicative term q1·Ω = 5·k5·M4 ≥ 1.5e201 for
  σ = 1 (M4 = 3σ⁴), and the RMS squares it → inf; with an amplitude or σ of
  1e12 already the term overflows;
- Ω̄ = 1e308: the k3..k5 denominators |Ω̄|^n·M overflow → a bound of 0;
- r = 1e308: c_M = 1/√(1+r²) = 1e-308 (subnormal), so β and the k3..k5 bounds
  underflow.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from gyrovib import api
from gyrovib.catalog.loader import merge, parse_catalog
from gyrovib.errors import RangeError

# line 4 holds the profile's id (its value starts at column 9)
TEMPLATE = """\
gyrovib: 1
{allocation}
profiles:
  - id: p
    rate: [0, 0, 1]
{vibration}
sensors:
  - id: s
    coefficients: {{k2: 1.0e-4, A1: 1.0e-3, k3: 1.0e-6{extra}}}
"""
TONE = "    harmonic: [{frequency: 100, amplitude: [0, 0, %s]}]"
RANDOM = "    random: {rms: [0, 0, %s]}"


HUGE_K5 = ", k5: 1.0e+200"


def catalogue(write, vibration: str, allocation: str = "", extra: str = "") -> str:
    return str(write(TEMPLATE.format(vibration=vibration, allocation=allocation or "# -",
                                     extra=extra)))


def assert_refused_at_profile(result, path: str, *needles: str) -> None:
    assert result.exit_code == 2, result.stdout + result.stderr
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, lines  # one line, no numpy RuntimeWarning
    assert re.match(rf"^{re.escape(path)}:4:9: (sensor 's' under )?profile 'p': .*overflows "
                    r"floating point", lines[0]), lines[0]
    for needle in needles:
        assert needle in lines[0], lines[0]


COMMANDS = {
    "analyze": ["analyze"],
    "analyze-paper": ["analyze", "--method", "paper"],
    "bounds": ["bounds", "--budget", "0.01"],
    "bounds-paper": ["bounds", "--budget", "0.01", "--method", "paper"],
    "select": ["select", "--budget", "0.01"],
    "select-paper": ["select", "--budget", "0.01", "--method", "paper"],
    "sweep": ["sweep", "--rate-range", "0:1:3"],
}


#: The commands that evaluate the sensors' coefficients (bounds computes only the
#: profile's side, finite for every vibration the models accept).
EVALUATING = [c for c in COMMANDS if not c.startswith("bounds")]


@pytest.mark.parametrize("fmt", ["json", "csv"])
@pytest.mark.parametrize("command", EVALUATING, ids=EVALUATING)
@pytest.mark.parametrize("vibration", [TONE % "1e12", RANDOM % "1e12", RANDOM % "1"],
                         ids=["amplitude-1e12", "sigma-1e12", "sigma-1"])
def test_absurd_coefficient_is_refused_at_the_profile(run, write, vibration, command, fmt):
    path = catalogue(write, vibration, extra=HUGE_K5)
    result = run(*COMMANDS[command][:1], path, *COMMANDS[command][1:], "--format", fmt)
    assert_refused_at_profile(result, path)


@pytest.mark.parametrize("command", ["analyze", "bounds", "select"])
def test_absurd_rate_option_is_refused_at_the_profile(run, write, command):
    path = catalogue(write, TONE % "1")
    extra = [] if command == "analyze" else ["--budget", "0.01"]
    result = run(command, path, *extra, "--rate", "1e308", "--format", "json")
    # the message says the rate came from the option, not from the file
    assert_refused_at_profile(result, path, "rate given")


def test_bounds_name_the_coefficients_that_overflow(run, write):
    path = catalogue(write, TONE % "1")
    result = run("bounds", path, "--budget", "0.01", "--rate", "1e308")
    # Ω̄ enters the k3, k4 (multiplicative) and k5 denominators only
    assert_refused_at_profile(result, path, "coefficient bound (k3, k4, k5)")


def test_sane_inputs_are_not_refused(run, write):
    # the same catalogue with a 1 deg/s tone: every bound finite or +inf, exit 0
    path = catalogue(write, TONE % "1")
    result = run("bounds", path, "--budget", "0.01", "--format", "json")
    assert result.exit_code == 0, result.stderr
    bounds = json.loads(result.stdout)["profiles"][0]["bounds"]
    # eq. (23): |k2| ≤ α2·Δ*/M2, α2 = 0.4447496 (test_select_cli.py), M2 = a²/2 = 0.5
    assert bounds["k2"] == pytest.approx(0.4447496 * 0.01 / 0.5, rel=1e-6)
    assert all(b is None or b > 0 for b in bounds.values())


def test_absurd_allocation_option_is_refused_by_name(run, write):
    path = catalogue(write, TONE % "1")
    for command in ("bounds", "select"):
        result = run(command, path, "--budget", "0.01", "--allocation", "1e308,1,1,1,1,1,1,1,1")
        assert result.exit_code == 2 and result.stdout == ""
        assert result.stderr.startswith("gyrovib: error: the allocation given by --allocation "
                                        "makes a share of the budget underflow"), result.stderr


def test_absurd_allocation_section_is_refused_at_its_place(run, write):
    path = catalogue(write, TONE % "1", allocation="allocation: {r: 1.0e+308}")
    result = run("bounds", path, "--budget", "0.01")
    assert result.exit_code == 2 and result.stdout == ""
    # line 2, column 13: the value of the 'allocation:' key
    assert result.stderr.startswith(f"{path}:2:13: the allocation given by the 'allocation:' "
                                    "section"), result.stderr


def test_every_overflowing_profile_is_reported(write):
    # 'fine' has no carrier rate: the k5 terms (multiplicative, × Ω) vanish there
    text = TEMPLATE.format(vibration=TONE % "1e12", allocation="# -", extra=HUGE_K5) + (
        "  - id: q\n    coefficients: {}\n")  # a second sensor changes nothing
    text = text.replace("sensors:", "  - id: fine\n    random: {rms: [0, 0, 1]}\n"
                        "  - id: huge\n    rate: [0, 0, 1]\n    random: {rms: [0, 0, 1e12]}\n"
                        "sensors:")
    catalog = merge([parse_catalog(text, "cat.yaml")])
    with pytest.raises(RangeError) as info:
        api.analyze(catalog)
    # the first pair at its profile, the count of the others ('huge'; not 'fine')
    places = [(p.line, p.message.split(":")[0]) for p in info.value.problems]
    assert places == [(4, "sensor 's' under profile 'p'")]
    assert info.value.problems[0].message.endswith("(1 more sensor/profile pairs too)")


def test_library_refuses_without_warnings(write, recwarn):
    catalog = api.load([catalogue(write, RANDOM % "1", extra=HUGE_K5)])
    for call in (lambda: api.sweep(catalog, [0.0, 1.0]),
                 lambda: api.analyze(catalog, method="paper"),
                 lambda: api.select(catalog, budget=0.01, method="paper")):
        with pytest.raises(RangeError):
            call()
    assert not [w for w in recwarn if issubclass(w.category, RuntimeWarning)]
    assert np.geterr()["over"] == "warn"  # the guard does not leak out of the library
