"""docs/notebook.py, the notebook-style example, runs top to bottom and plots."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("pandas", reason="the example needs the pandas extra")
pytest.importorskip("matplotlib", reason="the example needs the plot extra")

EXAMPLE = Path(__file__).resolve().parents[1] / "docs" / "notebook.py"


def test_notebook_example_runs_and_plots(tmp_path):
    target = tmp_path / "sweep.png"
    env = {**os.environ, "GYROVIB_PLOT": str(target), "MPLBACKEND": "Agg"}
    done = subprocess.run([sys.executable, str(EXAMPLE)], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr[-3000:]
    out = done.stdout
    # both parts appear in the comparison tables, and the plot is a PNG file
    assert "adxrs645" in out and "sch16t" in out and f"plotted to {target}" in out
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
