"""Located problems of a recording (docs/recordings.md): the error type, where a CSV's
sample is, what a file's first bytes say, and a lone rate column that needs placing."""

from __future__ import annotations

from collections.abc import Sequence

from gyrovib.errors import GyrovibError, Problem, literal


class RecordingError(GyrovibError):
    """A recording cannot be read, or does not suit the analysis asked of it."""


def problem(file: str, message: str, line: int | None = None, column: int | None = None,
            arguments: tuple[str, ...] = ()) -> RecordingError:
    """A located :class:`RecordingError`; a message that names library ``arguments``
    writes each ``{name}`` (:meth:`~gyrovib.errors.Problem.naming`)."""
    if arguments:
        return RecordingError(Problem.naming(message, arguments, file, line, column))
    return RecordingError(Problem(message, file, line, column))


#: The first bytes of a .npy file and of a zip archive (an .npz is one).
_MAGIC = {"npy": (b"\x93NUMPY",), "npz": (b"PK\x03\x04", b"PK\x05\x06")}


def check_magic(path: str, kind: str) -> None:
    """Refuse a file whose first bytes are not its format's: numpy would read anything
    else as pickled data and suggest allow_pickle, which is wrong advice and unsafe."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(8)
    except OSError as exc:
        raise problem(path, f"cannot read: {exc.strerror or exc}") from None
    if not head.startswith(_MAGIC[kind]):
        what = ("a NumPy .npy file (it does not start with the .npy magic bytes)"
                if kind == "npy" else "a NumPy .npz file (it is not a zip archive)")
        raise problem(path, f"not a valid {kind}: the file is not {what}")


def csv_where(path: str, time_col: int | None, sample: int) -> tuple[int | None, int | None]:
    """The line of a CSV's ``sample``-th data row (blank lines are skipped, as the parser
    skips them) and the column of its time cell; (None, None) past the end."""
    with open(path, encoding="utf-8-sig", newline="") as fh:
        fh.readline()
        seen = -1
        for line_no, line in enumerate(fh, start=2):
            if line.strip():
                seen += 1
                if seen == sample:
                    cells = line.split(",")
                    column = (None if time_col is None
                              else 1 + sum(len(x) + 1 for x in cells[:time_col]))
                    return line_no, column
    return None, None


def unplaced(path: str, names: Sequence[str]) -> RecordingError:
    """Fewer than three rate columns and no ``--rate-columns``: no rule places them (a
    lone ``gz`` is not X), the user does; an axis not recorded is ``-`` (unknown, never 0)."""
    shown = ", ".join(repr(n) for n in names)
    example = ",".join(["-"] * (3 - len(names)) + list(names))
    return problem(path, f"{len(names)} rate column(s) ({literal(shown)}) besides the time, and "
                         "no rule says which axis each is: place them with {rate_columns} X,Y,Z, "
                         f"e.g. {{rate_columns}} {literal(example)} (- for an axis not recorded: "
                         "it is then unknown, never taken as 0)", arguments=("rate_columns",))
