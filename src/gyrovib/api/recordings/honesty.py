"""The honesty warnings of ``analyze --recording`` (docs/model.md section 13): where the
closed form of the fitted profile and the recorded error Δ_V,rec disagree by more than
:data:`RATIO_RANGE`, where the recording saturates a sensor, and where Δ_V,rec is unknown."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from gyrovib.api.evaluation.unknown import words
from gyrovib.api.recordings.results import RecordingFit
from gyrovib.api.recordings.yaml import mission_id
from gyrovib.core._types import FloatArray
from gyrovib.errors import Note

#: The fitted mission's closed form and Δ_V,rec should agree within this range.
RATIO_RANGE = (0.8, 1.25)


def unknown_warnings(unknown: Sequence[tuple[str, ...]],
                     warnings: dict[int, tuple[str, ...]]) -> dict[int, tuple[str, ...]]:
    """``warnings`` with, first on each row whose Δ_V,rec is unknown, the parts it lacks."""
    for i, parts in enumerate(unknown):
        if parts:
            warnings[i] = (f"Δ_V,rec unknown: {words(parts)}, and this sensor's error "
                           "depends on it (an axis not recorded is unknown, never 0)",
                           *warnings.get(i, ()))
    return warnings


def g2_warnings(rows: Sequence[int], spec: NDArray[np.bool_],
                warnings: dict[int, tuple[str, ...]]) -> None:
    """First on each row of ``rows`` (:func:`~gyrovib.api.recordings.analysis.g2_not_given`),
    why its Δ_V,rec is unknown: the recording's accelerations meet a g² figure not given."""
    for i in rows:
        what = ("the datasheet publishes no VRE" if spec[i] else
                "the sensor gives no g² sensitivity (g2_sensitivity or vre; write `vre: 0` "
                "for a known zero)")
        warnings[i] = (f"Δ_V,rec unknown: {what}, and the recording holds the accelerations "
                       "of a linear vibration, so its g² term is unknown, not zero",
                       *warnings.get(i, ()))


def ratio_warnings(fit: RecordingFit, ratio: FloatArray, saturated: NDArray[np.bool_],
              peak: FloatArray, ranges: FloatArray, unit: str) -> dict[int, tuple[str, ...]]:
    """Per sensor row the warnings of ``analyze --recording`` (peak and range in ``unit``)."""
    warnings: dict[int, tuple[str, ...]] = {}
    lo, hi = RATIO_RANGE
    for i in range(ratio.size):
        w: list[str] = []
        if np.isfinite(ratio[i]) and not lo <= ratio[i] <= hi:
            worst = (" (the fitted harmonics take their worst relative phases, so the closed "
                     "form is a bound over phases the recording does not show: "
                     "{independent_tones} compares like with like)"
                     if fit.angular.harmonics else "")
            w.append(Note(f"the fitted profile's closed form is {ratio[i]:.3g} × Δ_V,rec, "
                          f"outside [{lo}, {hi}]: the recording is not Gaussian-plus-tones or "
                          f"not stationary, and Δ_V,rec is the number to trust{worst}",
                          ("independent_tones", True)))
        if saturated[i]:
            w.append(f"max |ω3| = {peak[i]:.6g} {unit} on the recording exceeds the "
                     f"sensor's range {ranges[i]:.6g} {unit}: the static model does not "
                     "hold in saturation")
        if w:
            warnings[i] = tuple(w)
    return warnings


def at_mean_warnings(fit: RecordingFit, ratio: FloatArray,
                      warnings: dict[int, tuple[str, ...]]) -> None:
    """Add to ``warnings`` each sensor whose fitted profile at its mean rate and the
    recording disagree by more than :data:`RATIO_RANGE` (its ratio ``ratio``)."""
    lo, hi = RATIO_RANGE
    rate = ", ".join(f"{v:.4g}" for v in np.asarray(fit.rate, dtype=float).tolist())
    for i in range(ratio.size):
        if np.isfinite(ratio[i]) and not lo <= ratio[i] <= hi:
            warnings[i] = (*warnings.get(i, ()), (
                f"the fitted profile {fit.profile_id!r} at its mean rate Ω_K = [{rate}] deg/s "
                f"is {ratio[i]:.3g} × Δ_V,rec, outside [{lo}, {hi}]: one mean rate hides "
                f"the carrier's spread; judge with the fitted mission "
                f"{mission_id(fit)!r}, which keeps it"))
