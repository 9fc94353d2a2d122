"""``python -m gyrovib``: the same command line as ``gyrovib``."""

from gyrovib.cli import main

if __name__ == "__main__":  # pragma: no cover
    main()
