"""The catalogue's ``uncertainty`` and ``lot`` blocks (docs/rate-table.md;
docs/model.md section 14): what the models accept, the located exit-2 errors, the JSON
Schema agreeing with validate, and `gyrovib fit -o` writing what validate accepts."""

from __future__ import annotations

from pathlib import Path

import jsonschema
import numpy as np
import pytest

from gyrovib.catalog.loader import _parse
from gyrovib.models import Catalogue, Sensor
from gyrovib.models.schema import catalog_schema
from tests.conftest import invoke

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "docs" / "examples" / "rate-table-gx100.csv"
EXAMPLE_CATALOG = ROOT / "docs" / "examples" / "rate-table-gx100.gyrovib.yaml"

GOOD = """\
gyrovib: 1
sensors:
  - id: unit-0042
    coefficients: {k0: 0.01, A1: 1.2e-3, k2: 3.1e-5, k3: -2.0e-7}
    uncertainty:
      sigma: {k0: 0.001, A1: 1.0e-4, k2: 2.0e-6, k3: 1.5e-8}
      correlation: {A1 k2: 0.3}
  - id: lot-xyz
    lot:
      units: 12
      mean: {A1: 1.1e-3, k2: 2.9e-5, k3: -1.8e-7}
      sigma: {A1: 3.0e-4, k2: 8.0e-6, k3: 5.0e-8}
      correlation: {A1 k2: 0.2}
"""

#: (what is broken, replacement of GOOD's text, where the error is placed, words said)
BAD = [
    ("negative sigma", ("A1: 1.0e-4, k2: 2.0e-6", "A1: -1.0e-4, k2: 2.0e-6"), "6:30",
     "must not be negative"),
    ("unknown coefficient", ("k2: 2.0e-6, k3", "k2: 2.0e-6, kk3"), "6:50", "unknown key 'kk3'"),
    ("k1 has no uncertainty", ("{k0: 0.001,", "{k1: 0.001,"), "6:15", "unknown key 'k1'"),
    ("correlation above 1", ("{A1 k2: 0.3}", "{A1 k2: 1.3}"), "7:28",
     "must not be greater than 1"),
    ("pair of one name", ("{A1 k2: 0.3}", "{A1 A1: 0.3}"), "7:28", "with itself"),
    ("pair without sigma", ("{A1 k2: 0.3}", "{A1 k4: 0.3}"), "7:28", "k4 has no sigma"),
    ("pair of three", ("{A1 k2: 0.3}", "{A1 k2 k3: 0.3}"), "7:31", "two coefficients"),
    ("pair not a coefficient", ("{A1 k2: 0.3}", "{A1 G11: 0.3}"), "7:29", "'G11' is not"),
    ("pair twice", ("{A1 k2: 0.3}", "{A1 k2: 0.3, k2 A1: 0.3}"), "7:40", "given twice"),
    ("not positive semi-definite", ("{A1 k2: 0.3}", "{A1 k2: 0.9, A1 k3: 0.9, k2 k3: -0.9}"),
     "7:20", "not positive semi-definite"),
    ("uncertainty without coefficients", ("    lot:\n", "    uncertainty: {sigma: {A1: 1}}\n"
                                           "    lot:\n"), "9:18", "beside 'coefficients'"),
    ("lot of one unit", ("units: 12", "units: 1"), "10:14", "must not be less than 2"),
    ("lot units not an integer", ("units: 12", "units: 12.5"), "10:14", "integer"),
    ("lot and coefficients", ("    lot:\n", "    coefficients: {}\n    lot:\n"), "8:5",
     "give the conversion function once"),
    ("lot without mean", ("      mean: {A1: 1.1e-3, k2: 2.9e-5, k3: -1.8e-7}\n", ""), "10:7",
     "missing required key 'mean'"),
    ("lot correlation inconsistent", ("{A1 k2: 0.2}", "{A1 k2: 0.9, A1 k3: 0.9, k2 k3: -0.9}"),
     "13:20", "not positive semi-definite"),
]


def test_the_interface_example_validates() -> None:
    catalogue = Catalogue.model_validate(_parse(GOOD, "<test>"))
    unit, lot = catalogue.sensors
    assert unit.uncertainty is not None and lot.lot is not None
    assert unit.uncertainty.sigma.named() == {"k0": 0.001, "A1": 1.0e-4, "k2": 2.0e-6,
                                              "k3": 1.5e-8}
    assert dict(lot.lot.correlation) == {"A1 k2": 0.2}
    # a lot is analysed at its mean: its conversion function is the mean's
    assert lot.rate_coefficients.k2 == 2.9e-5 and lot.rate_coefficients.k1 == 1.0


def test_a_sensor_built_in_python() -> None:
    s = Sensor(id="s", coefficients={"A1": 1e-3}, uncertainty={"sigma": {"A1": 1e-4}})
    assert s.uncertainty is not None and dict(s.uncertainty.correlation) == {}
    with pytest.raises(ValueError, match="positive semi-definite"):
        Sensor(id="s", lot={"units": 3, "mean": {}, "sigma": {"A1": 1, "k2": 1, "k3": 1},
                            "correlation": {"A1 k2": -1, "A1 k3": -1, "k2 k3": -1}})


@pytest.mark.parametrize(("what", "change", "place", "words"), BAD, ids=[b[0] for b in BAD])
def test_bad_blocks_are_located_exit_2_errors(tmp_path: Path, what: str,
                                              change: tuple[str, str], place: str,
                                              words: str) -> None:
    assert change[0] in GOOD, what
    path = tmp_path / "c.yaml"
    path.write_text(GOOD.replace(change[0], change[1], 1), encoding="utf-8")
    result = invoke("validate", path)
    assert result.exit_code == 2, result.stdout
    lines = [line for line in result.stderr.splitlines() if line.startswith(str(path))]
    assert any(line.startswith(f"{path}:{place}: ") and words in line for line in lines), (
        result.stderr)


@pytest.fixture(scope="module")
def validator() -> jsonschema.Draft7Validator:
    return jsonschema.Draft7Validator(catalog_schema())


def test_the_schema_agrees_with_validate(validator: jsonschema.Draft7Validator) -> None:
    """Everything validate accepts the schema accepts; what the schema can express (bounds,
    keys, the one-of, uncertainty only beside coefficients, the pair texts) it refuses
    too. The pair rules across keys and positive semi-definiteness are validate's."""
    assert validator.is_valid(_parse(GOOD, "<test>"))
    assert validator.is_valid(_parse(EXAMPLE_CATALOG.read_text(encoding="utf-8"), "<test>"))
    schema_can = {"negative sigma", "unknown coefficient", "k1 has no uncertainty",
                  "correlation above 1", "pair of three", "uncertainty without coefficients",
                  "lot of one unit", "lot units not an integer", "lot and coefficients",
                  "lot without mean"}
    for what, (old, new), _, _ in BAD:
        data = _parse(GOOD.replace(old, new, 1), "<test>")
        assert validator.is_valid(data) != (what in schema_can), what


def test_fit_output_validates(tmp_path: Path) -> None:
    """`gyrovib fit -o` on the bundled table writes a catalogue validate accepts, and it is
    the bundled one."""
    out = tmp_path / "fitted.gyrovib.yaml"
    result = invoke("fit", EXAMPLE, "--output-unit", "mV", "-o", out)
    assert result.exit_code == 0, result.stderr
    checked = invoke("validate", out)
    assert checked.exit_code == 0, checked.stderr
    assert "9 sensor(s)" in checked.stderr
    bundled = invoke("validate", EXAMPLE_CATALOG)
    assert bundled.exit_code == 0, bundled.stderr


def test_fitted_correlations_are_what_the_models_read() -> None:
    """The lot of the bundled catalogue: its correlation matrix as the models read it is
    the one core.lot builds from the same pairs (so both judge one matrix)."""
    from gyrovib.core.lot import correlation_from_pairs

    catalogue = Catalogue.model_validate(_parse(EXAMPLE_CATALOG.read_text(encoding="utf-8"),
                                                "<test>"))
    lot = catalogue.sensors[-1].lot
    assert lot is not None and lot.units == 8
    names = list(lot.sigma.named())
    r = correlation_from_pairs(names, dict(lot.correlation))
    assert np.linalg.eigvalsh(r)[0] > 0
