"""A result's columns as a pandas DataFrame: pandas imported on request, the
document-level fields in ``frame.attrs`` (optional extra ``gyrovib[pandas]``)."""

from __future__ import annotations

from typing import Any

from gyrovib._version import __version__
from gyrovib.errors import GyrovibError

MISSING_PANDAS = "DataFrames need pandas, which is not installed: pip install 'gyrovib[pandas]'"


class MissingDependency(GyrovibError, ImportError):
    """An optional dependency is not installed (the message names the extra)."""


def pandas() -> Any:
    """The pandas module, or :class:`MissingDependency` naming the extra to install."""
    try:
        # lazy: pandas is optional (pip install 'gyrovib[pandas]')
        import pandas
    except ImportError:
        raise MissingDependency(MISSING_PANDAS) from None
    return pandas


def dataframe(columns: dict[str, Any], attrs: dict[str, Any]) -> Any:
    """A DataFrame of ``columns`` (name → values, in order), with the tool, its version
    and ``attrs`` in ``frame.attrs``."""
    frame = pandas().DataFrame(columns)
    frame.attrs.update({"tool": "gyrovib", "version": __version__, **attrs})
    return frame
