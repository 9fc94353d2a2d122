"""The noise domain (docs/model.md section 15): the overlapping Allan deviation of a
static recording, a sensor's noise figures, and the angle budget of a mission.

=====================================  ===========================================
name                                    what it is
=====================================  ===========================================
:func:`allan`                           a recording → :class:`AllanResult`
:func:`noise_yaml`                      an Allan result as a ``noise:`` block
:func:`noise_values`                    a sensor's ``noise:`` in the default units
:func:`budget`                          one row's angle budget → :class:`Budget`
:func:`allowance`                       the largest figures that meet an angle budget
:func:`timeline`                        a row's budget at the end of each segment
:func:`mission`                         ``gyrovib mission`` with every row's budget
:func:`ranked`                          a mission result, sensors by budget total
=====================================  ===========================================
"""

from gyrovib.api.noise.allan import allan
from gyrovib.api.noise.budget import allowance, budget, noise_angles, timeline
from gyrovib.api.noise.figures import FIGURES, noise_values
from gyrovib.api.noise.mission import check_coverage, mission, ranked
from gyrovib.api.noise.results import (
    ALLOWANCE_UNITS,
    FIGURE_UNITS,
    NOISE_TERMS,
    AllanResult,
    Allowance,
    AxisAllan,
    Budget,
    Figure,
    GaussMarkov,
)
from gyrovib.api.noise.yaml import noise_yaml

__all__ = [
    "ALLOWANCE_UNITS",
    "FIGURES",
    "FIGURE_UNITS",
    "NOISE_TERMS",
    "AllanResult",
    "Allowance",
    "AxisAllan",
    "Budget",
    "Figure",
    "GaussMarkov",
    "allan",
    "allowance",
    "budget",
    "check_coverage",
    "mission",
    "noise_angles",
    "noise_values",
    "noise_yaml",
    "ranked",
    "timeline",
]
