"""A sensor's ``noise:`` block in the default units (deg/√h, deg/h, deg/h/√h, deg/h)."""

from __future__ import annotations

from gyrovib import units
from gyrovib.models.noise import WHAT, Noise

#: The figures of a noise block, in order.
FIGURES = tuple(WHAT)


def noise_values(noise: Noise | None) -> dict[str, float | None]:
    """Each figure in its default unit; None where it is not given (unknown)."""
    out: dict[str, float | None] = dict.fromkeys(FIGURES)
    if noise is None:
        return out
    for name, fig in noise.figures().items():
        if fig is not None:
            out[name] = fig.value * units.noise_factor(name, fig.unit)
    return out


def typical_figures(noise: Noise | None) -> tuple[str, ...]:
    """The figures the datasheet gives as typical (``typ``), not guaranteed, in order."""
    if noise is None:
        return ()
    given = noise.figures()
    return tuple(name for name in FIGURES
                 if (fig := given.get(name)) is not None and fig.qualifier == "typ")
