"""Helpers shared by the commands."""

from __future__ import annotations

from typing import Any


def load_catalog(files: tuple[str, ...]) -> Any:
    """The merged catalogue of ``files``, or the bundled catalogues when none are given."""
    from gyrovib.api import load

    return load(files)
