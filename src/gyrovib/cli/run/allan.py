"""The body of `gyrovib allan` (declared in :mod:`gyrovib.cli.allan`)."""

from __future__ import annotations

from typing import Any

from gyrovib.api.noise import allan as run
from gyrovib.api.noise import noise_yaml
from gyrovib.cli.common import page_width, plain_ascii, say, use_color
from gyrovib.cli.output import write_binary, write_output
from gyrovib.cli.run.recording import read
from gyrovib.errors import OptionError
from gyrovib.render import allan as render
from gyrovib.render.kalibr import to_kalibr


def parse_confidence(text: str) -> float:
    """``68%``, ``68`` or ``0.68`` → 0.68."""
    raw = text.strip()
    try:
        value = float(raw.rstrip("%").strip())
    except ValueError:
        raise OptionError(f"--confidence {text!r}: give a level such as 68% or 0.95") from None
    if raw.endswith("%") or value > 1.0:
        value /= 100.0
    if not 0.0 < value < 1.0:
        raise OptionError(f"--confidence {text!r}: give a level between 0 and 100 %")
    return value


def allan(recording: str, unit: str, per_decade: int | None, plot: str | None, output: str | None,
          confidence: str, fmt: str, **options: Any) -> None:
    """See :func:`gyrovib.cli.allan.allan`."""

    result = run(read(recording, options), unit=unit, per_decade=per_decade,
                 confidence=parse_confidence(confidence))
    for warning in result.warnings:  # a log's damage, said as profile says it; the fit's
        say(f"gyrovib: warning: {warning}")
    if plot is not None:
        write_binary(render.plot(result), plot)
    if output is not None:
        write_output(noise_yaml(result), output)
        if output == "-":
            return
    if fmt == "json":
        text = render.to_json(result)
    elif fmt == "kalibr":
        text = to_kalibr(result)
    else:
        text = render.to_table(result, color=use_color(), width=page_width(),
                               ascii=plain_ascii())
    write_output(text, None)
