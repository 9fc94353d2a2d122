"""``--placement`` on analyze, bounds, select and sweep: one library call in the sensor
axes of a placement, or the three of a triad written as one document."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from gyrovib.cli.options import parse_placement
from gyrovib.cli.output import write_output
from gyrovib.errors import OptionError


def run_placed(command: Callable[..., Any], catalog: Any, placement: str | None, fmt: str,
               **options: Any) -> Any:
    """``command(catalog, **options)`` under ``--placement`` (a TriadResult for triad)."""
    parsed = parse_placement(placement)
    if parsed is None:
        return command(catalog, **options)
    # lazy: --placement only; a first analyze does without it
    from gyrovib.api.placement.triad import placed
    from gyrovib.render.triad import TRIAD_FORMATS

    if isinstance(parsed, tuple) and fmt not in TRIAD_FORMATS:
        raise OptionError(f"--placement triad: use --format {', '.join(TRIAD_FORMATS)} "
                          f"(not {fmt})")
    return placed(command, catalog, parsed, **options)


def is_triad(result: Any) -> bool:
    return type(result).__name__ == "TriadResult"


def write_triad(result: Any, draw: Callable[[Any], Any], fmt: str,
                output: str | None) -> None:
    """The triad's document; ``draw`` renders one axis's result in ``fmt`` (text, or
    pieces of text that are joined)."""
    # lazy: --placement only; a first analyze does without it
    from gyrovib.render.triad import render

    def text(one: Any) -> str:
        out = draw(one)
        return out if isinstance(out, str) else "".join(out)

    write_output(render(result, text, fmt), output)
