"""The datasheet form (``specs:``): a sensor known by its datasheet figures.

Its modules are listed in docs/architecture.md. It reads a prepared
:class:`~gyrovib.api.study.Study`; it evaluates no view.
"""

from __future__ import annotations

from gyrovib.api.datasheet.spec_bounds import DatasheetBounds, datasheet_bounds, spec_checks
from gyrovib.api.datasheet.specs import figures, is_spec, worst

__all__ = ["DatasheetBounds", "datasheet_bounds", "figures", "is_spec", "spec_checks", "worst"]
