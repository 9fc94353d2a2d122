"""Caps shared by the command line and the library, each defined once.

Plain constants, no imports: ``gyrovib.cli.options`` reads them while
``gyrovib --help`` is drawn, and the library and the notebook API enforce the
same values, so a cap cannot be bypassed by calling Python instead of the
command.
"""

from __future__ import annotations

#: The most samples ``analyze --method numeric`` (and ``gyrovib.analyze(samples=)``)
#: takes per sensor × profile: 10^8 evaluations of eq. (2) take minutes; more is a
#: typo, not a study.
MAX_SAMPLES = 100_000_000
