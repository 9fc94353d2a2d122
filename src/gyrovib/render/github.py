"""GitHub Actions workflow commands: ``::error file=…,line=…::message`` annotations.

Pure functions, no I/O. A workflow step that prints these lines on standard
output gets them shown as annotations on the files and lines they name.

Escaping follows the runner's rules: in the message (the "data") ``%``,
``\\r`` and ``\\n`` are percent-encoded; in a property value (file, title, …)
``:`` and ``,`` are encoded as well, since they separate properties.
"""

from collections.abc import Iterable

from gyrovib.errors import Problem

LEVELS = ("error", "warning", "notice")

#: One annotation: (file, line, title, message, level); file, line and title may be None.
Item = tuple[str | None, int | None, str | None, str, str]


def escape_data(text: str) -> str:
    """Escape a workflow command's message."""
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


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


def annotations(items: Iterable[Item]) -> str:
    """Annotation lines for ``(file, line, title, message, level)`` items, newline-ended."""
    lines = [annotation(message, level=level, file=file, line=line, title=title)
             for file, line, title, message, level in items]
    return "".join(line + "\n" for line in lines)


def problems_to_github(problems: Iterable[Problem], level: str = "error",
                       title: str | None = "gyrovib") -> str:
    """One annotation line per :class:`~gyrovib.errors.Problem` (validation errors etc.)."""
    return "".join(
        annotation(p.message, level=level, file=p.file, line=p.line, column=p.column,
                   title=title) + "\n"
        for p in problems
    )
