"""Missions (docs/model.md section 12): ``MissionResult``, every sensor over every
mission. The view that computes it is :mod:`gyrovib.api.commands.mission`; the
whole angle budget of section 15 is added by :mod:`gyrovib.api.noise`.
"""

from __future__ import annotations

from gyrovib.api.missions.results import MissionResult, MissionRow, SegmentResult

__all__ = ["MissionResult", "MissionRow", "SegmentResult"]
