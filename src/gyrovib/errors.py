"""The one error root of gyrovib.

Every problem a user can cause (a bad catalogue, a bad option, a profile a
method cannot handle) is raised as a :class:`GyrovibError` carrying one or
more :class:`Problem` records. The command line catches it once, prints one
line per problem on standard error and exits with status 2.

A warning that advises a library argument (``strict``, ``breakpoints``) is a
:class:`Note`: its text names the argument as the library takes it, and the
command line words it with the option that sets it instead.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
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
    #: The message with each argument it names written ``{name}``, and those arguments
    #: (:meth:`naming`): the command line words them as its options.
    template: str | None = None
    arguments: tuple[str, ...] = ()

    @classmethod
    def naming(cls, template: str, arguments: tuple[str, ...], file: str | None = None,
               line: int | None = None, column: int | None = None) -> Problem:
        """A problem whose message names library ``arguments``, each written ``{name}`` in
        ``template``: the library's message names them as they are (``fs``), the command
        line's as its options (:meth:`worded`)."""
        return cls(fill(template, arguments, str), file, line, column, template, arguments)

    def worded(self, name: Callable[[str], str]) -> Problem:
        """The problem with each argument it names written by ``name`` (an option)."""
        if self.template is None:
            return self
        return Problem(fill(self.template, self.arguments, name), self.file, self.line,
                       self.column)

    def __str__(self) -> str:
        if self.file is None:
            return self.message
        if self.line is None:
            return f"{self.file}: {self.message}"
        return f"{self.file}:{self.line}:{self.column or 1}: {self.message}"


_PLACES = re.compile(r"\{\{|\}\}|\{([A-Za-z_]\w*)\}")


def fill(template: str, arguments: tuple[str, ...], name: Callable[[str], str]) -> str:
    """``template`` with each of ``arguments`` written ``{argument}`` replaced by
    ``name(argument)``, in one pass. A template that names arguments writes any text of
    the user's inside it through :func:`literal` (its braces doubled), so that a file
    named ``{strict}.csv`` is never taken for the argument; a brace that is neither
    doubled nor around an argument is kept. Without arguments the template is the text."""
    if not arguments:
        return template
    named = set(arguments)

    def place(match: re.Match[str]) -> str:
        word = match.group(1)
        if word is None:
            return match.group(0)[0]
        return name(word) if word in named else match.group(0)

    return _PLACES.sub(place, template)


def literal(text: object) -> str:
    """``text`` as it is, inside a template that names arguments (:func:`fill`): its
    braces doubled, so that none is read as an argument."""
    return str(text).replace("{", "{{").replace("}", "}}")


class Note(str):
    """A warning that names library arguments: as text, each is written as the library
    takes it (``strict=True``, ``accel_unit='g'``, ``breakpoints``); :meth:`worded` writes
    them otherwise (the command line: as its options, ``--strict``, ``--accel-unit g``).

    ``template`` writes each argument ``{name}``; ``arguments`` pairs each name with the
    value the warning gives it, None for the argument alone. Being a ``str``, a note
    goes wherever a warning's text goes (JSON, tables, a worker process's pickle)."""

    template: str
    arguments: tuple[tuple[str, object], ...]

    def __new__(cls, template: str, *arguments: tuple[str, object]) -> Note:
        note = super().__new__(cls, _fill_values(template, arguments, library_words))
        note.template, note.arguments = template, arguments
        return note

    def worded(self, name: Callable[[str, object], str]) -> str:
        """The text with each argument written ``name(argument, value)``."""
        return _fill_values(self.template, self.arguments, name)

    def __reduce__(self) -> tuple[type[Note], tuple[object, ...]]:
        return Note, (self.template, *self.arguments)


def headed(head: str, text: str) -> str:
    """``text`` after ``head`` (a file's name, say); a note stays a note."""
    if isinstance(text, Note):
        return Note((literal(head) if text.arguments else head) + text.template,
                    *text.arguments)
    return head + text


def library_words(argument: str, value: object) -> str:
    """An argument as the library takes it: ``breakpoints``, ``strict=True``."""
    return argument if value is None else f"{argument}={value!r}"


def _fill_values(template: str, arguments: tuple[tuple[str, object], ...],
                 name: Callable[[str, object], str]) -> str:
    values = dict(arguments)
    return fill(template, tuple(values), lambda argument: name(argument, values[argument]))


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
    """A library argument (a command-line option) is not valid.

    Raised with ``argument`` (the library's parameter name), ``value`` (its value as
    written) and ``reason``, the message names the argument: ``samples=10: give at
    least 32``. A reason that points to arguments writes each as ``{name}`` and lists
    them in ``others`` (``argument`` may then be None: a message about several). The
    command line names the options instead (``--samples 10: …``), from the same fields
    (:func:`gyrovib.cli.options.as_option`). Without them, the message is given whole.
    """

    def __init__(self, problems: str | Problem | Iterable[Problem] | None = None, *,
                 argument: str | None = None, value: str | None = None,
                 reason: str | None = None, others: tuple[str, ...] = ()) -> None:
        self.argument = argument
        self.value = value
        self.template = reason
        self.others = others
        self.problems = ()
        if problems is None:
            problems = self.worded(lambda name: name, head=True)
        super().__init__(problems)
        self.reason = self.worded(lambda name: name)

    def worded(self, name: Callable[[str], str], head: bool = False) -> str:
        """The reason with each argument written by ``name`` (an option, or as is);
        ``head``: after the argument and its value, ``NAME=VALUE: reason``."""
        if self.template is None:
            return self.problems[0].message if self.problems else ""
        reason = fill(self.template, self.others, name)
        if not head or self.argument is None:
            return reason
        who = name(self.argument)
        if self.value is None:
            return f"{who}: {reason}"
        return f"{who}={self.value}: {reason}" if who == self.argument else \
            f"{who} {self.value}: {reason}"


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
