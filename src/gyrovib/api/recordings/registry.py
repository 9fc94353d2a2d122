"""The recording formats by suffix, and their readers (docs/model.md section 13)."""

from __future__ import annotations

from collections.abc import Callable

from gyrovib.api.recordings.dataflash import open_dataflash
from gyrovib.api.recordings.px4 import open_ulog
from gyrovib.api.recordings.readers import Columns, open_csv, open_npy, open_npz, problem

Opener = Callable[[str, "str | None", "int | None"], Columns]

#: The readers by suffix (lower case): a format's name and its reader.
READERS: dict[str, tuple[str, Opener]] = {
    ".csv": ("csv", open_csv), ".txt": ("csv", open_csv),
    ".npy": ("npy", open_npy), ".npz": ("npz", open_npz),
    ".ulg": ("ulog", open_ulog), ".bin": ("dataflash", open_dataflash),
}
#: The formats whose samples carry their own units (rad/s and m/s²) and whose topics
#: or messages have instances.
LOGS = ("ulog", "dataflash")


#: The first bytes of the log formats, for a file whose suffix says nothing.
MAGIC = {b"ULog\x01\x12\x35": ".ulg", b"\xa3\x95\x80": ".bin"}


def reader_for(path: str) -> tuple[str, Opener]:
    """The format of a file by its suffix, else by its first bytes, and its reader."""
    lower = path.lower()
    for suffix, reader in READERS.items():
        if lower.endswith(suffix):
            return reader
    try:
        with open(path, "rb") as fh:
            head = fh.read(8)
    except OSError:
        head = b""
    for magic, suffix in MAGIC.items():
        if head.startswith(magic):
            return READERS[suffix]
    raise problem(path, "unknown recording format: use .csv (header row), .npy, .npz, "
                        ".ulg (PX4 ULog) or .bin (ArduPilot DataFlash)")


__all__ = ["LOGS", "READERS", "Opener", "reader_for"]
