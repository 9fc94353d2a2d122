"""The eq. (1) output form equals the eq. (2) rate form after dividing by K1."""

from __future__ import annotations

import json

import pytest


def test_output_coefficients_equal_rate_coefficients(run, write):
    # K1 = 25 mV/(deg/s): Kn = 25·kn, M3i = 25·m3i; A1 is dimensionless and unchanged
    path = write("""
        gyrovib: 1
        sensors:
          - id: rate-form
            coefficients: {k0: 0.1, A1: 2e-3, k2: 1e-4, k3: -2e-6, k4: 1e-7, k5: -3e-9,
                           m1: 1e-3, m31: 1e-4, m32: -1e-4}
          - id: output-form
            output_coefficients: {unit: mV, K1: 25, K0: 2.5, A1: 2e-3, K2: 2.5e-3, K3: -5e-5,
                                  K4: 2.5e-6, K5: -7.5e-8, M1: 0.025, M31: 2.5e-3, M32: -2.5e-3}
        profiles:
          - id: p
            rate: [0, 0, 1]
            harmonic: [{frequency: 50, amplitude: [1, 1, 2]}]
            random: {rms: [0.5, 0.5, 1]}
    """)
    result = run("analyze", path, "--format", "json")
    assert result.exit_code == 0, result.output
    a, b = json.loads(result.output)["results"]
    for key in ("additive_terms", "multiplicative_coefficients"):
        for name in a[key]:
            assert b[key][name] == pytest.approx(a[key][name], rel=1e-12, abs=1e-300)
    assert b["total"] == pytest.approx(a["total"], rel=1e-12)
    assert a["total"] != 0.0
