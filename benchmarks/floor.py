"""The start-up floor of ``gyrovib analyze``: a minimal program of the same stack and
shape, to compare gyrovib's start-up against (benchmarks/bench_floor.py).

What any program built like gyrovib pays before it does anything of its own: a
click command; the catalogue files read with PyYAML's ``CSafeLoader``; a dozen
pydantic models validating them (every section gyrovib reads, the rest allowed
through); numpy for the arithmetic of sensors × profiles; one rich table.
Nothing of gyrovib is imported. The numbers it prints are a rough second-moment
product, not gyrovib's model: they exist so that the work is done, not to be read.

    python benchmarks/floor.py [FILE ...] [--sensor ID ...]

Without FILE it reads the catalogues bundled with gyrovib (found on disk beside
this file, as ``src/gyrovib/catalogs``), as ``gyrovib analyze`` does.
"""

from __future__ import annotations

import os
from typing import Any

import click
import numpy as np
import yaml
from pydantic import BaseModel, ConfigDict, Field
from rich.console import Console
from rich.table import Table

BUNDLED = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "src",
                       "gyrovib", "catalogs")
Triple = tuple[float, float, float]


class Model(BaseModel):
    """Keys this floor does not read are allowed through (gyrovib checks each)."""

    model_config = ConfigDict(extra="allow", frozen=True)


class Units(Model):
    rate: str = "deg/s"
    acceleration: str = "g"


class Nonlinearity(Model):
    value: float = Field(ge=0)
    unit: str
    fit: str = "least-squares"
    measure: str = "max"


class Specs(Model):
    range: float = Field(gt=0)
    nonlinearity: Nonlinearity
    vre: float | None = None


class Response(Model):
    at: str = "output"
    table: list[tuple[float, float]] = []


class Coefficients(Model):
    A1: float = 0.0
    k2: float = 0.0
    k3: float = 0.0
    k4: float = 0.0
    k5: float = 0.0
    m31: float = 0.0
    m32: float = 0.0


class OutputCoefficients(Model):
    unit: str
    K1: float
    K2: float = 0.0


class Sensor(Model):
    id: str = Field(pattern=r"^[A-Za-z0-9._-]+$")
    name: str = ""
    range: float | None = None
    specs: Specs | None = None
    coefficients: Coefficients | None = None
    output_coefficients: OutputCoefficients | None = None
    response: Response | None = None


class Tone(Model):
    frequency: float = Field(gt=0)
    amplitude: Triple
    phase: Triple = (0.0, 0.0, 0.0)


class Random(Model):
    psd: dict[str, list[tuple[float, float]]] | None = None
    rms: Triple | None = None


class Profile(Model):
    id: str = Field(pattern=r"^[A-Za-z0-9._-]+$")
    name: str = ""
    rate: Triple = (0.0, 0.0, 0.0)
    harmonic: list[Tone] = []
    random: Random | None = None
    mount: list[tuple[float, float]] = []


class Segment(Model):
    profile: str
    duration: float | str
    rate: Triple = (0.0, 0.0, 0.0)


class Mission(Model):
    id: str
    segments: list[Segment]


class Catalogue(Model):
    gyrovib: int
    units: Units = Units()
    sensors: list[Sensor] = []
    profiles: list[Profile] = []
    missions: list[Mission] = []


def load(paths: list[str]) -> list[Catalogue]:
    out = []
    for path in paths:
        with open(path, "rb") as handle:
            out.append(Catalogue.model_validate(yaml.load(handle, Loader=yaml.CSafeLoader)))
    return out


def second_moment(profile: Profile) -> float:
    """⟨x3²⟩ of the tones and the random part on the sensor axis."""
    tones = np.array([t.amplitude[2] for t in profile.harmonic], dtype=float)
    total = float(np.sum(tones**2) / 2.0)
    random = profile.random
    if random is not None and random.psd and "x3" in random.psd:
        f, g = np.array(random.psd["x3"], dtype=float).T
        total += float(np.trapezoid(g, f))
    elif random is not None and random.rms is not None:
        total += random.rms[2] ** 2
    return total


def coefficients(sensor: Sensor) -> Any:
    """(A1, k2) of a coefficient sensor; a datasheet sensor's from its nonlinearity."""
    if sensor.coefficients is not None:
        return np.array([sensor.coefficients.A1, sensor.coefficients.k2])
    if sensor.output_coefficients is not None:
        return np.array([0.0, sensor.output_coefficients.K2 / sensor.output_coefficients.K1])
    assert sensor.specs is not None
    return np.array([0.0, sensor.specs.nonlinearity.value / 100.0 / sensor.specs.range])


@click.command()
@click.argument("files", nargs=-1, type=click.Path(dir_okay=False))
@click.option("--sensor", "sensors", multiple=True, metavar="ID", help="Only this sensor.")
def main(files: tuple[str, ...], sensors: tuple[str, ...]) -> None:
    """A table of sensors × profiles from catalogue files."""
    paths = list(files) or sorted(os.path.join(BUNDLED, name) for name in os.listdir(BUNDLED)
                                  if name.endswith((".yaml", ".yml")))
    catalogues = load(paths)
    chosen = [s for c in catalogues for s in c.sensors if not sensors or s.id in sensors]
    profiles = [p for c in catalogues for p in c.profiles]
    m2 = np.array([second_moment(p) for p in profiles])
    rates = np.array([p.rate[2] for p in profiles])
    c = np.array([coefficients(s) for s in chosen]).reshape(-1, 2)
    error = 0.5 * np.abs(c[:, :1]) * np.sqrt(m2)[None, :] + c[:, 1:] * (m2 + rates**2)[None, :]
    table = Table(title="second-moment product (deg/s)", header_style="bold")
    table.add_column("profile", no_wrap=True)
    for s in chosen:
        table.add_column(s.id, justify="right")
    for j, p in enumerate(profiles):
        table.add_row(p.id, *(f"{v:.4g}" for v in error[:, j]))
    Console().print(table)


if __name__ == "__main__":
    main()
