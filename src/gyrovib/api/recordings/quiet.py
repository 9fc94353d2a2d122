"""What a log library prints, kept off gyrovib's standard output.

pyulog and pymavlink report what they notice ("Warning: no subscription found…",
"bad header 0x.. at N", "Skipped N bad bytes…") with ``print``, on standard output
and standard error (pymavlink's compiled indexer with C's ``fprintf``).
gyrovib's standard output carries its document and nothing else, and its standard
error says things in its own located form, so a reader runs the library inside
:func:`captured`: Python's ``sys.stdout`` and ``sys.stderr`` are swapped for
buffers, and file descriptors 1 and 2 themselves are pointed at temporary files (a
message written below Python, by compiled code, is caught too). What was captured
comes back as lines, which the reader turns into warnings that name the file
(:func:`as_notes`).
"""

from __future__ import annotations

import contextlib
import io
import os
import sys
import tempfile
from collections.abc import Iterator

#: Library lines repeated as warnings at most; the rest are counted.
MAX_NOTES = 5


@contextlib.contextmanager
def captured(lines: list[str]) -> Iterator[None]:
    """Run the body with standard output and error captured; append their lines to
    ``lines`` (blank lines dropped) when the body ends, normally or not."""
    out, err = io.StringIO(), io.StringIO()
    with tempfile.TemporaryFile() as raw_out, tempfile.TemporaryFile() as raw_err, \
            _fd_redirected(1, raw_out), _fd_redirected(2, raw_err), \
            contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            yield
        finally:
            lines.extend(_lines(out.getvalue()) + _lines(err.getvalue()))
            lines.extend(_lines(_read(raw_out)) + _lines(_read(raw_err)))


@contextlib.contextmanager
def _fd_redirected(fd: int, target: io.BufferedRandom) -> Iterator[None]:
    """File descriptor ``fd`` pointed at ``target`` for the body (nothing happens where
    ``fd`` is not open, as under some test runners)."""
    try:
        saved = os.dup(fd)
    except OSError:
        yield
        return
    with contextlib.suppress(Exception):
        sys.stdout.flush()
        sys.stderr.flush()
    try:
        os.dup2(target.fileno(), fd)
        yield
    finally:
        os.dup2(saved, fd)
        os.close(saved)


def _read(raw: io.BufferedRandom) -> str:
    raw.flush()
    raw.seek(0)
    return raw.read().decode("utf-8", errors="replace")


def _lines(text: str) -> list[str]:
    return [line.strip() for line in text.splitlines() if line.strip()]


def as_notes(library: str, lines: list[str]) -> tuple[str, ...]:
    """The captured lines as warnings in the library's name: the first
    :data:`MAX_NOTES` distinct ones, and how many more there were."""
    distinct = list(dict.fromkeys(lines))
    notes = [f"{library} said: {line}" for line in distinct[:MAX_NOTES]]
    if len(distinct) > MAX_NOTES:
        notes.append(f"{library} said {len(distinct) - MAX_NOTES} more thing(s) like these")
    return tuple(notes)
