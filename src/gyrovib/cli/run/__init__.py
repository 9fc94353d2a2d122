"""The bodies of the commands declared in :mod:`gyrovib.cli` (one module per command,
imported by :func:`gyrovib.cli.lazy.runs` when the command runs)."""
