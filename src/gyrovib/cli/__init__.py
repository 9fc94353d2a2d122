"""The ``gyrovib`` command line: thin commands over :mod:`gyrovib.api`."""

from __future__ import annotations

import sys


def main() -> None:
    """Console-script entry point; Ctrl-C during the imports exits 130 in one line too."""
    try:
        from gyrovib.cli.main import main as run
    except KeyboardInterrupt:
        sys.stderr.write("\ngyrovib: interrupted\n")
        raise SystemExit(130) from None
    run()
