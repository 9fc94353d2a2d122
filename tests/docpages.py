"""Docs pages that show gyrovib's own output.

A ``$ gyrovib ...`` console block of a page is what that command prints at 100
columns without colour, run from the root of the tree. A block may leave lines
out: a line ``...`` stands for lines left out (the pieces between must appear in
that order, the first at the start and the last at the end), so a block ending
in ``...`` is the beginning of the output. ``tools/regenerate_docs.py PAGE``
rewrites a page's blocks from the commands.

Numbers are compared as numbers, not as text: the last digits of a least-squares fit
or a long sum are the machine's rounding (another BLAS, another summation order), so a
number matches when it is within :data:`REL_TOL` of the page's or one unit of the page's
last printed digit; the words, symbols and line breaks between numbers must be the same
(spaces, which a wider number shifts, only separate them).
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BLOCK = re.compile(r"```console\n\$ (gyrovib [^\n]*)\n(.*?)```", flags=re.S)
#: A number in printed output: an optional sign, digits with an optional point, an exponent.
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
#: Relative difference of two printed numbers that is rounding, not a change.
REL_TOL = 1e-9
TOKEN = re.compile(NUMBER.pattern + r"|\n|[^\s0-9.+-]+|\S")


def console_blocks(page: Path) -> list[tuple[str, str]]:
    """``(command, shown)`` of every console block of ``page``."""
    return [(c, shown) for c, shown in BLOCK.findall(page.read_text(encoding="utf-8"))]


def run_shown(command: str, codes: tuple[int, ...] = (0, 1)) -> str:
    """What ``command`` prints on standard output as the pages show it (100 columns,
    no colour, from the root of the tree); its exit status must be one of ``codes``."""
    env = {**os.environ, "COLUMNS": "100", "NO_COLOR": "1"}
    env.pop("FORCE_COLOR", None)
    done = subprocess.run([sys.executable, "-m", "gyrovib", *shlex.split(command)[1:]],
                          cwd=ROOT, capture_output=True, text=True, env=env, timeout=120,
                          check=False)
    assert done.returncode in codes, done.stderr
    return done.stdout


def tokens(text: str) -> list[str]:
    """``text`` as numbers, line breaks, words and single symbols (spaces, which a wider
    number shifts, separate tokens and are not tokens themselves)."""
    return TOKEN.findall(text)


def last_place(number: str) -> float:
    """One unit of the last printed digit of ``number`` (``0.0123`` -> 1e-4, ``1.5e-08`` ->
    1e-9, ``120`` -> 1)."""
    mantissa, _, exponent = number.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 10.0 ** (int(exponent or 0) - decimals)


def same_token(shown: str, out: str) -> bool:
    """Text is equal; numbers agree to :data:`REL_TOL`, or a number with a decimal point
    or an exponent to one unit of its last printed digit."""
    if shown == out:
        return True
    if not (NUMBER.fullmatch(shown) and NUMBER.fullmatch(out)):
        return False
    a, b = float(shown), float(out)
    # a whole number (a count, an index, part of a name such as k2) is not a rounded value
    rounded = any(c in shown.lower() for c in ".e")
    place = last_place(shown) * 1.000001 if rounded else 0.0
    return abs(a - b) <= max(REL_TOL * max(abs(a), abs(b)), place)


def _match_at(out: list[str], piece: list[str], at: int) -> bool:
    return (at + len(piece) <= len(out)
            and all(same_token(s, o) for s, o in zip(piece, out[at:at + len(piece)],
                                                     strict=False)))


def same_text(shown: str, out: str) -> bool:
    """``out`` is ``shown`` up to rounding of its numbers (:func:`same_token`)."""
    a, b = tokens(shown), tokens(out)
    return len(a) == len(b) and _match_at(b, a, 0)


def assert_shows(page: Path, command: str, shown: str, out: str) -> None:
    """``shown`` (a block of ``page``) is ``out``, with its ``...`` lines left out, numbers
    compared up to their rounding (:func:`same_token`)."""
    where = f"regenerate {page.name}: {command}"
    pieces = [tokens(p) for p in ("\n" + shown).split("\n...\n")]
    words = tokens(out)
    if len(pieces) == 1:
        assert same_text(shown, out), f"{where}\n--- shown\n{shown}\n--- printed\n{out}"
        return
    first, last = pieces[0][1:], pieces[-1]  # the first piece without the added line break
    assert _match_at(words, first, 0), where
    assert _match_at(words, last, len(words) - len(last)), where
    at = 0
    for piece in (tokens(p.strip("\n")) for p in ("\n" + shown).split("\n...\n")):
        found = next((i for i in range(at, len(words) - len(piece) + 1)
                      if _match_at(words, piece, i)), -1)
        assert found >= 0, f"{where}: {''.join(piece)[:80]!r}"
        at = found + len(piece)
