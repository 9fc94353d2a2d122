"""Caps and defaults shared by the command line and the library, each defined once.

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
#: The fewest samples ``analyze --method numeric`` takes: two for each of the 16
#: shifted copies of the phase grid whose spread gives the standard error
#: (:mod:`gyrovib.core.numeric`).
MIN_SAMPLES = 32

#: κ of docs/model.md section 9, the peak factor of a random vibration's saturation
#: check (``--peak-factor``, ``peak_factor=``).
DEFAULT_PEAK_FACTOR = 3.0

#: The fit of a recording's profile (docs/recordings.md): f_c (Hz) between the carrier's
#: manoeuvres and the vibration, the Welch PSD's resolution (Hz), how far (dB) a line
#: stands above the running median, and the most breakpoints of the random part's PSD.
DEFAULT_CROSSOVER = 5.0
DEFAULT_RESOLUTION = 0.5
DEFAULT_THRESHOLD = 10.0
DEFAULT_BREAKPOINTS = 12
