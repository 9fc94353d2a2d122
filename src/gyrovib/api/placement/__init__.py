"""Placements: a profile mapped into a sensor's axes, and the triad of three axes.

=========================================  =======================================
module                                     what it holds
=========================================  =======================================
:mod:`gyrovib.api.placement.placement`     ``place_profile``, ``place_catalog``
:mod:`gyrovib.api.placement.triad`         a command run per axis, ``TriadResult``
=========================================  =======================================
"""

from __future__ import annotations

from gyrovib.api.placement.placement import place_catalog, place_profile
from gyrovib.api.placement.triad import TriadResult

__all__ = ["TriadResult", "place_catalog", "place_profile"]
