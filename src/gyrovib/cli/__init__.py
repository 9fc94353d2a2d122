"""The ``gyrovib`` command line: thin commands over :mod:`gyrovib.api`."""

from __future__ import annotations

import signal
import sys
from typing import Any

#: The words of the signals a run answers in one line (as gyrovib.cli.main does).
_EARLY = {"SIGTERM": "terminated", "SIGHUP": "hung up"}


def _early_exit(signum: int, frame: Any) -> None:
    """SIGTERM or SIGHUP while the command line is still being imported: one line,
    exit 128 + the signal, nothing written yet."""
    word = _EARLY.get(signal.Signals(signum).name, "terminated")
    sys.stderr.write(f"\ngyrovib: {word}\n")
    raise SystemExit(128 + signum)


def main() -> None:
    """Console-script entry point; a signal during the imports exits in one line too
    (130 for Ctrl-C, 143 SIGTERM, 129 SIGHUP), as it would once the command runs."""
    early = []
    for name in _EARLY:
        signum = getattr(signal, name, None)
        if signum is not None and signal.getsignal(signum) in (signal.SIG_DFL, None):
            signal.signal(signum, _early_exit)
            early.append(signum)
    try:
        # lazy: after the early handlers, so a signal while it loads exits in one line
        from gyrovib.cli.main import main as run
    except KeyboardInterrupt:
        sys.stderr.write("\ngyrovib: interrupted\n")
        raise SystemExit(130) from None
    # back to the default, so the command installs its own handlers (it keeps a
    # signal the parent set to be ignored as it was)
    for signum in early:
        signal.signal(signum, signal.SIG_DFL)
    run()
