"""A first run that answers: ``gyrovib analyze`` on the bundled catalogues prints one
compact matrix and what to run next (README, "Quick start"; it once
printed 304 lines at 160 columns and 45 footnotes)."""

from __future__ import annotations

import numpy as np

import gyrovib
from gyrovib.formatting import fmt
from gyrovib.render import analysis as render
from tests.conftest import invoke


def first_run(*args: str, columns: int = 160) -> str:
    done = invoke("analyze", *args, env={"COLUMNS": str(columns), "NO_COLOR": "1"})
    assert done.exit_code == 0, done.stderr
    return done.stdout


def test_the_bundled_analysis_fits_a_screen_and_says_what_next() -> None:
    out = first_run()
    lines = out.splitlines()
    assert len(lines) <= 80
    assert lines[-1].startswith("Next: `gyrovib select --budget B`")
    # each distinct warning once, with the cells it applies to
    result = gyrovib.analyze()
    messages = {w for ws in result.warnings.values() for w in ws}
    flat = " ".join(out.split())
    for message in messages:
        assert flat.count(" ".join(message.split())) == 1


def test_a_matrix_cell_is_the_error_and_its_dominant_term() -> None:
    result = gyrovib.analyze()
    out = first_run()
    # generic-rate-mems under uav-blade-pass-tone: Δ_V(RMS), and A1 dominates (its
    # asymmetry 2e-2 against k2 …; the largest |term| of eq. (13))
    i, j = result.sensors.index("generic-rate-mems"), result.profiles.index(
        "uav-blade-pass-tone")
    terms = [*result.error.additive_terms[i, j], *result.error.extra_terms[i, j]]
    q = result.error.multiplicative_coefficients[i, j]
    omega = result.rates[j, 2]
    everything = [*terms, *(q[k] * omega ** (k + 1) for k in range(3))]
    assert int(np.argmax(np.abs(everything))) == 0  # A1
    assert render.dominant_term(result, i, j) == "A1"
    cell = f"{fmt(float(result.error.rms[i, j]), 3)} A1"
    row = next(line for line in out.splitlines() if line.startswith("│ uav-blade-pass-tone"))
    assert cell in row
    # a datasheet part without a VRE under a linear profile: unknown ('?'), never 0 nor
    # the error of its other figures
    vre = next(line for line in out.splitlines() if line.startswith("│ adis16460-vre-test"))
    assert "? ⚠" in vre and "≥" not in vre


def test_detail_and_one_or_two_profiles_give_the_per_term_tables() -> None:
    assert "Δ0 A1" not in first_run()
    assert "Δ0 A1" in first_run("--detail")
    two = first_run("--profile", "engine-harmonics", "--profile", "uav-blade-pass-tone")
    assert two.count("Δ0 A1") == 2 and "Next:" not in two
    assert "Δ0 A1" not in first_run("--profile", "engine-harmonics", "--matrix")


def test_errors_in_the_output_unit_rates_in_the_catalogue_unit() -> None:
    # --unit deg/h: the errors in deg/h, Ω_K3 of the profile still in the file's deg/s
    # (uav-blade-pass-tone: Ω_K3 = 0.5 deg/s, not 1800 deg/h)
    out = first_run("--profile", "uav-blade-pass-tone", "--unit", "deg/h")
    assert "uav-blade-pass-tone  (Ω_K3 = 0.5 deg/s, method exact)" in out
    assert "Errors in deg/h." in " ".join(out.split())
    doc = invoke("analyze", "--profile", "uav-blade-pass-tone", "--unit", "deg/h",
                 "--format", "json").stdout
    assert '"rate": [0.0, 0.0, 1800.0]' in doc  # JSON: everything in the output unit


def test_noise_below_1e_12_of_its_row_prints_as_zero() -> None:
    assert render.row_cells([-3.405e-181, 1.0, 2.5e-13, 1e-12]) == ["0", "1", "0", "1e-12"]
    assert render.row_cells([0.0, 0.0]) == ["0", "0"]
    # NaN is an unknown error (an axis a fitted profile's recording lacks): "?", never "nan"
    assert render.row_cells([float("nan"), 2.0]) == ["?", "2"]
