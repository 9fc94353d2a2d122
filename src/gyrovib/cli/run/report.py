"""The body of `gyrovib report` (declared in :mod:`gyrovib.cli.report`)."""

from __future__ import annotations

from typing import Any

from gyrovib import api
from gyrovib.api.report import views as studies
from gyrovib.cli.common import load_catalog, say
from gyrovib.cli.options import budget_arguments
from gyrovib.cli.output import write_output
from gyrovib.cli.run.mission import mission_section
from gyrovib.cli.run.recording import report_recording
from gyrovib.cli.sweep import parse_rate_range
from gyrovib.render.report import to_html


def report(files: tuple[str, ...], sensors: tuple[str, ...], profiles: tuple[str, ...],
           missions: tuple[str, ...], angle_budget: str | None,
           budget: str, method: str, rate: str | None, unit: str | None, allocation: str | None,
           peak_factor: float, criterion: str, assume_unknown: str | None, require: str,
           rate_range: str | None, yield_target: float | None, seed: int, draws: int,
           output: str, recording: str | None, coverage: float, placement: str | None = None,
           **rec: Any) -> None:
    """See :func:`gyrovib.cli.report.report`."""
    split = budget_arguments(budget, unit, rate, allocation)
    sweep_rates = None
    if rate_range is not None:
        sweep_rates = api.rate_range(*parse_rate_range(rate_range, split["unit"]))
    catalog = load_catalog(files)
    section = ""
    if recording is not None:
        catalog, profiles, section = report_recording(recording, catalog, sensors, profiles,
                                                      split["unit"], rec)
    if missions:  # after the recording's section, before the profiles
        section += mission_section(catalog, missions, sensors, angle_budget, split["unit"],
                                   peak_factor, assume_unknown=assume_unknown or "none",
                                   coverage=coverage, placement=placement)
    result = studies.trade_study(
        catalog, sensors=sensors, profiles=profiles, method=method, **split,
        criterion=criterion, require=require, sweep_rates=sweep_rates, peak_factor=peak_factor,
        assume_unknown=assume_unknown or "none", yield_target=yield_target, seed=seed,
        draws=draws)
    write_output(to_html(result, section), output)
    if output not in ("-", ""):
        say(f"gyrovib: wrote {output}")
