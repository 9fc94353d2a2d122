"""Profiles in sensor axes: a placement applied to a profile (docs/model.md section 12).

Profiles are written in vehicle axes X, Y, Z. A placement
(:class:`gyrovib.core.placement.Placement`) says which signed vehicle axis
each sensor axis x1, x2, x3 lies on; :func:`place_profile` maps every part of
a profile through it with the kernels of :mod:`gyrovib.core.placement`:

* the carrier rate Ω_K: signed (a flipped axis negates its rate);
* tones (rate and acceleration) and phase-locked orders: amplitudes move with
  their axis, phases gain 180° on a flipped axis (``phase: worst`` stays worst);
* the random part: PSD tables and RMS move with their axis; the coherences
  (ρ31, ρ32, ρ12; ρ12 omitted is ρ31·ρ32) and the acceleration's (ρ12, ρ13,
  ρ23) are the placed correlation matrix's, re-signed where exactly one axis
  of the pair is flipped;
* the mounts: unchanged (one transmissibility for every axis).

The default placement returns the profile itself, so every result is unchanged.
"""

from __future__ import annotations

from typing import Any

from gyrovib.catalog.loader import Catalog, ProfileEntry
from gyrovib.core.placement import DEFAULT, Placement
from gyrovib.models import Profile

_AXES = ("x1", "x2", "x3")


def _triple(values: Any) -> tuple[float, float, float]:
    a, b, c = (float(v) for v in values)
    return (a, b, c)


def _tone(tone: Any, placement: Placement) -> Any:
    return tone.model_copy(update={"amplitude": _triple(placement.magnitudes(tone.amplitude)),
                                   "phase": _triple(placement.phases(tone.phase))})


def _psd(psd: Any, placement: Placement) -> Any:
    return psd.model_copy(update={name: getattr(psd, _AXES[placement.source[i]])
                                  for i, name in enumerate(_AXES)})


def _random(random: Any, placement: Placement, coherence: tuple[float, ...]) -> Any:
    update: dict[str, Any] = {"coherence": coherence}
    if random.psd is not None:
        update["psd"] = _psd(random.psd, placement)
    if random.rms is not None:
        update["rms"] = _triple(placement.magnitudes(random.rms))
    return random.model_copy(update=update)


def _order(order: Any, placement: Placement) -> Any:
    update: dict[str, Any] = {"amplitude": _triple(placement.magnitudes(order.amplitude))}
    if not order.worst_phase:
        update["phase"] = _triple(placement.phases(order.phase))
    return order.model_copy(update=update)


def place_profile(profile: Profile, placement: Placement) -> Profile:
    """``profile`` (vehicle axes) in the sensor axes of ``placement`` (see the module)."""
    if placement.is_default:
        return profile
    update: dict[str, Any] = {
        "rate": _triple(placement.signed(profile.rate)),
        "harmonic": [_tone(t, placement) for t in profile.harmonic],
    }
    if profile.random is not None:
        c = profile.random.coherence
        rho = placement.rate_coherence(c[0], c[1], c[2] if len(c) > 2 else None)
        update["random"] = _random(profile.random, placement, rho)
    groups = profile.harmonic_groups
    if groups:
        update["harmonics"] = [g.model_copy(update={"orders": [_order(o, placement)
                                                               for o in g.orders]})
                               for g in groups]
    acc = profile.acceleration
    if acc is not None:
        a_update: dict[str, Any] = {"harmonic": [_tone(t, placement) for t in acc.harmonic]}
        if acc.random is not None:
            a_update["random"] = _random(acc.random, placement,
                                         placement.pair_coherence(*acc.random.coherence))
        update["acceleration"] = acc.model_copy(update=a_update)
    if profile.not_recorded:  # sensor axis x(i+1) is unknown where its vehicle axis is
        gone = set(profile.not_recorded)
        update["not_recorded"] = [
            *(f"x{i + 1}" for i, a in enumerate(placement.source) if f"x{a + 1}" in gone),
            *(["acceleration"] if "acceleration" in gone else [])]
    return profile.model_copy(update=update)


def place_catalog(catalog: Catalog, placement: Placement | None) -> Catalog:
    """``catalog`` with every profile in the sensor axes of ``placement``.

    Each placed profile keeps its file and index, so a problem found in it is
    still reported at the profile's place. ``None`` or the default placement
    return ``catalog`` itself.
    """
    if placement is None or placement == DEFAULT:
        return catalog
    profiles = tuple(ProfileEntry(e.source, e.index, place_profile(e.profile, placement))
                     for e in catalog.profiles)
    return Catalog(catalog.sources, catalog.sensors, profiles, catalog.allocation,
                   catalog.missions)
