from __future__ import annotations

import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner


@pytest.fixture
def write(tmp_path: Path):
    """Write a dedented catalogue into tmp_path and return its path."""

    def _write(text: str, name: str = "catalog.yaml") -> Path:
        path = tmp_path / name
        path.write_text(textwrap.dedent(text), encoding="utf-8")
        return path

    return _write


@pytest.fixture
def run():
    """Invoke the gyrovib CLI in-process; returns click's Result."""
    from gyrovib.cli.main import cli

    def _run(*args: str):
        return CliRunner().invoke(cli, [str(a) for a in args], catch_exceptions=True)

    return _run
