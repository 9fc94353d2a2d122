"""Progress of long work: reported where the work is done, drawn (or not) by the caller.

One mechanism for every command and every layer (like :mod:`gyrovib.errors`,
usable from ``core`` on up; standard library only). A computation calls
:func:`advance` with what it is doing and how far it has got, at the points
where it returns to Python between chunks; whoever runs it installs a receiver
with :func:`receiving` — the command line draws a bar on a terminal
(:func:`gyrovib.cli.progress.terminal_progress`), a notebook may pass its own.
Without a receiver :func:`advance` does nothing (one context-variable look-up),
so the library, tests and pipes see no difference.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar

#: ``receiver(label, done, total)``: ``label`` says what is being done (e.g.
#: "datasheet worst cases"), ``done`` of ``total`` units of it.
Receiver = Callable[[str, int, int], None]

_RECEIVER: ContextVar[Receiver | None] = ContextVar("gyrovib_progress", default=None)


def advance(label: str, done: int, total: int) -> None:
    """Report that ``done`` of ``total`` units of the work ``label`` are finished."""
    receiver = _RECEIVER.get()
    if receiver is not None:
        receiver(label, done, total)


@contextmanager
def receiving(receiver: Receiver | None) -> Iterator[None]:
    """Send the :func:`advance` calls made inside the block to ``receiver`` (None: nowhere)."""
    token = _RECEIVER.set(receiver)
    try:
        yield
    finally:
        _RECEIVER.reset(token)


@contextmanager
def part_of(index: int, count: int) -> Iterator[None]:
    """Inside the block, report the work as part ``index`` of ``count`` equal parts of the
    whole: ``done`` of ``total`` becomes ``index·total + done`` of ``count·total`` (a
    search per profile, each reporting its own sensors, reads as one bar)."""
    outer = _RECEIVER.get()
    if outer is None:
        yield
        return

    def scaled(label: str, done: int, total: int) -> None:
        outer(label, index * total + done, count * total)

    with receiving(scaled):
        yield
