"""Writing command output: standard output, or a file replaced atomically.

A path that cannot hold the output (no such directory, a directory, no
permission to create a file there) is bad usage (:class:`OptionError`, exit 2).
A failure while writing is the environment's, not a bug: it raises
:class:`WriteFailure` (exit status 74, one line naming what could not be
written), except a reader that went away (``| head``), which stays a
:class:`BrokenPipeError` (exit 141, quiet).
"""

from __future__ import annotations

import contextlib
import os
import select
import stat
import sys
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING, BinaryIO, TextIO

if TYPE_CHECKING:
    from pathlib import Path


def _bad_output(message: str) -> Exception:
    """An :class:`~gyrovib.errors.OptionError` (exit 2), its module imported only when
    an ``--output`` is refused (``gyrovib --help`` does without it)."""
    from gyrovib.errors import OptionError

    return OptionError(message)


class WriteFailure(Exception):
    """The output could not be written (closed stream, full disk, I/O error)."""


#: Set as a command's ``--output`` is renamed into place: from then on the run
#: has succeeded, and a signal no longer interrupts it (cli/main.py).
_in_place = False


def output_in_place() -> bool:
    """Whether the command's output file is (being) put in place: the run has succeeded."""
    return _in_place


def start_run() -> None:
    """A command starts: its output is not in place yet (one process may run several)."""
    global _in_place
    _in_place = False


def silence(fd: int, name: str) -> None:
    """Point a standard stream (its descriptor ``fd`` and ``sys.<name>``) at the null
    device, so that nothing more is written (nor fails again when Python flushes it on
    exit)."""
    with contextlib.suppress(OSError, ValueError):
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, fd)
        os.close(devnull)
    with contextlib.suppress(OSError):
        setattr(sys, name, open(os.devnull, "w", encoding="utf-8"))  # noqa: SIM115


def silence_stdout() -> None:
    """Point standard output at the null device (:func:`silence`)."""
    silence(1, "stdout")


def encodable(text: str, encoding: str | None) -> str:
    """``text``, or its ASCII fallback when ``encoding`` cannot encode it."""
    try:
        text.encode(encoding or "utf-8")
    except UnicodeEncodeError:
        # lazy: this module is loaded by --help, which must not load numpy
        from gyrovib.render.common import to_ascii

        return to_ascii(text)
    except LookupError:
        pass
    return text


#: What a command writes: one text, or its pieces in order (a streaming renderer's
#: chunks), which are written as they come and never joined in memory.
Output = str | Iterable[str]


def _chunks(text: Output) -> Iterator[str]:
    if isinstance(text, str):
        yield text
    else:
        yield from text


def write_output(text: Output, path: str | None) -> None:
    """Write ``text`` to ``path`` atomically (temp file + rename), or to stdout.

    ``text`` is a string or an iterable of strings written one after the
    other, so that a long document need not be held whole. A failure leaves an
    existing file untouched. Standard output that cannot encode a character
    (``PYTHONIOENCODING=ascii``) gets the ASCII fallback, chunk by chunk.
    """
    if path is None or path == "-":
        stream = sys.stdout
        if stream is None:
            raise WriteFailure("cannot write standard output: it is closed")
        encoding = getattr(stream, "encoding", None)
        for chunk in _chunks(text):  # a renderer's own error is not a write failure
            try:
                _write_all(stream, encodable(chunk, encoding))
            except BrokenPipeError:
                raise
            except (OSError, ValueError) as exc:
                silence_stdout()
                reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
                raise WriteFailure(f"cannot write standard output: {reason}") from None
        return
    _replace(path, (chunk.encode("utf-8") for chunk in _chunks(text)), "--output: ",
             final=True)


def _write_all(stream: TextIO, text: str) -> None:
    """Write ``text`` and flush, every byte or an exception.

    With ``PYTHONUNBUFFERED=1`` the stream's binary layer is the raw file, and
    a write to a pipe whose reader left part-way returns a short count that the
    text layer drops without a word: the output would end silently truncated
    with exit 0. So the bytes go to the binary layer here, until all are
    written; the write after a short one raises BrokenPipeError (exit 141).
    """
    buffer = getattr(stream, "buffer", None)
    if buffer is None:  # a stream without a binary layer (io.StringIO, some wrappers)
        stream.write(text)
        stream.flush()
        return
    stream.flush()
    data = memoryview(text.encode(stream.encoding or "utf-8"))
    while data:
        written = buffer.write(data)
        if written is None:  # non-blocking and full: wait until writable
            select.select([], [buffer], [])
            continue
        data = data[written:]
    buffer.flush()


def write_binary(data: bytes, path: str) -> None:
    """Write ``data`` to ``path`` atomically (temp file + rename); never to stdout."""
    _replace(path, data, "")


def _replace(path: str, data: bytes | Iterable[bytes], what: str,
             final: bool = False) -> None:
    """Put ``data`` (bytes, or pieces of it in order) at ``path`` through a
    temporary file in the same directory.

    An existing file keeps its permissions; a new one gets the umask's. A
    symbolic link is written through: its target is replaced, the link stays.
    On any failure, and on SIGINT or SIGTERM (which the command line turns into
    exceptions), the temporary file is removed and ``path`` is left as it was.
    A path that is not a regular file (``/dev/null``, a FIFO, a terminal) is
    written to directly: renaming over it would replace the device.

    ``final``: this is the command's output, its last act. Just before the
    rename the run is marked as succeeded (:func:`output_in_place`): a signal
    from then on is let pass, so a status of 130 or 143 always means that
    ``path`` was left as it was, and 0 that it holds the new output.
    """
    if not path:
        raise _bad_output(f"{what}give a file name")
    from pathlib import Path  # not at import time: ~3 ms of every start-up

    try:  # a name too long, a loop of links, a directory that cannot be searched: exit 2
        target = Path(os.path.realpath(path)) if os.path.islink(path) else Path(path)
        try:
            mode: int | None = os.stat(target).st_mode
        except (FileNotFoundError, NotADirectoryError):
            mode = None
        directory = target.parent if str(target.parent) else Path(".")
        directory_exists = directory.is_dir()
    except (OSError, ValueError) as exc:
        raise _bad_output(f"{what}cannot write {path!r}: {_reason(exc)}") from None
    if mode is not None and not stat.S_ISREG(mode) and not stat.S_ISDIR(mode):
        _write_device(target, data, path, what)
        return
    if not directory_exists:
        raise _bad_output(f"{what}directory {str(directory)!r} of {path!r} does not exist")
    if mode is not None and stat.S_ISDIR(mode):
        raise _bad_output(f"{what}{path!r} is a directory")
    _write_through_temporary(target, directory, data, path, what, final)


def _write_device(target: Path, data: bytes | Iterable[bytes], path: str, what: str) -> None:
    """Write to what is not a regular file (``/dev/null``, a FIFO) directly."""
    try:
        with open(target, "wb") as handle:
            _write_pieces(handle, data)
    except OSError as exc:
        raise WriteFailure(f"{what}cannot write {path!r}: {_reason(exc)}") from None


def _write_through_temporary(target: Path, directory: Path, data: bytes | Iterable[bytes],
                             path: str, what: str, final: bool) -> None:
    """Write a temporary file in ``directory``, give it ``target``'s permissions (a
    new file: the umask's), rename it over ``target``; remove it on any failure."""
    global _in_place
    import tempfile  # not at import time: it costs ~7 ms of start-up

    try:  # the temporary name stays short, whatever the length of the target's
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name[:_PREFIX]}.", suffix=".tmp",
                                   dir=directory)
    except OSError as exc:
        raise _bad_output(f"{what}cannot write in {str(directory)!r} to create {path!r}: "
                          f"{_reason(exc)}") from None
    try:
        with os.fdopen(fd, "wb") as handle:
            _write_pieces(handle, data)
            handle.flush()
            os.fsync(handle.fileno())
        if target.exists():
            os.chmod(tmp, target.stat().st_mode & 0o777)
        else:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(tmp, 0o666 & ~umask)
        _in_place = final  # a signal from here on no longer interrupts (cli/main.py)
        os.replace(tmp, target)
    except OSError as exc:
        _in_place = False
        raise WriteFailure(f"{what}cannot write {path!r}: {_reason(exc)}") from None
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


#: Characters of the target's name kept in the temporary file's: with the random part
#: and the suffix the temporary name stays far below the 255 bytes of a file name.
_PREFIX = 40


def _reason(exc: BaseException) -> str:
    """An OSError's own words (``File name too long``), else the exception's text."""
    return (exc.strerror if isinstance(exc, OSError) and exc.strerror else None) or str(exc)


def _write_pieces(handle: BinaryIO, data: bytes | Iterable[bytes]) -> None:
    if isinstance(data, bytes):
        handle.write(data)
        return
    for piece in data:
        handle.write(piece)
