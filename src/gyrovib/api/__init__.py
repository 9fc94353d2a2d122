"""Library entry points: a catalogue in, immutable results out.

This layer joins the catalogue (:mod:`gyrovib.catalog`) to the numpy engines
(:mod:`gyrovib.core`) and does all unit handling: catalogue values are
converted to deg/s on the way in, results to the requested output unit on the
way out.

=================================  ============================================
package                            what it holds
=================================  ============================================
:mod:`gyrovib.api.study`           the Study: entries chosen, values in deg/s,
                                   the one preparation and its overflow checks
:mod:`gyrovib.api.datasheet`       the datasheet form: figures, worst case, the
                                   spec checks and spec bounds
:mod:`gyrovib.api.evaluation`      the model evaluated per sensor form, and the
                                   immutable result types
:mod:`gyrovib.api.commands`        one view of a Study per command
:mod:`gyrovib.api.report`          ``gyrovib report``: three views of one Study
:mod:`gyrovib.api.placement`       placements and the triad
=================================  ============================================

The public names are listed once, in ``__init__.pyi`` (for type checkers); at run
time each is imported from the module named there on first use.

>>> from gyrovib.api import load, analyze
>>> result = analyze(load())          # the bundled catalogues  # doctest: +SKIP
"""

from __future__ import annotations

import importlib
import os
import re
from typing import Any

#: One line of __init__.pyi: ``from MODULE import NAME as NAME``.
_LINE = re.compile(r"^from ([\w.]+) import (\w+) as \2$", re.MULTILINE)


def _listing() -> dict[str, str]:
    """Each public name and its module, read from ``__init__.pyi``."""
    path = os.path.join(os.path.dirname(__file__), "__init__.pyi")
    with open(path, encoding="utf-8") as stub:
        return {name: module for module, name in _LINE.findall(stub.read())}


_WHERE: dict[str, str] = _listing()

__all__ = [*_WHERE]


def __getattr__(name: str) -> Any:
    where = _WHERE.get(name)
    if where is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(where), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_WHERE})
