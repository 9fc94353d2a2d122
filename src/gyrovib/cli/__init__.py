"""The ``gyrovib`` command line: thin commands over :mod:`gyrovib.api`."""

from __future__ import annotations

import signal

from gyrovib.cli.early import EARLY, early_exit


def main() -> None:
    """Console-script entry point; a signal during the imports exits in one line too
    (130 for Ctrl-C, 143 SIGTERM, 129 SIGHUP), as it would once the command runs.

    The handlers set here stay until :func:`gyrovib.cli.main.main` replaces each by its
    own in one step: at no moment does a signal's default action (death, or a
    ``KeyboardInterrupt`` traceback) apply. A signal the parent set to be ignored
    stays ignored."""
    for name in EARLY:
        signum = getattr(signal, name, None)
        if signum is not None and signal.getsignal(signum) in (signal.SIG_DFL, None,
                                                               signal.default_int_handler):
            signal.signal(signum, early_exit)
    # lazy: after the early handlers, so a signal while it loads exits in one line
    from gyrovib.cli.main import main as run

    run()
