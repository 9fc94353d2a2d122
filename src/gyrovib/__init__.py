"""gyrovib: the instrumental vibration error of angular-rate sensors.

The package is layered; each layer imports only the ones below it (the
import-linter contracts of pyproject.toml enforce it; docs/architecture.md):

``gyrovib.core``
    Pure numpy engines: vibration statistics, the error of eq. (13)-(16), the
    allowable coefficients of eq. (23)/(25) and brute-force averaging.
``gyrovib.models``
    The catalogue format as pydantic models (``Catalogue``, ``Sensor``,
    ``Profile``...): a notebook can build them and pass them to
    ``gyrovib.analyze`` (imports no ``core``, no YAML).
``gyrovib.catalog``
    Catalogue files: the YAML dialect and loader, validation through the
    models, located messages (imports no ``core``).
``gyrovib.api``
    Library entry points joining the two: catalogue in, immutable results out;
    one module per command on one preparation pipeline.
``gyrovib.render``
    Pure functions from results to text (table, json, csv, markdown, ...).
``gyrovib.cli``
    The ``gyrovib`` command.

Importing :mod:`gyrovib` itself is cheap: numpy and rich are only
imported by the modules that need them. The notebook API (:mod:`gyrovib.notebook`)
is reached from here, lazily:

>>> import gyrovib
>>> result = gyrovib.select(budget="10deg/h")            # doctest: +SKIP
>>> result.to_frame()                                     # doctest: +SKIP
"""

from typing import Any

from gyrovib._version import __version__

_NOTEBOOK = ("load", "analyze", "bounds", "select", "sweep", "mission")

__all__ = ["__version__", *_NOTEBOOK]


def __getattr__(name: str) -> Any:
    """``gyrovib.load`` & co.: import :mod:`gyrovib.notebook` on first use."""
    if name in _NOTEBOOK:
        # lazy (PEP 562): `import gyrovib` stays light; the notebook face loads on use
        from gyrovib import notebook

        value = getattr(notebook, name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'gyrovib' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_NOTEBOOK})
