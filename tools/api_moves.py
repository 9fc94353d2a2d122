"""Rewrite imports of the flat ``gyrovib.api`` modules to their rooms.

The library's modules moved into domain packages (docs/architecture.md, "The
rooms of api"); ``gyrovib.api``'s own names did not move. Code that imported a
module by its old path (``from gyrovib.api.prepare import float_guard``) is
rewritten in place:

    python tools/api_moves.py FILE...            # rewrite, print what changed
    python tools/api_moves.py --check FILE...    # exit 1 if any would change

Only dotted module paths and ``from gyrovib.api import <module>`` are
rewritten; names imported from ``gyrovib.api`` itself are left alone. Run it
once, on code of the old layout: ``gyrovib.api.study`` was a module and is now
a package, so a second run would take ``gyrovib.api.study`` for the old module.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

#: Old module of gyrovib.api -> its module now (absolute).
MOVES: dict[str, str] = {
    "entries": "gyrovib.api.study.entries",
    "convert": "gyrovib.api.study.convert",
    "linear": "gyrovib.api.study.linear",
    "prepare": "gyrovib.api.study.prepare",
    "study": "gyrovib.api.study.study",
    "specs": "gyrovib.api.datasheet.specs",
    "spec_bounds": "gyrovib.api.datasheet.spec_bounds",
    "evaluate": "gyrovib.api.evaluation.evaluate",
    "results": "gyrovib.api.evaluation.results",
    "placement": "gyrovib.api.placement.placement",
    "triad": "gyrovib.api.placement.triad",
    "trade_study": "gyrovib.api.report.views",
    "frames": "gyrovib.presentation.frames",
    "reasons": "gyrovib.presentation.reasons",
}

#: An old path, or an import of old modules from the face; a path already in a room
#: (``gyrovib.api.study.prepare``, ``gyrovib.api.placement.triad``) is left alone.
_OLD = re.compile(
    r"(?m)^(?P<indent>[ \t]*)from gyrovib\.api import (?P<names>\w+(?: as \w+)?"
    r"(?:, \w+(?: as \w+)?)*)[ \t]*$"
    r"|gyrovib\.api\.(?P<module>\w+)"
    r"(?!\w|\.(?:entries|convert|linear|prepare|study|placement|triad)\b)")


def _new(match: re.Match[str]) -> str:
    module = match.group("module")
    if module is not None:
        return MOVES.get(module, match.group(0))
    names = [n.strip() for n in match.group("names").split(",")]
    if not all(n.split(" as ")[0] in MOVES for n in names):
        return match.group(0)  # names of the face (or a mix): left alone
    lines = []
    for name in names:
        old, _, alias = name.partition(" as ")
        package, _, module = MOVES[old].rpartition(".")
        lines.append(f"from {package} import {module}" + (f" as {alias}" if alias else ""))
    return match.group("indent") + ("\n" + match.group("indent")).join(lines)


def rewrite(text: str) -> str:
    """``text`` with every old module path of gyrovib.api replaced by the new one, in
    one pass (a path already rewritten is not rewritten again)."""
    return _OLD.sub(_new, text)


def main(argv: list[str]) -> int:
    check = "--check" in argv
    changed = []
    for name in (a for a in argv if a != "--check"):
        path = Path(name)
        text = path.read_text(encoding="utf-8")
        new = rewrite(text)
        if new != text:
            changed.append(name)
            if not check:
                path.write_text(new, encoding="utf-8")
    for name in changed:
        print(("would rewrite " if check else "rewrote ") + name)
    return 1 if check and changed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
