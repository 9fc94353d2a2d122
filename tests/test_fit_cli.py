"""`gyrovib fit` end to end: the rate-table reader, every output, exit codes.

Expected numbers come from tables made here from stated eq. (1) coefficients
(noise-free: the fit must return them), and from the JSON of the same run
(the other formats must carry the same values).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import yaml

from tests.conftest import invoke
from tests.docpages import same_text

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "docs" / "examples" / "rate-table-gx100.csv"
EXAMPLE_CATALOG = ROOT / "docs" / "examples" / "rate-table-gx100.gyrovib.yaml"
LEVELS = (-300.0, -200.0, -100.0, -50.0, -20.0, 0.0, 20.0, 50.0, 100.0, 200.0, 300.0)
UNIT_KEYS = {"unit", "coefficients", "uncertainty", "t", "residual_rms", "nonlinearity", "points"}


def unit_rows(name: str, k0: float, k1: float, a1: float, k2: float, k3: float,
              noise: float = 0.0, seed: int = 0) -> list[str]:
    """Rows of a unit whose eq. (2) is k0 + ω + ½A1|ω| + k2ω² + k3ω³, output K1 times it."""
    rng = np.random.default_rng(seed)
    rows = []
    for w in LEVELS:
        for _ in range(2):
            u = k1 * (k0 + w + 0.5 * a1 * abs(w) + k2 * w**2 + k3 * w**3)
            rows.append(f"{name},{w:g},{u + rng.normal(0, noise) if noise else u!r}")
    return rows


@pytest.fixture
def table(tmp_path: Path) -> Path:
    path = tmp_path / "bench.csv"
    rows = (unit_rows("u1", 0.1, 25.0, 2e-3, 3e-6, -4e-9, 0.05, 1)
            + unit_rows("u2", -0.2, 24.9, 1e-3, 1e-6, -2e-9, 0.05, 2)
            + unit_rows("u3", 0.0, 25.1, 1.5e-3, 2e-6, -3e-9, 0.05, 3))
    path.write_text("# three units\nunit,rate,output\n" + "\n".join(rows) + "\n",
                    encoding="utf-8")
    return path


def test_noise_free_table_gives_its_coefficients(tmp_path: Path) -> None:
    path = tmp_path / "clean.csv"
    rows = unit_rows("a", 0.1, 25.0, 2e-3, 3e-6, -4e-9) + unit_rows("b", 0.0, 5.0, 1e-3,
                                                                     -1e-6, 2e-9)
    path.write_text("unit,rate,output\n" + "\n".join(rows) + "\n", encoding="utf-8")
    result = invoke("fit", path, "--order", "3", "--format", "json")
    assert result.exit_code == 0, result.stderr
    document = json.loads(result.stdout)
    a, b = document["units"]
    expected_a = {"k0": 0.1, "A1": 2e-3, "k2": 3e-6, "k3": -4e-9}
    for name, value in expected_a.items():
        assert a["coefficients"][name] == pytest.approx(value, rel=1e-9, abs=1e-15), name
    assert b["coefficients"]["k2"] == pytest.approx(-1e-6, rel=1e-9)


def test_json_keys(table: Path) -> None:
    result = invoke("fit", table, "--format", "json", "--output-unit", "mV")
    assert result.exit_code == 0, result.stderr
    document = json.loads(result.stdout)
    assert document["tool"] == "gyrovib" and document["unit"] == "deg/s"
    assert document["output_unit"] == "mV" and document["order"] == 5
    assert [u["unit"] for u in document["units"]] == ["u1", "u2", "u3"]
    for unit in document["units"]:
        assert set(unit) == UNIT_KEYS
        assert set(unit["uncertainty"]) == {"sigma", "correlation"}
        assert set(unit["nonlinearity"]) == {"least_squares_max", "endpoint_max", "unit",
                                             "range"}
        assert unit["nonlinearity"]["unit"] == "%FS" and unit["nonlinearity"]["range"] == 300
        assert list(unit["coefficients"]) == ["k0", "A1", "k2", "k3", "k4", "k5"]
        assert unit["points"] == 22
        assert "A1 k2" in unit["uncertainty"]["correlation"]
        for name, t in unit["t"].items():
            assert t == pytest.approx(unit["coefficients"][name]
                                      / unit["uncertainty"]["sigma"][name], rel=1e-12)
    # three units, six coefficients: n ≤ p, the lot keeps only σ, with a warning
    lot = document["lot"]
    assert set(lot) == {"units", "mean", "sigma", "correlation"}
    assert lot["units"] == 3 and lot["correlation"] == {}
    means = [np.mean([u["coefficients"][n] for u in document["units"]]) for n in lot["mean"]]
    np.testing.assert_allclose(list(lot["mean"].values()), means, rtol=1e-12)
    assert document["warnings"] and "3 units" in document["warnings"][0]
    assert "gyrovib: warning: lot 'lot-bench': a lot of 3 units" in result.stderr


def test_catalogue_output(table: Path, tmp_path: Path) -> None:
    out = tmp_path / "fitted.yaml"
    result = invoke("fit", table, "-o", out, "--format", "json")
    assert result.exit_code == 0, result.stderr
    document = json.loads(result.stdout)
    catalog = yaml.safe_load(out.read_text(encoding="utf-8"))
    assert catalog["gyrovib"] == 1 and catalog["units"] == {"rate": "deg/s"}
    sensors = catalog["sensors"]
    assert [s["id"] for s in sensors] == ["u1", "u2", "u3", "lot-bench"]
    for sensor, unit in zip(sensors, document["units"], strict=False):
        assert set(sensor) == {"id", "coefficients", "uncertainty"}
        for name, value in unit["coefficients"].items():
            sigma = unit["uncertainty"]["sigma"][name]
            # written to the decimal place of σ's third significant digit (catalog/writer.py's
            # quantum_of): within half that place of the full-precision JSON value
            place = 10.0 ** (np.floor(np.log10(sigma)) - 2)
            assert sensor["coefficients"][name] == pytest.approx(value, abs=place / 2 * 1.001)
            # σ to three significant digits, not the machine's twelve
            assert sensor["uncertainty"]["sigma"][name] == float(f"{sigma:.3g}")
        for pair, value in unit["uncertainty"]["correlation"].items():
            # nine decimal places (catalog/writer.py's CORRELATION_PLACES)
            assert sensor["uncertainty"]["correlation"][pair] == pytest.approx(value,
                                                                               abs=5.001e-10)
    lot = sensors[-1]["lot"]
    assert lot["units"] == 3 and lot["correlation"] == {}
    assert lot["sigma"]["A1"] == pytest.approx(document["lot"]["sigma"]["A1"], rel=5e-3)


def test_catalogue_to_standard_output(table: Path) -> None:
    result = invoke("fit", table, "-o", "-")
    assert result.exit_code == 0, result.stderr
    assert result.stdout.startswith("# Written by gyrovib")
    assert yaml.safe_load(result.stdout)["sensors"][0]["id"] == "u1"


def test_the_bundled_example_and_its_catalogue(monkeypatch: pytest.MonkeyPatch) -> None:
    """The made-up GX-100 table: eight units (n > p = 6, so the lot has correlations), and
    docs/examples/rate-table-gx100.gyrovib.yaml is what `fit -o -` writes of it."""
    result = invoke("fit", EXAMPLE.relative_to(ROOT), "--output-unit", "mV", "-o", "-")
    assert result.exit_code == 0, result.stderr
    catalog = yaml.safe_load(result.stdout)
    assert len(catalog["sensors"]) == 9
    lot = catalog["sensors"][-1]["lot"]
    assert lot["units"] == 8 and len(lot["correlation"]) == 15
    monkeypatch.chdir(ROOT)  # the catalogue names the table as given, relative to the root
    again = invoke("fit", "docs/examples/rate-table-gx100.csv", "--output-unit", "mV", "-o", "-")
    # numbers up to the rounding of their last printed digit (tests/docpages.py): the
    # digits the fit writes are those its uncertainty supports, the last one may round
    # either way on another machine's BLAS
    assert same_text(EXAMPLE_CATALOG.read_text(encoding="utf-8"), again.stdout), (
        "regenerate: gyrovib fit docs/examples/rate-table-gx100.csv --output-unit mV "
        "-o docs/examples/rate-table-gx100.gyrovib.yaml")


def test_the_example_is_what_its_generator_writes() -> None:
    import subprocess
    import sys

    done = subprocess.run([sys.executable, str(ROOT / "tools" / "make_rate_table.py"),
                           "--check"], capture_output=True, text=True, check=False, timeout=60)
    assert done.returncode == 0, "docs/examples/rate-table-gx100.csv differs from its generator"
    assert "Made-up numbers" in EXAMPLE.read_text(encoding="utf-8").splitlines()[0]


@pytest.mark.parametrize("fmt", ["table", "csv", "markdown"])
def test_other_formats_carry_the_json_values(table: Path, fmt: str) -> None:
    document = json.loads(invoke("fit", table, "--format", "json").stdout)
    result = invoke("fit", table, "--format", fmt, env={"COLUMNS": "200", "NO_COLOR": "1"})
    assert result.exit_code == 0, result.stderr
    a1 = document["units"][1]["coefficients"]["A1"]
    if fmt == "csv":
        import csv
        import io

        rows = list(csv.DictReader(io.StringIO(result.stdout)))
        assert len(rows) == 3 * 6
        row = next(r for r in rows if r["unit"] == "u2" and r["coefficient"] == "A1")
        assert float(row["value"]) == a1
        assert row["significant"] in ("true", "false")
    else:
        assert f"{a1:.4g}" in result.stdout
        assert "u2" in result.stdout and "The lot" in result.stdout


def test_to_frame_matches_the_csv(table: Path) -> None:
    from gyrovib import api

    result = api.fit(api.read_rate_table(table))
    frame = result.to_frame()
    csv_head = invoke("fit", table, "--format", "csv").stdout.splitlines()[0].split(",")
    assert list(frame.columns) == csv_head
    assert len(frame) == 18
    assert frame.attrs["lot"]["units"] == 3
    assert repr(result).startswith("FitResult(method='least-squares', unit='deg/s'")


def test_plot(table: Path, tmp_path: Path) -> None:
    png = tmp_path / "residuals.png"
    result = invoke("fit", table, "--plot", png)
    assert result.exit_code == 0, result.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_single_unit_without_unit_column(tmp_path: Path) -> None:
    path = tmp_path / "one unit.csv"
    rows = [r.split(",", 1)[1] for r in unit_rows("x", 0.1, 25.0, 2e-3, 3e-6, -4e-9, 0.05)]
    path.write_text("rate,output\n" + "\n".join(rows) + "\n", encoding="utf-8")
    document = json.loads(invoke("fit", path, "--format", "json").stdout)
    assert [u["unit"] for u in document["units"]] == ["one-unit"]
    assert "lot" not in document and document["warnings"] == []


def test_rate_unit_option(tmp_path: Path) -> None:
    """The same table written in rad/s: every coefficient in its rad/s unit."""
    from gyrovib import units

    deg = tmp_path / "deg.csv"
    rad = tmp_path / "rad.csv"
    rows = unit_rows("a", 0.1, 25.0, 2e-3, 3e-6, -4e-9, 0.05, 8)
    deg.write_text("unit,rate,output\n" + "\n".join(rows) + "\n", encoding="utf-8")
    s = units.scale("rad/s")
    converted = [f"{u},{float(w) / s!r},{v}" for u, w, v in (r.split(",") for r in rows)]
    rad.write_text("unit,rate,output\n" + "\n".join(converted) + "\n", encoding="utf-8")
    a = json.loads(invoke("fit", deg, "--format", "json").stdout)["units"][0]
    b = json.loads(invoke("fit", rad, "--format", "json", "--rate-unit", "rad/s").stdout)
    assert b["unit"] == "rad/s"
    for name, value in b["units"][0]["coefficients"].items():
        back = value * units.coefficient_factor(name, "rad/s", "deg/s")
        assert back == pytest.approx(a["coefficients"][name], rel=1e-8), name


# --------------------------------------------------------------------------- errors


def write(tmp_path: Path, text: str, name: str = "t.csv") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_bad_cell_is_located(tmp_path: Path) -> None:
    path = write(tmp_path, "# c\nunit,rate,output\nu1,10,250\nu1, 1O ,250\nu1,20,\n")
    result = invoke("fit", path)
    assert result.exit_code == 2
    lines = result.stderr.splitlines()
    assert f"{path}:4:5: rate: '1O' is not a number" in lines
    assert f"{path}:5:7: output: empty" in lines


def test_header_problems(tmp_path: Path) -> None:
    result = invoke("fit", write(tmp_path, "unit,rate,outptu\nu,1,2\n"))
    assert result.exit_code == 2
    assert ":1:11: unknown column 'outptu'" in result.stderr
    assert "no 'output' column" in result.stderr
    result = invoke("fit", write(tmp_path, "# only a comment\n\n"))
    assert result.exit_code == 2 and "no header row" in result.stderr
    result = invoke("fit", write(tmp_path, "rate,output\n"))
    assert result.exit_code == 2 and "no data rows" in result.stderr


def test_ragged_row_and_bad_unit_name(tmp_path: Path) -> None:
    result = invoke("fit", write(tmp_path, "unit,rate,output\nu1,1\nu 2,1,2\n"))
    assert result.exit_code == 2
    assert ":2:1: 2 cells in this row, 3 columns in the header" in result.stderr
    assert ":3:1: unit: 'u 2' is not a unit name" in result.stderr


def test_unreadable_inputs(tmp_path: Path) -> None:
    result = invoke("fit", tmp_path / "missing.csv")
    assert result.exit_code == 2 and "cannot read the rate table" in result.stderr
    bad = tmp_path / "latin1.csv"
    bad.write_bytes("unit,rate,output\nü,1,2\n".encode("latin-1"))
    result = invoke("fit", bad)
    assert result.exit_code == 2 and ":2:1: not UTF-8 text" in result.stderr
    result = invoke("fit", write(tmp_path, "rate,output\n1,2\n"), "--rate-unit", "furlong/s")
    assert result.exit_code == 2 and "unknown rate unit 'furlong/s'" in result.stderr


def test_identification_errors_name_the_unit_and_its_line(tmp_path: Path) -> None:
    good = unit_rows("good", 0.1, 25.0, 2e-3, 3e-6, -4e-9, 0.05)
    positive = [r for r in unit_rows("pos", 0.1, 25.0, 2e-3, 3e-6, -4e-9, 0.05)
                if not r.split(",")[1].startswith("-")]
    path = write(tmp_path, "unit,rate,output\n" + "\n".join(good + positive) + "\n")
    result = invoke("fit", path)
    assert result.exit_code == 2
    line = 2 + len(good)
    assert (f"{path}:{line}:1: unit 'pos' (12 points): every rate is positive"
            in result.stderr)
    assert "good" not in result.stderr


def test_order_option_is_checked(table: Path) -> None:
    result = invoke("fit", table, "--order", "6")
    assert result.exit_code == 2 and "--order" in result.stderr


def test_standard_input(table: Path) -> None:
    result = invoke("fit", "-", "--format", "json", input=table.read_bytes())
    assert result.exit_code == 0, result.stderr
    assert json.loads(result.stdout)["file"] == "<stdin>"


def test_cross_rate_columns(tmp_path: Path) -> None:
    """rate_x2 alone adds m2 and m32 (noise-free: given back); quoted cells and a BOM read."""
    rows = []
    for w in LEVELS:
        for x2 in (0.0, 60.0):
            u = 20.0 * (0.05 + w + 0.5 * 1e-3 * abs(w) + 2e-6 * w**2 + 1e-3 * x2
                        + 4e-6 * w * x2)
            rows.append(f'"a",{w:g},{u!r},"{x2:g}"')
    path = tmp_path / "cross.csv"
    path.write_bytes(("\ufeffunit,rate,output,rate_x2\n" + "\n".join(rows) + "\n")
                     .encode("utf-8"))
    result = invoke("fit", path, "--order", "2", "--format", "json")
    assert result.exit_code == 0, result.stderr
    coefficients = json.loads(result.stdout)["units"][0]["coefficients"]
    assert list(coefficients) == ["k0", "A1", "k2", "m2", "m32"]
    expected = {"k0": 0.05, "A1": 1e-3, "k2": 2e-6, "m2": 1e-3, "m32": 4e-6}
    for name, value in expected.items():
        assert coefficients[name] == pytest.approx(value, rel=1e-9), name
