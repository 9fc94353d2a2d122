"""gyrovib: the instrumental vibration error of angular-rate sensors.

The package is layered; each layer imports only the ones below it:

``gyrovib.core``
    Pure numpy engines: vibration statistics, the error of eq. (13)-(16), the
    allowable coefficients of eq. (23)/(25) and brute-force averaging.
``gyrovib.catalog``
    The catalogue file format (one spec, plain-Python validation) and the YAML loader.
``gyrovib.api``
    Library entry points joining the two: catalogue in, immutable results out.
``gyrovib.render``
    Pure functions from results to text (table, json, csv, markdown, ...).
``gyrovib.cli``
    The ``gyrovib`` command.

Importing :mod:`gyrovib` itself is cheap: numpy, pydantic and rich are only
imported by the modules that need them.
"""

from gyrovib._version import __version__

__all__ = ["__version__"]
