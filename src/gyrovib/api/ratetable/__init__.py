"""Rate-table tests (docs/model.md section 14): the table read a block at a time
(``reading``), what ``gyrovib fit`` gives (``results``: ``FitResult``) and the catalogue
its ``-o`` writes (``yaml``: ``fit_catalog``). The fit itself is the command view
:mod:`gyrovib.api.commands.fit` on ``core.fit`` and ``core.lot``.
"""

from __future__ import annotations

from gyrovib.api.ratetable.reading import RateTable, RateTableError, read_rate_table
from gyrovib.api.ratetable.results import FitResult

__all__ = ["FitResult", "RateTable", "RateTableError", "read_rate_table"]
