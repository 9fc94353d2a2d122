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

    A failure leaves an existing file untouched. A path that is not a regular
    file (``/dev/null``, a FIFO, a terminal) is written to directly: renaming
    a temporary file over it would replace the device with a plain file.
    """
    if path is None or path == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    target = Path(path)
    try:
        mode = os.stat(target).st_mode
    except OSError:
        mode = None
    if mode is not None and not stat.S_ISREG(mode) and not stat.S_ISDIR(mode):
        try:
            with open(target, "w", encoding="utf-8", newline="") as handle:
                handle.write(text)
        except OSError as exc:
            raise OptionError(f"--output: cannot write {path!r}: {exc.strerror or exc}") from None
        return
    directory = target.parent if str(target.parent) else Path(".")
    if not directory.is_dir():
        raise OptionError(f"--output: directory {str(directory)!r} does not exist")
    if target.is_dir():
        raise OptionError(f"--output: {path!r} is a directory")
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as handle:
            handle.write(text)
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
        raise OptionError(f"--output: cannot write {path!r}: {exc.strerror or exc}") from None
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
