"""Many recordings (docs/fleet.md): the one-recording step as a pure function of
(path, options), the recordings in worker processes, and their envelope profile.

``run``: ``RecordingOptions``, ``profile_one``, ``run_recordings``,
``analyze_recordings``; ``envelope``: the envelope as a reduction that can be split
anywhere (``envelope_step``, ``combine``, ``fit_envelope``), and
``profile_recordings`` for ``gyrovib profile A B ...``.
"""

from __future__ import annotations

from gyrovib.api.fleet.envelope import (
    Envelope,
    combine,
    envelope_step,
    fit_envelope,
    profile_recordings,
)
from gyrovib.api.fleet.run import (
    DEFAULTS,
    RecordingOptions,
    analyze_recordings,
    profile_one,
    run_recordings,
)

__all__ = ["DEFAULTS", "Envelope", "RecordingOptions", "analyze_recordings", "combine",
           "envelope_step", "fit_envelope", "profile_one", "profile_recordings",
           "run_recordings"]
