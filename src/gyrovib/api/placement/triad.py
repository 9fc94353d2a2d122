"""A command under a placement, or under the three placements of a triad (docs/model.md §12).

:func:`placed` runs ``analyze``, ``bounds``, ``select`` or ``sweep`` on the
catalogue's profiles mapped into the sensor axes of a placement
(:func:`gyrovib.api.placement.placement.place_catalog`). Under the triad it runs the
command three times, x3 on +X, +Y and +Z, and returns a :class:`TriadResult`:
the three results and, per sensor (per profile and coefficient for
``bounds``), the worst axis. An IMU has one sensor per axis, so a part passes
``select`` only where it passes on every axis.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from gyrovib.api.placement.placement import place_catalog
from gyrovib.catalog.loader import Catalog
from gyrovib.core.placement import Placement
from gyrovib.core.synthesis import BOUNDED
from gyrovib.frozen import Frozen


@dataclass(frozen=True, eq=False, repr=False)
class TriadResult(Frozen):
    """A command's result per axis of the triad.

    ``axes``: ("X", "Y", "Z"), the vehicle axis of the sensitive axis x3;
    ``placements``: each as text (``x1=+Y,x2=+Z,x3=+X``); ``results``: the
    command's result per axis; ``worst_axis``: per sensor id the axis of the
    largest error (analyze, sweep) or of the failure / smallest margin
    (select), and for bounds per profile id a mapping coefficient → axis of the
    smallest bound; ``requirement_met``: select's --require over the sensors
    that pass on all three axes (True for the other commands).
    """

    axes: tuple[str, ...]
    placements: tuple[str, ...]
    results: tuple[Any, ...]
    worst_axis: Mapping[str, Any]
    requirement_met: bool = True


def placed(command: Callable[..., Any], catalog: Catalog,
           placement: Placement | tuple[Placement, ...] | None, **options: Any) -> Any:
    """``command(catalog, **options)`` in the sensor axes of ``placement``; a
    :class:`TriadResult` when ``placement`` is the triad (a tuple)."""
    if not isinstance(placement, tuple):
        return command(place_catalog(catalog, placement), **options)
    results = tuple(command(place_catalog(catalog, p), **options) for p in placement)
    axes = tuple(p.axis for p in placement)
    worst, met = _worst(results, axes)
    return TriadResult(axes=axes, placements=tuple(str(p) for p in placement),
                       results=results, worst_axis=worst, requirement_met=met)


def _worst(results: tuple[Any, ...], axes: tuple[str, ...]) -> tuple[dict[str, Any], bool]:
    first = results[0]
    name = type(first).__name__
    if name == "BoundsResult":
        stacked = np.stack([r.bounds.stacked() for r in results])   # (3, P, 7)
        out: dict[str, Any] = {}
        for j, profile in enumerate(first.profiles):
            out[profile] = {c: axes[int(np.argmin(stacked[:, j, k]))]
                            for k, c in enumerate(BOUNDED)}
        return out, True
    if name == "SelectionResult":
        passes = np.stack([np.asarray(r.sensor_pass, dtype=bool) for r in results])  # (3, N)
        margin = np.stack([np.asarray(r.worst_margin, dtype=float) for r in results])
        worst = {}
        for i, sensor in enumerate(first.sensors):
            key = [(bool(passes[a, i]), float(np.nan_to_num(margin[a, i], nan=-np.inf)))
                   for a in range(len(axes))]
            worst[sensor] = axes[min(range(len(axes)), key=lambda a: key[a])]
        every = passes.all(axis=0)
        met = bool(every.all()) if first.require == "all" else bool(every.any())
        return worst, met
    totals = [np.abs(np.asarray(r.exact.total if name == "SweepResult" else r.error.total,
                                dtype=float)) for r in results]
    peak = np.stack([np.nanmax(t.reshape(t.shape[0], -1), axis=1, initial=0.0)
                     for t in totals])                             # (3, N)
    return {s: axes[int(np.argmax(peak[:, i]))] for i, s in enumerate(first.sensors)}, True
