"""`gyrovib allan`: JSON keys of INTERFACE.md (fourth round), the noise block it writes,
the reader options it shares with `profile`, and its refusals."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from gyrovib.core.allan import oadev
from gyrovib.models import Sensor
from tests.conftest import invoke

FS = 50.0
# white rate noise of N = 0.3 deg/√h (0.005 deg/√s): σ_y = N·√fs per sample
N_DEG_SQRT_S = 0.3 / 60.0


def _record(tmp_path: Path) -> tuple[Path, np.ndarray]:
    g = np.random.default_rng(7)
    rate = g.standard_normal((20_000, 2)) * N_DEG_SQRT_S * math.sqrt(FS)
    t = np.arange(rate.shape[0]) / FS
    path = tmp_path / "static.csv"
    np.savetxt(path, np.column_stack([t, rate]), delimiter=",", header="t,gx,gz",
               comments="", fmt="%.10g")
    return path, rate


def test_json_per_axis_with_the_interface_keys(tmp_path: Path) -> None:
    path, rate = _record(tmp_path)
    out = invoke("allan", path, "--rate-columns", "gx,-,gz", "--unit", "deg/s",
                 "--format", "json")
    assert out.exit_code == 0, out.stderr
    doc = json.loads(out.stdout)
    assert [a["axis"] for a in doc["axes"]] == ["X", "Z"]          # Y not recorded
    z = doc["axes"][1]
    assert {"axis", "tau", "adev", "arw", "bias_instability", "rrw"} <= set(z)
    for key in ("arw", "bias_instability", "rrw"):
        assert set(z[key]) >= {"value", "unit", "uncertainty"}
    # the curve is the kernel's on the column read from the CSV (written to 10 digits)
    expected = oadev(np.round(rate[:, 1], 12), 1 / FS)[1]
    assert np.allclose(z["adev"], expected, rtol=1e-6)
    # the simulated N, within 2 standard uncertainties
    assert abs(z["arw"]["value"] - 0.3) <= 2 * z["arw"]["uncertainty"]
    assert z["arw"]["unit"] == "deg/sqrt(h)"


def test_output_is_a_noise_block_a_sensor_accepts(tmp_path: Path) -> None:
    path, _ = _record(tmp_path)
    block = tmp_path / "noise.yaml"
    out = invoke("allan", path, "--rate-columns", "gx,-,gz", "-o", block)
    assert out.exit_code == 0, out.stderr
    documents = list(yaml.safe_load_all(block.read_text(encoding="utf-8")))
    assert len(documents) == 2                                      # one per recorded axis
    for doc in documents:
        sensor = Sensor(id="s", coefficients={}, noise=doc["noise"])
        assert sensor.noise is not None and sensor.noise.arw is not None
        assert sensor.noise.arw.unit == "deg/sqrt(h)"


def test_plot_writes_a_png(tmp_path: Path) -> None:
    path, _ = _record(tmp_path)
    png = tmp_path / "a.png"
    out = invoke("allan", path, "--rate-columns", "gx,-,gz", "--plot", png, "--format", "json")
    assert out.exit_code == 0, out.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_short_record_is_refused_with_the_file_named(tmp_path: Path) -> None:
    path = tmp_path / "short.csv"
    path.write_text("t,g\n" + "".join(f"{i / 10},{i % 3}\n" for i in range(10)),
                    encoding="utf-8")
    out = invoke("allan", path, "--rate-columns", "-,-,g")
    assert out.exit_code == 2
    assert "short.csv" in out.stderr and "needs 30" in out.stderr


def test_bias_instability_is_the_reported_minimum_over_0664(tmp_path: Path) -> None:
    path, _ = _record(tmp_path)
    for unit in ("deg/h", "rad/s"):
        doc = json.loads(invoke("allan", path, "--rate-columns", "gx,-,gz", "--unit", unit,
                                "--format", "json").stdout)
        for axis in doc["axes"]:
            b = axis["bias_instability"]["value"]                     # deg/h
            lowest = min(axis["adev"]) * (1.0 if unit == "deg/h" else 3600 * 180 / math.pi)
            assert b == pytest.approx(lowest / 0.664, rel=1e-12)
