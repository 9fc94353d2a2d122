"""The one error root of gyrovib.

Every problem a user can cause (a bad catalogue, a bad option, a profile a
method cannot handle) is raised as a :class:`GyrovibError` carrying one or
more :class:`Problem` records. The command line catches it once, prints one
line per problem on standard error and exits with status 2.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from gyrovib.frozen import Frozen


@dataclass(frozen=True, eq=False, repr=False)
class Problem(Frozen):
    """One thing wrong with the input, with its place when it has one.

    ``line`` and ``column`` are 1-based, as editors show them.
    """

    message: str
    file: str | None = None
    line: int | None = None
    column: int | None = None

    def __str__(self) -> str:
        if self.file is None:
            return self.message
        if self.line is None:
            return f"{self.file}: {self.message}"
        return f"{self.file}:{self.line}:{self.column or 1}: {self.message}"


class GyrovibError(Exception):
    """Root of every error reported to a user; carries one or more problems."""

    def __init__(self, problems: str | Problem | Iterable[Problem]) -> None:
        if isinstance(problems, str):
            problems = (Problem(problems),)
        elif isinstance(problems, Problem):
            problems = (problems,)
        self.problems: tuple[Problem, ...] = tuple(problems)
        super().__init__("\n".join(str(p) for p in self.problems))


class CatalogError(GyrovibError):
    """A catalogue file cannot be read or is not valid."""


class OptionError(GyrovibError):
    """A command-line option or library argument is not valid."""


class ArgumentError(OptionError, ValueError):
    """An argument of the notebook API has a wrong value (a NaN rate, samples past the
    cap); the message names the argument. Also a :class:`ValueError`."""


class ArgumentTypeError(OptionError, TypeError):
    """An argument of the notebook API has a wrong type (bytes for a path, a float for a
    count); the message names the argument. Also a :class:`TypeError`."""


class ModelError(GyrovibError):
    """A method of the model cannot handle a vibration (e.g. ``paper`` with two tones).

    Raised by :mod:`gyrovib.core` with ``reason`` in the model's own words and,
    when the raiser knows it, ``profile``: the index of the profile in the
    batch. The library re-raises it placed at the profile in its file, worded
    for the user.
    """

    def __init__(self, problems: str | Problem | Iterable[Problem] | None = None, *,
                 reason: str | None = None, profile: int | None = None) -> None:
        if problems is None:
            problems = reason or "the model cannot handle this vibration"
        super().__init__(problems)
        self.reason: str = reason if reason is not None else self.problems[0].message
        self.profile: int | None = profile


class RangeError(GyrovibError):
    """A result or an intermediate value overflows floating point (absurd magnitudes)."""


class Crash(Exception):
    """Not a user error: an unexpected exception (a bug) or a worker process that died
    while one file was handled, carried with that file's name.

    ``kind`` is the original exception's type name (or what happened to the worker),
    ``detail`` its message. The command line reports it as an internal error naming
    ``file`` (``FILE: internal error: kind: detail``, exit 3), or as running out of
    memory (exit 2) when ``kind`` is ``MemoryError``, as it reports the exception itself.
    Deliberately not a :class:`GyrovibError`: the input is not to blame.
    """

    def __init__(self, file: str, kind: str, detail: str) -> None:
        super().__init__(f"{file}: {kind}: {detail}" if detail else f"{file}: {kind}")
        self.file = file
        self.kind = kind
        self.detail = detail
