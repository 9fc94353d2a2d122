"""Writing command output: standard output, or a file replaced atomically."""

from __future__ import annotations

import os
import stat
import sys
import tempfile
from pathlib import Path

from gyrovib.errors import OptionError


def write_output(text: str, path: str | None) -> None:
    """Write ``text`` to ``path`` atomically (temp file + rename), or to stdout.

    A failure leaves an existing file untouched.
    """
    if path is None or path == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    _replace(path, text.encode("utf-8"), "--output: ")


def write_binary(data: bytes, path: str) -> None:
    """Write ``data`` to ``path`` atomically (temp file + rename); never to stdout."""
    _replace(path, data, "")


def _replace(path: str, data: bytes, what: str) -> None:
    """Put ``data`` at ``path`` through a temporary file in the same directory.

    An existing file keeps its permissions; a new one gets the umask's. On any
    failure the temporary file is removed and ``path`` is left as it was. A
    path that is not a regular file (``/dev/null``, a FIFO, a terminal) is
    written to directly: renaming over it would replace the device.
    """
    if not path:
        raise OptionError(f"{what}give a file name")
    target = Path(path)
    try:
        mode = os.stat(target).st_mode
    except OSError:
        mode = None
    if mode is not None and not stat.S_ISREG(mode) and not stat.S_ISDIR(mode):
        try:
            with open(target, "wb") as handle:
                handle.write(data)
        except OSError as exc:
            raise OptionError(f"{what}cannot write {path!r}: {exc.strerror or exc}") from None
        return
    directory = target.parent if str(target.parent) else Path(".")
    if not directory.is_dir():
        raise OptionError(f"{what}directory {str(directory)!r} of {path!r} does not exist")
    if target.is_dir():
        raise OptionError(f"{what}{path!r} is a directory")
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=directory)
    except OSError as exc:
        raise OptionError(f"{what}cannot write in {str(directory)!r}: "
                          f"{exc.strerror or exc}") from None
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        if target.exists():
            os.chmod(tmp, target.stat().st_mode & 0o777)
        else:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, target)
    except OSError as exc:
        raise OptionError(f"{what}cannot write {path!r}: {exc.strerror or exc}") from None
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
