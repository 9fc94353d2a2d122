"""Progress bars on standard error, shown only when standard error is a terminal.

Every command runs inside :func:`terminal_progress` (``cli/main.py``): the
library's :func:`gyrovib.progress.advance` calls then draw one transient rich
bar per kind of work, from the first report made after :data:`DELAY` seconds
of the command — a quick run draws nothing. Piped or captured standard error
(CI, ``2> file``) installs no receiver at all.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

from gyrovib.progress import advance, receiving

#: Seconds a command runs before its progress is drawn.
DELAY = 1.0


def _is_terminal() -> bool:
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError, OSError):
        return False


@contextmanager
def terminal_progress() -> Iterator[None]:
    """Draw the :func:`gyrovib.progress.advance` reports made inside the block on stderr."""
    if not _is_terminal():
        yield
        return
    started = time.monotonic()
    state: dict[str, Any] = {"bar": None, "tasks": {}}

    def receive(label: str, done: int, total: int) -> None:
        bar = state["bar"]
        if bar is None:
            if time.monotonic() - started < DELAY:
                return
            # lazy: rich only draws tables; csv and json output never load it
            from rich.console import Console
            from rich.progress import (
                BarColumn,
                Progress,
                TaskProgressColumn,
                TimeRemainingColumn,
            )

            bar = Progress("[progress.description]{task.description}", BarColumn(),
                           TaskProgressColumn(), TimeRemainingColumn(),
                           console=Console(stderr=True), transient=True,
                           redirect_stdout=False, redirect_stderr=False)
            bar.start()
            state["bar"] = bar
        tasks: dict[str, Any] = state["tasks"]
        if label not in tasks:
            tasks[label] = bar.add_task(label, total=total)
        bar.update(tasks[label], completed=done, total=total)
        if done >= total:  # this work is over: its bar goes, and the display with the last
            bar.remove_task(tasks.pop(label))
            if not tasks:
                bar.stop()
                state["bar"] = None

    try:
        with receiving(receive):
            yield
    finally:
        if state["bar"] is not None:
            state["bar"].stop()


@contextmanager
def progress_bar(description: str, enabled: bool = True) -> Iterator[Callable[[int, int], None]]:
    """Yield a ``progress(done, total)`` callback reporting ``description`` through
    :func:`gyrovib.progress.advance` (drawn by :func:`terminal_progress`); a no-op
    when ``enabled`` is false."""
    if not enabled:
        yield lambda done, total: None
        return
    yield lambda done, total: advance(description, done, total)
