"""The catalogue ``gyrovib fit -o`` writes (docs/model.md section 14): one coefficient-form
sensor per unit with its uncertainty and, with two or more units, the lot; built beside the
fit as the recordings' fitted profile is, with the one catalogue writer
(:mod:`gyrovib.catalog.writer`)."""

from __future__ import annotations

from gyrovib._version import __version__
from gyrovib.api.ratetable.results import FitResult, lot_mapping, lot_name, output_unit, pairs
from gyrovib.catalog.writer import CORRELATION_PLACES, flow_mapping, number, quantum_of
from gyrovib.formatting import fmt


def _flow(mapping: dict[str, float], sigma: dict[str, float] | None = None) -> str:
    """``{k: v, ...}``; values to the place their ``sigma`` supports, or σ itself to
    :data:`SIGMA_DIGITS` significant digits when ``sigma`` is None."""
    def written(k: str, v: float) -> str:
        quantum = quantum_of(sigma[k] if sigma is not None else v)
        return number(v, quantum=quantum)

    return flow_mapping({k: written(k, v) for k, v in mapping.items()})


def _block(mapping: dict[str, float], indent: str) -> list[str]:
    """Correlation pairs, one a line, to :data:`CORRELATION_PLACES` decimal places."""
    if not mapping:
        return [" {}"]
    quantum = 10.0 ** -CORRELATION_PLACES
    return [""] + [f"{indent}{k}: {number(v, quantum=quantum)}" for k, v in mapping.items()]


def fit_catalog(result: FitResult) -> str:
    """The catalogue ``-o`` writes (docs/rate-table.md): one coefficient-form
    sensor per unit with its ``uncertainty`` (σ and every correlation pair), and with
    two or more units a ``lot`` entry (mean, σ, correlation pairs unless the lot is
    too small for them). Values in the table's rate unit, each to the decimal place its
    uncertainty supports (:func:`quantum_of`), correlations to :data:`CORRELATION_PLACES`
    places: the digits beyond are rounding, which differs from one machine's BLAS to the
    next."""
    names = result.names
    lines = [
        f"# Written by gyrovib {__version__} fit from {result.file}: least squares of eq. (1),",
        f"# order {result.order}, {sum(f.points for f in result.fits)} points; eq. (2) "
        "coefficients (k1 = 1) with standard uncertainties",
        "# and correlations (docs/model.md section 14).",
        "gyrovib: 1",
        "units:",
        f"  rate: {result.unit}",
        "sensors:",
    ]
    for name, f in zip(result.units, result.fits, strict=True):
        sigma = dict(zip(names, map(float, f.sigma), strict=True))
        values = dict(zip(names, map(float, f.values), strict=True))
        lines += [
            f"  - id: {name}",
            f"    # K1 = {fmt(f.scale_factor, 8)} ± {fmt(f.scale_factor_sigma, 2)} "
            f"{output_unit(result)} per {result.unit}, {f.points} points, residual rms "
            f"{fmt(f.residual_rms, 3)}",
            f"    coefficients: {_flow(values, sigma)}",
            "    uncertainty:",
            f"      sigma: {_flow(sigma)}",
            "      correlation:" + "\n".join(_block(pairs(names, f.correlation), " " * 8)),
        ]
    if result.lot is not None:
        lot = lot_mapping(result)
        lines += [f"  - id: {lot_name(result.file)}"]
        lines += [f"    # {w}" for w in result.warnings]
        lines += [
            "    lot:",
            f"      units: {lot['units']}",
            f"      mean: {_flow(lot['mean'], lot['sigma'])}",
            f"      sigma: {_flow(lot['sigma'])}",
            "      correlation:" + "\n".join(_block(lot["correlation"], " " * 8)),
        ]
    return "\n".join(lines) + "\n"
