"""Linear vibration of a profile and the sensors' g²-sensitivities, in g (docs/model.md section 8).

The catalogue gives a profile's ``acceleration:`` block in its file's
``units.acceleration`` (g or m/s²) and a sensor's ``g2_sensitivity`` / ``vre``
per g² (a bare number, in the file's rate unit) or with its own unit
(:func:`gyrovib.api.study.convert.g2_value`). Here they become what the engines
take: a :class:`~gyrovib.core.linear.LinearVibration` in g at the sensor's
axes, and G_jk in deg/s per g².

The linear vibration passes the profile's mount (the block's own ``mount`` if
it has one, else the profile's): a tone's amplitude is scaled by ν(f), a PSD
by ν(f)² and integrated exactly on log-log axes, as for rate PSDs
(:func:`~gyrovib.core.transmissibility.psd_variance`); an ``rms`` is the value
at the sensor. The sensor's own response never applies: the rectification
happens in the sensing element (docs/model.md section 8).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from gyrovib import units
from gyrovib.api.study.convert import g2_value
from gyrovib.catalog.loader import ProfileEntry, SensorEntry
from gyrovib.core._types import FloatArray, Table
from gyrovib.core.linear import LinearVibration, linear_vibration
from gyrovib.core.transmissibility import as_table, loglog_interp, psd_variance

_AXES = ("x1", "x2", "x3")


def acceleration_mount(entry: ProfileEntry) -> Table | None:
    """ν(f) of the linear vibration: the block's ``mount``, else the profile's, else None."""
    block = entry.profile.acceleration
    table = None if block is None else block.mount
    if table is None:
        table = entry.profile.mount
    return None if table is None else as_table(table)


def profile_linear(entry: ProfileEntry) -> LinearVibration | None:
    """The profile's linear vibration at the sensor's axes in g, or None if it has none.

    Tones of one frequency add as phasors (as rate tones do), so the tones
    handed on have distinct frequencies, which docs/model.md section 8 assumes.
    """
    block = entry.profile.acceleration
    if block is None:
        return None
    to_g = units.acceleration(entry.acceleration_unit)
    mount = acceleration_mount(entry)
    gains = () if mount is None else (mount,)
    merged: dict[float, FloatArray] = {}
    for tone in block.harmonic:
        nu = 1.0 if mount is None else float(loglog_interp(mount, tone.frequency))
        phasor = (np.asarray(tone.amplitude, dtype=float) * to_g * nu
                  * np.exp(1j * np.deg2rad(np.asarray(tone.phase, dtype=float))))
        key = float(tone.frequency)
        merged[key] = merged.get(key, np.zeros(3, complex)) + phasor
    p = np.array([merged[k] for k in sorted(merged)], dtype=complex).reshape(-1, 3)
    sigma = np.zeros(3)
    coherence = (0.0, 0.0, 0.0)
    random = block.random
    if random is not None:
        coherence = random.coherence
        if random.psd is not None:
            for k, axis in enumerate(_AXES):
                table = getattr(random.psd, axis)
                if table is not None:
                    freq, level = as_table(table)
                    sigma[k] = math.sqrt(psd_variance((freq, level * to_g * to_g), gains))
        elif random.rms is not None:
            sigma = np.asarray(random.rms, dtype=float) * to_g
    return linear_vibration(np.abs(p), np.rad2deg(np.angle(p)), sigma, coherence)


def g2_matrix(entries: Sequence[SensorEntry]) -> FloatArray:
    """G_jk of every sensor in deg/s per g², shape (sensors, 6), order G11, G22, G33, G12, G13, G23.

    A sensor gives G per g² in its file's rate unit (a bare number), or with its
    own unit (:func:`gyrovib.api.study.convert.g2_value`). Zero where a sensor gives none.
    """
    out: FloatArray = np.array([[g2_value(g, e.unit) for g in e.sensor.g2] for e in entries],
                               dtype=float).reshape(len(entries), 6)
    return out
