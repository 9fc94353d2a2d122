"""The ``gyrovib`` command line: thin commands over :mod:`gyrovib.api`."""
