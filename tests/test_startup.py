"""`gyrovib --help` and `--version` start fast: no heavy module is imported."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

HEAVY = ("numpy", "pydantic", "pydantic_core", "rich", "yaml", "scipy", "highspy")

#: Runs the command in a fresh interpreter, then prints the imported modules.
VIA_CLI = """
import contextlib, io, json, sys
from gyrovib.cli.main import cli
with contextlib.redirect_stdout(io.StringIO()) as out:
    code = cli.main({args!r}, prog_name="gyrovib", standalone_mode=False)
assert code in (None, 0), code
assert out.getvalue().strip(), "the command printed nothing"
print(json.dumps(sorted(sys.modules)))
"""

VIA_MODULE = """
import contextlib, io, json, runpy, sys
sys.argv = ["gyrovib", *{args!r}]
with contextlib.redirect_stdout(io.StringIO()) as out:
    try:
        runpy.run_module("gyrovib", run_name="__main__", alter_sys=True)
    except SystemExit as exc:
        assert exc.code in (None, 0), exc.code
assert out.getvalue().strip(), "the command printed nothing"
print(json.dumps(sorted(sys.modules)))
"""


def imported_modules(template: str, args: list[str]) -> list[str]:
    done = subprocess.run([sys.executable, "-c", template.format(args=args)],
                          capture_output=True, text=True, check=False, timeout=60)
    assert done.returncode == 0, done.stderr
    modules: list[str] = json.loads(done.stdout.strip().splitlines()[-1])
    return modules


@pytest.mark.parametrize("template", [VIA_CLI, VIA_MODULE], ids=["cli.main", "python -m"])
@pytest.mark.parametrize("args", [["--help"], ["--version"], ["analyze", "--help"],
                                  ["select", "--help"], ["report", "--help"]])
def test_help_and_version_import_no_heavy_module(template, args):
    modules = imported_modules(template, args)
    assert "click" in modules  # the probe works
    heavy = sorted(m for m in modules if m.split(".")[0] in HEAVY)
    assert heavy == [], f"gyrovib {' '.join(args)} imported {heavy}"


#: What a first ``gyrovib analyze`` (table) does not need of the libraries: json
#: (tables only), scipy, numpy.ma (~15 ms; np.unique and np.setdiff1d import it).
#: (rich it needs: it draws the table; pydantic validates the
#: catalogue, and imports pathlib itself.) Which of gyrovib's own modules it loads
#: is its business: the start-up budget below is what it must keep.
NOT_FOR_ANALYZE = ("json", "scipy", "numpy.ma")

#: As VIA_CLI, json imported only after the modules are listed (it is one of them).
VIA_CLI_LATE_JSON = """
import contextlib, io, sys
from gyrovib.cli.main import cli
with contextlib.redirect_stdout(io.StringIO()) as out:
    code = cli.main({args!r}, prog_name="gyrovib", standalone_mode=False)
assert code in (None, 0), code
assert out.getvalue().strip(), "the command printed nothing"
modules = sorted(sys.modules)
import json
print(json.dumps(modules))
"""

COEFFICIENTS_ONLY = """
gyrovib: 1
sensors:
  - id: s
    coefficients: {A1: 1e-3, k2: 1e-4, k4: 1e-8, m31: 1e-5}
profiles:
  - id: tone
    harmonic: [{frequency: 100, amplitude: [0, 0, 20]}]
  - id: shaft
    rate: [0, 0, 2]
    harmonics:
      fundamental: 25
      orders:
        - {order: 1, amplitude: [0.5, 0.3, 1.5], phase: [0, 90, 0]}
        - {order: 2, amplitude: [0.2, 0.2, 0.8], phase: [0, 0, 270]}
"""


def test_first_analyze_imports_only_what_it_uses():
    modules = imported_modules(VIA_CLI_LATE_JSON, ["analyze"])
    assert "numpy" in modules and "gyrovib.api.evaluation.results" in modules  # the probe works
    assert sorted(set(NOT_FOR_ANALYZE) & set(modules)) == []


def test_csv_and_json_output_do_not_import_rich():
    # rich draws the tables only: the machine formats, the fast path past 2,000 rows,
    # pay nothing for it
    for fmt in ("json", "csv"):
        modules = imported_modules(VIA_CLI_LATE_JSON, ["analyze", "--format", fmt])
        assert "gyrovib.api.evaluation.results" in modules  # the probe works
        assert "rich" not in modules, fmt


def test_analyze_of_coefficient_sensors_needs_no_numpy_ma(tmp_path):
    # numpy.ma (~7 ms) comes with np.unique; the coefficient-form path avoids it, and
    # needs none of the datasheet envelope's modules
    path = tmp_path / "c.gyrovib.yaml"
    path.write_text(COEFFICIENTS_ONLY, encoding="utf-8")
    modules = imported_modules(VIA_CLI_LATE_JSON, ["analyze", str(path)])
    assert "gyrovib.core.harmonics" in modules  # the probe works: a locked group was built
    heavy = sorted(m for m in modules if m in ("numpy.ma", "numpy.random", "highspy")
                   or m in NOT_FOR_ANALYZE)
    assert heavy == []


def test_a_command_scans_no_pydantic_plugins_unless_asked(monkeypatch):
    # importlib.metadata (~20 ms, with the entry-point scan) is what pydantic's plugin
    # loader needs; the command runs no plugin, so neither is imported...
    monkeypatch.delenv("PYDANTIC_DISABLE_PLUGINS", raising=False)
    modules = imported_modules(VIA_CLI, ["analyze", "--sensor", "adxrs453"])
    assert "gyrovib.models.catalogue" in modules  # the probe works: models were built
    assert "importlib.metadata" not in modules
    # ... unless the user asks for plugins: then pydantic's own loader runs
    monkeypatch.setenv("PYDANTIC_DISABLE_PLUGINS", "")
    modules = imported_modules(VIA_CLI, ["analyze", "--sensor", "adxrs453"])
    assert "importlib.metadata" in modules
