"""A sensor's ``noise:`` block in the default units (deg/√h, deg/h, deg/h/√h, deg/h)."""

from __future__ import annotations

from gyrovib import units
from gyrovib.models.noise import WHAT, Noise

#: The figures of a noise block, in order.
FIGURES = tuple(WHAT)


def noise_values(noise: Noise | None, axis: str | None = None) -> dict[str, float | None]:
    """Each figure of ``axis`` (see :meth:`Noise.for_axis`) in its default unit, a bound
    as its upper value; None where it is not given (unknown)."""
    out: dict[str, float | None] = dict.fromkeys(FIGURES)
    if noise is None:
        return out
    for name, fig in noise.for_axis(axis).items():
        if fig is not None:
            out[name] = fig.upper * units.noise_factor(name, fig.unit)
    return out


def noise_bounds(noise: Noise | None, axis: str | None = None) -> tuple[str, ...]:
    """The figures of ``axis`` given only as upper bounds."""
    if noise is None:
        return ()
    return tuple(name for name, fig in noise.for_axis(axis).items()
                 if fig is not None and fig.is_bound)


def typical_figures(noise: Noise | None, axis: str | None = None) -> tuple[str, ...]:
    """The figures of ``axis`` the datasheet gives as typical (``typ``), not guaranteed."""
    if noise is None:
        return ()
    return tuple(name for name, fig in noise.for_axis(axis).items()
                 if fig is not None and fig.qualifier == "typ")
