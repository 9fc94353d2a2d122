"""Placements: a profile mapped into a sensor's axes, and the triad of three axes.

Its modules are listed in docs/architecture.md."""

from __future__ import annotations

from gyrovib.api.placement.placement import place_catalog, place_profile
from gyrovib.api.placement.triad import TriadResult

__all__ = ["TriadResult", "place_catalog", "place_profile"]
