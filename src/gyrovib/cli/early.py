"""The signal handler of the console script's start-up (:func:`gyrovib.cli.main`), until
the command line's own (:mod:`gyrovib.cli.main`) replaces it. Standard library only."""

from __future__ import annotations

import signal
import sys
from typing import Any

#: The words of the signals a run answers in one line (as gyrovib.cli.main does).
EARLY = {"SIGINT": "interrupted", "SIGTERM": "terminated", "SIGHUP": "hung up"}


def early_exit(signum: int, frame: Any) -> None:
    """A signal while the command line is still being imported: one line, exit
    128 + the signal, nothing written yet."""
    word = EARLY.get(signal.Signals(signum).name, "terminated")
    sys.stderr.write(f"\ngyrovib: {word}\n")
    raise SystemExit(128 + signum)
