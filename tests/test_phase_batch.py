"""The batched objective of a ``phase: worst`` search (core/phase_batch.py) against the
one-point path it replaces in the search (core/analysis.profile_multipliers, itself
checked against brute force in tests/test_mixtures.py and tests/test_harmonics.py): at
random offsets and several rates, every multiplier agrees to 1e-12 relative. Cases: three
groups (two folded into the table, one order of known phase), one group with a tone, and
a group with no part on the sensitive axis (moments only)."""

from __future__ import annotations

import numpy as np
import pytest

from gyrovib.core.analysis import profile_multipliers, stack_multipliers
from gyrovib.core.harmonics import locked_group
from gyrovib.core.phase_batch import batched
from gyrovib.core.phases import apply_offsets, free_offsets
from gyrovib.core.statistics import vibration_at_sensor

CASES = {
    "three groups": (
        [locked_group([1, 2, 3], [[0.1, 0.2, 0.5], [0, 0.1, 0.3], [0, 0, 0.2]],
                      [[0, 0, 0], [0, 0, 40], [0, 0, 10]], worst=[True] * 3),
         locked_group([1, 2], [[0, 0, 0.3], [0, 0, 0.1]], np.zeros((2, 3)),
                      worst=[True, True]),
         locked_group([2, 5], [[0, 0, 0.2], [0.1, 0, 0.15]], np.zeros((2, 3)),
                      worst=[False, True])],
        vibration_at_sensor([(7.0, (0.0, 0.0, 0.3), (0.0, 0.0, 0.0))], rms=(0.1, 0.2, 0.25))),
    "one group and a tone": (
        [locked_group([1, 2, 4], [[0, 0, 1.0], [0, 0, 0.4], [0, 0, 0.2]], np.zeros((3, 3)),
                      worst=[True] * 3)],
        vibration_at_sensor([(7.0, (0.0, 0.0, 0.5), (0.0, 0.0, 0.0))], rms=(0.0, 0.0, 0.3))),
    "a group off the sensitive axis": (
        [locked_group([1, 2], [[0, 0, 1.0], [0, 0, 0.4]], np.zeros((2, 3)), worst=[True] * 2),
         locked_group([1, 3], [[0.3, 0, 0], [0.2, 0, 0]], np.zeros((2, 3)), worst=[True] * 2)],
        vibration_at_sensor([], rms=(0.1, 0.1, 0.3))),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_batched_multipliers_are_the_one_point_path(name: str) -> None:
    groups, vibration = CASES[name]
    free = free_offsets(groups)
    batch = batched(vibration, groups, free, None)
    assert batch is not None
    psi = np.random.default_rng(3).uniform(0.0, 2.0 * np.pi, (12, len(free)))
    rates = np.repeat([0.0, 0.3, 1.7, -2.5], 3)  # rows at different rates in one call
    got = batch.multipliers(psi, rates)
    want = stack_multipliers([
        profile_multipliers(vibration, np.asarray(w), "exact",
                            locked=apply_offsets(groups, free, row))
        for row, w in zip(psi, rates, strict=True)])
    for field in ("asymmetry", "m2", "m3", "m4", "m5", "c31", "c32", "omega"):
        assert getattr(got, field) == pytest.approx(getattr(want, field), rel=1e-12,
                                                    abs=1e-300), field


def test_no_batched_form_without_a_random_part() -> None:
    # no Gaussian part on x3: the one-point path takes another route (two groups alone)
    groups = CASES["three groups"][0][:2]
    assert batched(vibration_at_sensor(), groups, free_offsets(groups), None) is None


def test_a_repeated_search_gives_the_same_answer_and_a_copy() -> None:
    # a report asks analyze and select the same profile's worst phases: the second call
    # takes the first one's result, and a caller's change to it never reaches the next
    from gyrovib.core.phases import worst_phase_errors

    groups, vibration = CASES["one group and a tone"]
    from gyrovib.core.analysis import COEFFICIENTS

    c = np.zeros((1, len(COEFFICIENTS)))
    for name, value in {"k1": 1.0, "A1": 0.02, "k3": 1e-3}.items():
        c[0, COEFFICIENTS.index(name)] = value
    first = worst_phase_errors(c, vibration, groups, [0.4])[0]
    kept = float(first.error.total[0])
    first.error.total[0] = 0.0
    again = worst_phase_errors(c, vibration, groups, [0.4])[0]
    assert float(again.error.total[0]) == kept != 0.0
    assert np.array_equal(again.offsets, first.offsets)


def test_a_search_over_several_rates_is_never_below_a_sampled_phase() -> None:
    # worst_phase_errors searches every (rate, sensor) at once on the batched form; at
    # each rate and for each sensor the maximum found is at least |Δ_V| at any phases
    # drawn at random, each evaluated on the one-point path
    from gyrovib.core.analysis import COEFFICIENTS, vibration_error
    from gyrovib.core.phases import worst_phase_errors

    groups, vibration = CASES["three groups"]
    c = np.zeros((2, len(COEFFICIENTS)))
    for k, row in enumerate(({"k1": 1.0, "A1": 0.02, "k2": 1e-3, "k3": -2e-3},
                             {"k1": 1.0, "k3": 1e-3, "k4": -2e-3, "k5": 5e-4})):
        for name, value in row.items():
            c[k, COEFFICIENTS.index(name)] = value
    rates = [0.0, 0.8]
    found = worst_phase_errors(c, vibration, groups, rates)
    free = free_offsets(groups)
    for psi in np.random.default_rng(17).uniform(0.0, 2.0 * np.pi, (25, len(free))):
        for r, w in enumerate(rates):
            mu = profile_multipliers(vibration, np.asarray(w), "exact",
                                     locked=apply_offsets(groups, free, psi))
            trial = np.abs(vibration_error(c, mu).total)
            assert np.all(np.abs(found[r].error.total) >= trial * (1 - 1e-12))
