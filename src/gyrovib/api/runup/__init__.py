"""The run-up test (docs/model.md section 16): a recording of the vehicle at rest, its
vibration stepped, turned into the installed sensor's own rectification.

=====================  =========================================================
name                   what it is
=====================  =========================================================
:func:`runup`          a recording (and a catalogue sensor) → :class:`RunupResult`
:func:`runup_yaml`     a result as a catalogue sensor entry with the in-situ figures
``measure``            the steps found or placed, and what each one measures
=====================  =========================================================
"""

from gyrovib.api.runup.results import Estimate, RunupResult, Step
from gyrovib.api.runup.run import check_terms, default_terms, estimate_units, runup
from gyrovib.api.runup.yaml import runup_yaml

__all__ = ["Estimate", "RunupResult", "Step", "check_terms", "default_terms",
           "estimate_units", "runup", "runup_yaml"]
