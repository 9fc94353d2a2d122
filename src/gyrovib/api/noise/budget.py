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

from gyrovib.api.noise.results import Allowance, Budget

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


#: Per noise term, θ over T hours from its figure: θ = figure · T^power · factor.
_POWER = {"arw": (0.5, 1.0), "bias_instability": (1.0, 1.0),
          "rrw": (1.5, 1.0 / math.sqrt(3.0)), "repeatability": (1.0, 1.0)}


def allowance(b: Budget, theta_deg: float, seconds: float) -> Allowance:
    """The largest value of each figure that meets θ* = ``theta_deg`` over the mission's
    ``seconds``, the others as in ``b`` (an unknown figure counts as 0, so the values
    are then upper limits: :attr:`Allowance.upper`).

    With A = (θ* − |θ_V|)/k the noise allowance: a noise term X may reach
    θ_X = √(A² − Σ_{others} θ²), its figure θ_X / (T^p·f) (p, f of :data:`_POWER`);
    the vibration may reach θ* − k·√(Σ θ²). None where that is not positive.
    """
    hours = seconds / 3600.0
    k = b.coverage
    known = {name: getattr(b, name) for name in _POWER if getattr(b, name) is not None}
    values: dict[str, float | None] = {}
    limits: list[tuple[str, str]] = []
    room = (theta_deg - abs(b.vibration)) / k
    for name in _POWER:
        values[name], limit = _noise_allowance(name, room, known, hours)
        if limit is not None:
            limits.append((name, limit))
    rss = math.sqrt(sum(v * v for v in known.values()))
    vib = theta_deg - k * rss
    values["vibration"] = vib if vib > 0 else None
    if vib <= 0:
        limits.append(("vibration", max(known, key=lambda n: known[n])))
    upper = tuple(name for name in ("vibration", *_POWER)
                  if any(u != name for u in b.unknown))
    return Allowance(vibration=values["vibration"], arw=values["arw"],
                     bias_instability=values["bias_instability"], rrw=values["rrw"],
                     repeatability=values["repeatability"], limited_by=tuple(limits),
                     upper=upper)


def _noise_allowance(name: str, room: float, known: dict[str, float], hours: float
                     ) -> tuple[float | None, str | None]:
    """Noise term ``name``'s largest figure within the noise allowance ``room`` (deg, 1σ),
    the other known terms as they are; or None and the term that alone uses it."""
    power, factor = _POWER[name]
    rest = {n: v for n, v in known.items() if n != name}
    if room <= 0:
        return None, "vibration"
    left = room * room - sum(v * v for v in rest.values())
    if left <= 0:
        return None, max(rest, key=lambda n: rest[n])
    return math.sqrt(left) / (hours ** power * factor), None


def timeline(vibration_deg: list[float], durations: list[float],
             figures: dict[str, float | None], coverage: float,
             bounds: tuple[str, ...] = (), typical: tuple[str, ...] = ()
             ) -> tuple[Budget, ...]:
    """The budget at the end of each segment: θ_V(t) the vibration staircase (the
    segments' angles ``vibration_deg`` summed up to t) and the noise over t, so that
    σ(t)² = N²t + B²t² + K²t³/3 + R²t² (t in hours), the cone ±k·σ(t)."""
    out: list[Budget] = []
    angle = 0.0
    elapsed = 0.0
    for theta, seconds in zip(vibration_deg, durations, strict=True):
        angle += theta
        elapsed += seconds
        out.append(budget(angle, figures, elapsed, coverage, bounds, typical))
    return tuple(out)
