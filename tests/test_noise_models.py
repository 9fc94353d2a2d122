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
    assert set(noise["properties"]) == {"arw", "bias_instability", "rrw", "bias_repeatability",
                                        "x", "y", "z"}
    # a bound is one of the forms the schema accepts, as text and as a mapping
    text = json.dumps(noise["properties"]["rrw"], ensure_ascii=False)
    assert "≤|<=" in text and '"bound"' in text


def test_a_bound_in_each_written_form_is_its_upper_value_and_flagged() -> None:
    from gyrovib.api.noise.figures import noise_bounds

    for rrw in ("≤ 0.8 deg/h/sqrt(h)", "<= 0.8 deg/h/sqrt(h)", "≤0.8 deg/h/√h",
                {"bound": 0.8, "unit": "deg/h/sqrt(h)"}):
        s = _noise(arw=0.1, rrw=rrw)
        assert s.noise is not None and s.noise.rrw is not None
        assert s.noise.rrw.is_bound and s.noise.rrw.value is None
        assert noise_values(s.noise)["rrw"] == 0.8           # the budget uses the bound
        assert noise_bounds(s.noise) == ("rrw",)
    # a bound in another unit converts like a value: 1 deg/s/√s = 216 000 deg/h/√h
    s = _noise(rrw={"bound": 1e-6, "unit": "deg/s/sqrt(s)"})
    assert noise_values(s.noise)["rrw"] == pytest.approx(0.216, rel=1e-15)


def test_a_mapping_gives_a_value_or_a_bound_not_both() -> None:
    with pytest.raises(ValidationError, match="value or a bound"):
        _noise(rrw={"value": 0.5, "bound": 0.8, "unit": "deg/h/sqrt(h)"})
    with pytest.raises(ValidationError, match="value or a bound"):
        _noise(rrw={"unit": "deg/h/sqrt(h)"})


def test_per_axis_figures_override_the_block_and_any_axis_takes_the_largest() -> None:
    s = _noise(arw=0.1, bias_repeatability=5,
               x={"arw": 0.2}, z={"arw": "0.3 deg/sqrt(h)", "rrw": "≤ 2 deg/h/sqrt(h)"})
    assert s.noise is not None
    assert noise_values(s.noise, "X")["arw"] == 0.2
    assert noise_values(s.noise, "Y")["arw"] == 0.1              # no y block: the block's
    z = noise_values(s.noise, "Z")
    assert z["arw"] == 0.3 and z["rrw"] == 2.0 and z["bias_repeatability"] == 5.0
    # a single-axis sensor (axis None): the block's own figure, else the axes' largest
    anyaxis = noise_values(s.noise, None)
    assert anyaxis["arw"] == 0.1 and anyaxis["rrw"] == 2.0


def test_a_flat_block_reads_as_before_for_every_axis() -> None:
    s = _noise(arw=0.12, rrw="0.5 deg/h/sqrt(h)")
    for axis in (None, "X", "Y", "Z"):
        assert noise_values(s.noise, axis) == noise_values(s.noise)
