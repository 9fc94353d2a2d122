"""Helpers shared by the commands."""

from __future__ import annotations

from typing import Any


def load_catalog(files: tuple[str, ...]) -> Any:
    """The merged catalogue of ``files``, or the bundled catalogues when none are given."""
    from gyrovib.api import load

    return load(files)


def use_color(output: str | None) -> bool:
    """Colour a table only on a terminal, and never when NO_COLOR is set."""
    import os
    import sys

    if output not in (None, "-") or os.environ.get("NO_COLOR"):
        return False
    return sys.stdout.isatty()
