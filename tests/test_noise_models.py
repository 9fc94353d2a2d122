"""The noise: block (models/noise.py): its written forms, its units and their conversion
to the default units (api/noise/figures.py), located errors, the schema."""

import json
from pathlib import Path

import pytest
from pydantic import ValidationError

from gyrovib.api.noise import noise_values
from gyrovib.models import Sensor
from tests.conftest import invoke


def _noise(**figures: object) -> Sensor:
    return Sensor(id="s", coefficients={}, noise=figures)


def test_every_written_form_in_the_default_units() -> None:
    s = _noise(arw="0.01 °/s/√Hz typ", bias_instability={"value": 1e-3, "unit": "deg/s"},
               rrw="2 deg/h/sqrt(h) max", bias_repeatability=20)
    assert s.noise is not None and s.noise.arw is not None and s.noise.rrw is not None
    assert s.noise.arw.qualifier == "typ" and s.noise.rrw.qualifier == "max"
    values = noise_values(s.noise)
    # 1 deg/s/√Hz = 1 deg/√s = 60 deg/√h; 1 deg/s = 3600 deg/h
    assert values["arw"] == pytest.approx(0.6, rel=1e-15)
    assert values["bias_instability"] == pytest.approx(3.6, rel=1e-15)
    assert values["rrw"] == 2.0 and values["bias_repeatability"] == 20.0


def test_per_hertz_forms_of_the_arw() -> None:
    # 1 deg/h/√Hz = (1/3600) deg/s/√Hz = 60/3600 deg/√h
    v = noise_values(_noise(arw="6 deg/h/√Hz").noise)["arw"]
    assert v == pytest.approx(0.1, rel=1e-15)


def test_an_omitted_figure_is_unknown_not_zero() -> None:
    values = noise_values(_noise(arw=0.12).noise)
    assert values == {"arw": 0.12, "bias_instability": None, "rrw": None,
                      "bias_repeatability": None}
    assert noise_values(None) == dict.fromkeys(values)


@pytest.mark.parametrize("figures", [{"arw": "0.1 deg/h"}, {"rrw": {"value": 1, "unit": "deg/h"}},
                                     {"arw": -0.1}, {"arw": True}, {}])
def test_refused(figures: dict[str, object]) -> None:
    with pytest.raises(ValidationError):
        _noise(**figures)


def test_a_wrong_unit_is_located_in_the_file(tmp_path: Path) -> None:
    path = tmp_path / "c.yaml"
    path.write_text("gyrovib: 1\nsensors:\n  - id: a\n    coefficients: {k2: 1.0e-4}\n"
                    "    noise:\n      bias_instability: 8 °/h typ\n      arw: 0.1 deg/h\n",
                    encoding="utf-8")
    out = invoke("validate", path)
    assert out.exit_code == 2
    assert out.stderr.startswith(f"{path}:7:12: ") and "angle random walk" in out.stderr


def test_in_the_schema() -> None:
    schema = json.loads(invoke("schema").stdout)
    noise = schema["definitions"]["Noise"]
    assert set(noise["properties"]) == {"arw", "bias_instability", "rrw", "bias_repeatability"}
