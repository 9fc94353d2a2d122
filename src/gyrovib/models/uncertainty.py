"""The uncertainty of a sensor's coefficients, and a production lot (docs/model.md section 14).

``uncertainty`` sits beside ``coefficients``: the standard uncertainty σ of
each eq. (2) coefficient and the correlations of pairs, written
``{"A1 k2": 0.3}`` (pairs not named are 0). A ``lot`` is a part as drawn from
production: the mean of its units' coefficients, their standard deviations
and correlations, and how many units were measured. Values are in the file's
rate unit, as the coefficients are.

The correlations must describe a distribution: each in [−1, 1], a pair of
two different coefficients that both have a σ, given once, and together a
positive semi-definite matrix. k1 is 1 in eq. (2): it has no uncertainty.
"""

from typing import Annotated, Any

import numpy as np
from pydantic import Field, Strict, model_validator

from gyrovib.coefficients import UNCERTAIN as UNCERTAIN
from gyrovib.models._types import AsInteger, Model, Number, Text, raise_at, rule_error

#: A correlation matrix whose smallest eigenvalue is below −this has no distribution
#: (gyrovib.core.lot.PSD_TOLERANCE: the same test).
PSD_TOLERANCE = 1e-8

Sigma = Annotated[Number, Field(ge=0)] | None


def _sigma(name: str) -> Any:
    return Field(None, description=f"Standard uncertainty of {name}, in {name}'s unit; >= 0.",
                 json_schema_extra={"unit": "rate"})


class Sigmas(Model):
    """Standard uncertainties σ of eq. (2) coefficients (k = 1), in their units."""

    k0: Sigma = _sigma("k0")
    A1: Sigma = _sigma("A1")
    k2: Sigma = _sigma("k2")
    k3: Sigma = _sigma("k3")
    k4: Sigma = _sigma("k4")
    k5: Sigma = _sigma("k5")
    m1: Sigma = _sigma("m1")
    m2: Sigma = _sigma("m2")
    m31: Sigma = _sigma("m31")
    m32: Sigma = _sigma("m32")

    def named(self) -> dict[str, float]:
        """The σ given, by coefficient name, in the order of :data:`UNCERTAIN`."""
        return {n: float(v) for n in UNCERTAIN if (v := getattr(self, n)) is not None}


Correlation = Annotated[Number, Field(ge=-1, le=1)]
#: The text of a pair: two coefficient names separated by one space.
PAIR_PATTERN = r"^[A-Za-z0-9]+ [A-Za-z0-9]+$"


def _correlation_field() -> Any:
    return Field(
        {}, description="Correlations of pairs of coefficients, {'A1 k2': 0.3}: each in "
        "[-1, 1], both coefficients with a sigma; pairs not named are 0; together positive "
        "semi-definite.",
        json_schema_extra={"propertyNames": {"pattern": PAIR_PATTERN}})


def pair_problems(names: list[str], pairs: dict[str, float]) -> tuple[str, str] | None:
    """The first pair of ``pairs`` that is not a pair of two different coefficients of
    ``names`` given once: ``(key, message)``; None when every pair is one."""
    seen: dict[frozenset[str], str] = {}
    for key in pairs:
        parts = key.split(" ")
        if len(parts) != 2 or not all(parts):
            return key, (f"correlation {key!r}: name two coefficients separated by one "
                         "space, e.g. 'A1 k2'")
        unknown = [p for p in parts if p not in UNCERTAIN]
        if unknown:
            return key, (f"correlation {key!r}: {unknown[0]!r} is not a coefficient with an "
                         f"uncertainty; use {', '.join(UNCERTAIN)}")
        if parts[0] == parts[1]:
            return key, (f"correlation {key!r}: a coefficient's correlation with itself is 1; "
                         "name two different coefficients")
        missing = [p for p in parts if p not in names]
        if missing:
            return key, (f"correlation {key!r}: {missing[0]} has no sigma; give its sigma "
                         "or remove the pair")
        both = frozenset(parts)
        if both in seen:
            return key, f"correlation {key!r}: the pair is given twice (also as {seen[both]!r})"
        seen[both] = key
    return None


def smallest_eigenvalue(names: list[str], pairs: dict[str, float]) -> float:
    """The smallest eigenvalue of the correlation matrix of ``names`` (identity plus pairs)."""
    index = {n: i for i, n in enumerate(names)}
    r = np.eye(len(names))
    for key, value in pairs.items():
        a, b = key.split(" ")
        r[index[a], index[b]] = r[index[b], index[a]] = value
    return float(np.linalg.eigvalsh(r)[0]) if names else 1.0


class Uncertainty(Model):
    """Standard uncertainties and correlations of the coefficients (docs/model.md section 14)."""

    sigma: Sigmas = Field(description="Standard uncertainty of each coefficient (k = 1), in "
                          "its unit; coefficients not named are exact.")
    correlation: dict[Text, Correlation] = _correlation_field()

    @model_validator(mode="after")
    def _distribution(self) -> "Uncertainty":
        names = list(self.sigma.named())
        problem = pair_problems(names, self.correlation)
        if problem is not None:
            raise_at(("correlation", problem[0]), rule_error(problem[1]),
                     self.correlation[problem[0]], type(self).__name__)
        if not self.correlation:
            return self
        smallest = smallest_eigenvalue(names, self.correlation)
        if smallest < -PSD_TOLERANCE:
            raise_at(("correlation",), rule_error(
                f"the correlations of {', '.join(names)} are not consistent: the matrix is "
                f"not positive semi-definite (smallest eigenvalue {smallest:.3g}), no "
                "distribution has them"), self.correlation, type(self).__name__)
        return self


class LotSpread(Uncertainty):
    """A lot's spread: the standard deviations and correlations of the coefficients of
    ``units`` measured units (its mean is added by :class:`gyrovib.models.sensor.Lot`).
    With units ≤ the number of coefficients with a sigma, only the standard deviations
    are used (the sample covariance is singular)."""

    units: Annotated[int, Strict(), Field(ge=2), AsInteger] = Field(
        description="Number of units measured; >= 2.")
    sigma: Sigmas = Field(description="Standard deviation of each coefficient over the "
                          "units (n - 1), in its unit; coefficients not named do not vary.")
    correlation: dict[Text, Correlation] = _correlation_field()
