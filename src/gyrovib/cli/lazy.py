"""The command line's one lazy boundary: a command is declared (its options, its help)
in a light module, and its body lives in :mod:`gyrovib.cli.run`, imported only when
the command runs.

``gyrovib --help`` and ``gyrovib COMMAND --help`` thus load click and the
declarations only (no numpy, pydantic, rich or YAML: tests/test_startup.py), while
the bodies import what they use at the top of their modules.
"""

from __future__ import annotations

import functools
import importlib
from collections.abc import Callable
from typing import Any, TypeVar, cast

F = TypeVar("F", bound=Callable[..., Any])

#: The package of the commands' bodies.
BODIES = "gyrovib.cli.run"


def runs(name: str) -> Callable[[F], F]:
    """Decorate a command's declaration: calling it calls the function of the same name
    in ``gyrovib.cli.run.<name>``, imported then, with the same arguments. The
    declaration keeps its name, docstring (the command's help) and signature."""
    def declare(declared: F) -> F:
        @functools.wraps(declared)
        def run(*args: Any, **kwargs: Any) -> Any:
            body = getattr(importlib.import_module(run.body_module), declared.__name__)
            return body(*args, **kwargs)

        run.body_module = f"{BODIES}.{name}"  # type: ignore[attr-defined]
        return cast(F, run)

    return declare
