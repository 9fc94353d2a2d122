"""GitHub Actions workflow commands: ``::error file=…,line=…::message`` annotations.

Pure functions, no I/O. A workflow step that prints these lines on standard
output gets them shown as annotations on the files and lines they name.

Escaping follows the runner's rules: in the message (the "data") ``%``,
``\\r`` and ``\\n`` are percent-encoded; in a property value (file, title, …)
``:`` and ``,`` are encoded as well, since they separate properties.
"""

from collections.abc import Iterable, Sequence

from gyrovib.errors import Problem

LEVELS = ("error", "warning", "notice")

#: GitHub shows at most this many annotations of each level per step.
GITHUB_LIMIT = 10

#: Control characters other than CR and LF (which the runner decodes), e.g. ESC.
_CONTROL = {c: f"\\x{c:02x}" for c in (*range(0x20), *range(0x7F, 0xA0))
            if c not in (0x0A, 0x0D)}

#: One annotation: (file, line, title, message, level); file, line and title may be None.
Item = tuple[str | None, int | None, str | None, str, str]


def escape_data(text: str) -> str:
    """Escape a workflow command's message; other control characters (an ANSI
    escape in a file name) are shown as ``\\x1b``."""
    return (text.translate(_CONTROL).replace("%", "%25").replace("\r", "%0D")
            .replace("\n", "%0A"))


def escape_property(text: str) -> str:
    """Escape a workflow command's property value."""
    return escape_data(text).replace(":", "%3A").replace(",", "%2C")


def annotation(message: str, *, level: str = "error", file: str | None = None,
               line: int | None = None, column: int | None = None,
               title: str | None = None) -> str:
    """One ``::level file=…,line=…,col=…,title=…::message`` line (no newline)."""
    if level not in LEVELS:
        raise ValueError(f"unknown annotation level {level!r}; use one of {', '.join(LEVELS)}")
    props: list[str] = []
    if file is not None:
        props.append(f"file={escape_property(file)}")
        if line is not None:
            props.append(f"line={int(line)}")
            if column is not None:
                props.append(f"col={int(column)}")
    if title is not None:
        props.append(f"title={escape_property(title)}")
    head = f"::{level}" + (" " + ",".join(props) if props else "")
    return f"{head}::{escape_data(message)}"


def capped(items: Sequence[Item], limit: int = GITHUB_LIMIT,
           rank: Sequence[float] | None = None) -> tuple[list[Item], list[Item]]:
    """Split ``items`` into what to annotate and what to leave out, both in the given order.

    GitHub shows at most ``limit`` annotations of each level per step and drops
    the rest silently. Past that, the ``limit`` of each level with the lowest
    ``rank`` (the worst; by default the first) are kept, and one closing notice,
    which takes one of the notices' places, says how many were left out.
    """
    order = [float(r) for r in rank] if rank is not None else [float(k) for k in
                                                                 range(len(items))]
    counts = {level: sum(1 for item in items if item[4] == level) for level in LEVELS}
    if all(n <= limit for n in counts.values()):
        return list(items), []
    keep = _worst_of_each_level(items, order, limit)
    kept = [item for k, item in enumerate(items) if k in keep]
    dropped = [item for k, item in enumerate(items) if k not in keep]
    kept.append(_left_out_notice(dropped, limit))
    return kept, dropped


def _worst_of_each_level(items: Sequence[Item], order: list[float], limit: int) -> set[int]:
    """The indices of the ``limit`` items of each level of lowest ``order`` (NaN last),
    one notice fewer: the closing notice takes its place."""
    room = {level: limit for level in LEVELS}
    room["notice"] = limit - 1  # the closing notice
    keep: set[int] = set()

    def key(k: int) -> tuple[float, int]:
        return (order[k] if order[k] == order[k] else float("inf"), k)  # NaN last

    for k in sorted(range(len(items)), key=key):
        level = items[k][4]
        if room[level] > 0:
            keep.add(k)
            room[level] -= 1
    return keep


def _left_out_notice(dropped: list[Item], limit: int) -> Item:
    """The closing notice: how many annotations of each level were left out."""
    left = ", ".join(f"{n} {level}(s)" for level in LEVELS
                     if (n := sum(1 for item in dropped if item[4] == level)))
    return (None, None, "gyrovib: more than GitHub shows",
            f"{left} more not annotated: GitHub shows at most {limit} annotations of "
            "each level per step; the worst are annotated and the rest follow in the log",
            "notice")


def _plain(item: Item) -> str:
    """A left-out annotation as a plain log line: ``level: FILE:LINE: message``."""
    file, line, title, message, level = item
    where = "" if file is None else f"{file}:{line}: " if line is not None else f"{file}: "
    head = f"{title}: " if title else ""
    return f"{level}: {where}{head}{message}".translate(_CONTROL).replace("\n", "\\n")


def annotations(items: Iterable[Item], limit: int = GITHUB_LIMIT,
                rank: Sequence[float] | None = None) -> str:
    """Annotation lines for ``(file, line, title, message, level)`` items, newline-ended.

    At most ``limit`` of each level, the worst by ``rank`` (see :func:`capped`);
    the ones left out follow as plain lines, so the log still has every one.
    """
    kept, dropped = capped(list(items), limit, rank)
    lines = [annotation(message, level=level, file=file, line=line, title=title)
             for file, line, title, message, level in kept]
    lines += [_plain(item) for item in dropped]
    return "".join(line + "\n" for line in lines)


def problems_to_github(problems: Iterable[Problem], level: str = "error",
                       title: str | None = "gyrovib", limit: int = GITHUB_LIMIT) -> str:
    """One annotation line per :class:`~gyrovib.errors.Problem` (validation errors etc.),
    in the order given: at most ``limit``, then one notice saying how many more
    there are (the plain ``FILE:LINE:COL: message`` lines on standard error list
    every problem)."""
    problems = list(problems)
    lines = [annotation(p.message, level=level, file=p.file, line=p.line, column=p.column,
                        title=title) for p in problems[:limit]]
    if len(problems) > limit:
        lines.append(annotation(
            f"{len(problems) - limit} more {level}(s) not annotated: GitHub shows at most "
            f"{limit} annotations of each level per step; every problem is listed in the log",
            level="notice", title="gyrovib: more than GitHub shows"))
    return "".join(line + "\n" for line in lines)
