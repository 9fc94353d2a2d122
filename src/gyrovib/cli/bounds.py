"""`gyrovib bounds`: the inverse problem, allowable coefficients per profile."""

from __future__ import annotations

import click

from gyrovib.cli.common import load_catalog, rendered
from gyrovib.cli.options import (
    budget_arguments,
    budget_options,
    files_argument,
    format_option,
    output_option,
    placement_option,
)
from gyrovib.cli.output import write_output
from gyrovib.cli.placement import is_triad, run_placed, write_triad
from gyrovib.cli.spec_options import (
    parse_range,
    parse_spec_weights,
    range_options,
    spec_weights_option,
)


@click.command()
@files_argument
@click.option("--profile", "profiles", multiple=True, metavar="ID",
              help="Only this profile (repeatable).")
@budget_options
@range_options
@spec_weights_option
@placement_option
@format_option("table", "json", "csv", "markdown")
@output_option
def bounds(files: tuple[str, ...], profiles: tuple[str, ...], budget: str, method: str,
           rate: str | None, unit: str | None, allocation: str | None, range_: str | None,
           nl_fit: str, nl_measure: str, nl_of: str, spec_weights: str | None,
           placement: str | None, fmt: str, output: str | None) -> None:
    """The inverse problem: the largest coefficients that keep the error within budget.

    Every file is validated whole, sensors included, as `gyrovib validate`
    does (a CI step running `bounds` fails on a broken file); the bounds use
    only the profiles.

    For each profile, bounds on |A1|, |k2|…|k5|, |m31|, |m32| from the paper's
    split of the budget (eq. 18-25). A sensor within every bound meets the
    budget (eq. 17). The sensor's own frequency response is taken as 1 here;
    `gyrovib select` includes it. With --range R, also the allowable datasheet
    figures: the nonlinearity in %FS of R (as --nl-fit / --nl-measure read it) and
    the VRE.
    """
    # lazy: the library and the renderers load when the command runs, not for --help
    from gyrovib import api
    from gyrovib.render import bounds as render

    catalog = load_catalog(files)  # validated whole; the bounds use the profiles only
    split = budget_arguments(budget, unit, rate, allocation)

    result = run_placed(api.bounds, catalog, placement, fmt, profiles=profiles, method=method,
                        **split, range_=parse_range(range_, split["unit"]), nl_fit=nl_fit,
                        nl_measure=nl_measure, nl_of=nl_of,
                        spec_weights=parse_spec_weights(spec_weights))

    if is_triad(result):
        write_triad(result, lambda one: rendered(render, one, fmt, output), fmt, output)
        return
    write_output(rendered(render, result, fmt, output), output)
