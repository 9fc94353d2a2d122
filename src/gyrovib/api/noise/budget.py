"""The angle budget of a mission (docs/model.md section 15).

Over a mission of T hours, for a sensor with angle random walk N (deg/√h), bias
instability B (deg/h), rate random walk K (deg/h/√h) and bias repeatability R
(deg/h)::

    θ_ARW = N·√T,  θ_B = B·T,  θ_RRW = K·T^{3/2}/√3,  θ_R = R·T,
    total = |θ_V| + k·√(θ_ARW² + θ_B² + θ_RRW² + θ_R²)

θ_V is the vibration angle (deterministic, added in full); the noise terms are 1σ
and combine in quadrature; k is the coverage factor. A figure not given is unknown:
its term is None and the total is a lower bound. The RSS is taken scaled
(``math.hypot``), so terms whose squares would overflow still give their finite total;
a term or total past double precision is inf, and the mission refuses it.
"""

from __future__ import annotations

import math

from gyrovib.api.noise.results import Budget

#: Each figure and its budget term.
TERM_OF = {"arw": "arw", "bias_instability": "bias_instability", "rrw": "rrw",
           "bias_repeatability": "repeatability"}


def noise_angles(figures: dict[str, float | None], hours: float) -> dict[str, float | None]:
    """Each noise term over ``hours`` in deg (None where its figure is unknown)."""
    # T^{3/2} as T·√T: a product past double precision is inf, where ** raises
    rules = {"arw": lambda v: v * math.sqrt(hours),
             "bias_instability": lambda v: v * hours,
             "rrw": lambda v: v * (hours / math.sqrt(3.0)) * math.sqrt(hours),
             "bias_repeatability": lambda v: v * hours}
    return {TERM_OF[name]: None if figures.get(name) is None else rules[name](figures[name])
            for name in rules}


def budget(vibration_deg: float, figures: dict[str, float | None], seconds: float,
           coverage: float = 1.0, bounds: tuple[str, ...] = (),
           typical: tuple[str, ...] = ()) -> Budget:
    """The budget of one row: θ_V in deg, the figures in their default units (a bound's
    upper value for the figures named in ``bounds``), the mission's duration in s,
    coverage k (> 0); ``typical``: the figures given as ``typ``."""
    angles = noise_angles(figures, seconds / 3600.0)
    known = [a for a in angles.values() if a is not None]
    rss = math.hypot(*known)  # scaled before squaring: no overflow of a finite RSS
    unknown = tuple(name for name, a in angles.items() if a is None)
    return Budget(vibration=vibration_deg, arw=angles["arw"],
                  bias_instability=angles["bias_instability"], rrw=angles["rrw"],
                  repeatability=angles["repeatability"],
                  total=abs(vibration_deg) + coverage * rss, coverage=coverage,
                  unknown=unknown, bounds=tuple(TERM_OF[name] for name in bounds),
                  typical=tuple(TERM_OF[n] for n in typical))
