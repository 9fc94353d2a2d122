"""The layering of docs/architecture.md, enforced: `lint-imports` keeps the contracts
of pyproject.toml ([tool.importlinter])."""

from __future__ import annotations

import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).parent.parent


def _lint_imports() -> list[str]:
    found = shutil.which("lint-imports", path=str(Path(sys.executable).parent))
    if found is None:
        found = shutil.which("lint-imports")
    if found is None:
        pytest.skip("import-linter is not installed (pip install -e '.[test]' brings it)")
    return [found]


def test_import_contracts_are_kept() -> None:
    result = subprocess.run([*_lint_imports(), "--no-cache"], cwd=ROOT, capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    # every contract of pyproject.toml was checked, and kept
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    contracts = config["tool"]["importlinter"]["contracts"]
    assert len(contracts) >= 4
    assert f"{len(contracts)} kept, 0 broken" in result.stdout, result.stdout


def test_core_messages_name_no_command_line_option() -> None:
    # core speaks of the model; the library and the command line word refusals for users
    for path in sorted((ROOT / "src" / "gyrovib" / "core").glob("*.py")):
        text = path.read_text(encoding="utf-8")
        for flag in ("--method", "--profile", "--sensor", "--rate", "--samples", "--unit"):
            assert flag not in text, f"{path.name} mentions {flag}"
