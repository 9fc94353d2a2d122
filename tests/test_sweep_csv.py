"""The sweep's CSV writer and the long-sweep shortcuts change no byte and no value.

* ``to_csv`` / ``to_csv_chunks`` (columns formatted at once, constant columns
  written once, the sensor and profile cells as a row prefix, the refused
  paper cells riding on the last column) against the csv module writing each
  value row by row, on sweeps with awkward values: negative zero, ±inf, NaN,
  subnormal, tiny and huge magnitudes, integers as floats, columns of one value;
* ``locked_abs_excess`` skipping the rates beyond the group's swing against its
  pieces integrated at every rate (bit for bit: beyond the swing both give 0.0);
* ``to_unit(..., in_place=True)`` against the copying conversion (bit for bit).
"""

from __future__ import annotations

import csv
import io
import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gyrovib.api import SweepResult
from gyrovib.api.study.convert import to_unit
from gyrovib.core.analysis import VibrationError
from gyrovib.core.harmonics import _abs_excess, locked_abs_excess
from gyrovib.render import sweep as render_sweep
from gyrovib.render.common import float_cells
from tests.conftest import invoke

HEAD = ["sensor", "profile", "rate_x3", "exact_total", "exact_rms", "paper_total",
        "paper_rms", "saturated"]

#: Values the writer must reproduce exactly (repr of each, as the csv module writes it).
AWKWARD = [0.0, -0.0, math.inf, -math.inf, math.nan, 5e-324, -5e-324, 2.2250738585072014e-308,
           1e-300, 1.7976931348623157e308, -1e300, 1e16, 1e15, 9999999999999998.0, 1e-5,
           1e-4, 0.1, 1.0, -1.0, 2.0, 100.0, 123456789.0, 1e22, 0.1 + 0.2, 1 / 3, -2 / 3]


def _cell(value: float) -> str:
    """A value as the CSV writes it: its repr, or empty where it is unknown (NaN)."""
    return "" if value != value else repr(value)


def row_by_row(result: SweepResult) -> str:
    """The csv module's text, one value at a time: what the CSV has always been (an
    unknown value, NaN, is an empty cell)."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(HEAD)
    sat = (np.zeros((len(result.sensors), len(result.profiles), len(result.rates)), bool)
           if result.saturated is None else result.saturated)
    for j, profile in enumerate(result.profiles):
        refused = profile in result.paper_refused
        for i, sensor in enumerate(result.sensors):
            for r, rate in enumerate(result.rates.tolist()):
                paper: list[Any] = (["", ""] if refused else
                                    [_cell(float(result.paper.total[i, j, r])),
                                     _cell(float(result.paper.rms[i, j, r]))])
                writer.writerow([sensor, profile, _cell(rate),
                                 _cell(float(result.exact.total[i, j, r])),
                                 _cell(float(result.exact.rms[i, j, r])), *paper,
                                 str(bool(sat[i, j, r]))])
    return buffer.getvalue()


def error_of(total: np.ndarray, rms: np.ndarray) -> VibrationError:
    shape = total.shape
    return VibrationError(additive_terms=np.zeros((*shape, 5)),
                          multiplicative_coefficients=np.zeros((*shape, 3)),
                          additive=total.copy(), multiplicative=np.zeros(shape),
                          total=total, rms=rms, extra_terms=np.zeros((*shape, 3)))


values = st.one_of(st.sampled_from(AWKWARD), st.floats(allow_nan=True, allow_infinity=True))


@st.composite
def sweeps(draw: st.DrawFn) -> SweepResult:
    """A sweep result with awkward values; some columns of one value throughout."""
    n_s = draw(st.integers(1, 2))
    n_p = draw(st.integers(1, 3))
    n_r = draw(st.integers(1, 12))
    names = st.text(alphabet=st.sampled_from('ab-%,"\n é'), min_size=1, max_size=6)
    sensors = draw(st.lists(names, min_size=n_s, max_size=n_s, unique=True))
    profiles = draw(st.lists(names, min_size=n_p, max_size=n_p, unique=True))
    shape = (n_s, n_p, n_r)

    def column_block() -> np.ndarray:
        out = np.empty(shape)
        for i in range(n_s):
            for j in range(n_p):
                if draw(st.booleans()):  # one value throughout (e.g. exact zeros)
                    out[i, j] = draw(values)
                else:
                    out[i, j] = draw(st.lists(values, min_size=n_r, max_size=n_r))
        return out

    rates = np.array(draw(st.lists(values, min_size=n_r, max_size=n_r)))
    refused = {p: "refused" for p in profiles if draw(st.booleans())}
    saturated = np.array(draw(st.lists(st.sampled_from([False, True]), min_size=n_s * n_p * n_r,
                                       max_size=n_s * n_p * n_r))).reshape(shape)
    if draw(st.booleans()):  # all False / all True series
        saturated[:] = draw(st.booleans())
    return SweepResult(unit="deg/s", sensors=tuple(sensors), profiles=tuple(profiles),
                       rates=rates, exact=error_of(column_block(), column_block()),
                       paper=error_of(column_block(), column_block()), paper_refused=refused,
                       saturated=saturated if draw(st.booleans()) else None)


# 100 sweeps draw ~5,700 cells, each AWKWARD value at least 37 times (the profile's fixed
# seed: the same ones every run); each special value alone is pinned by the test below
@settings(deadline=None, max_examples=100)
@given(sweeps())
def test_sweep_csv_is_the_row_by_row_text_for_awkward_values(result: SweepResult) -> None:
    expected = row_by_row(result)
    chunks = list(render_sweep.to_csv_chunks(result))
    # the header, then one piece per sensor × profile series
    assert len(chunks) == 1 + len(result.sensors) * len(result.profiles)
    assert "".join(chunks) == expected
    assert render_sweep.to_csv(result) == expected


@pytest.mark.parametrize("value", [0.0, -0.0, math.nan, math.inf, -math.inf, 5e-324, 1e16, 3.0])
def test_a_column_of_one_value_is_that_values_repr_throughout(value: float) -> None:
    # by the bits: 0.0 and -0.0 compare equal but are written differently; NaN (unknown)
    # is an empty cell
    assert float_cells(np.full(7, value)) == [_cell(value)] * 7
    mixed = np.array([0.0, -0.0, 0.0])
    assert float_cells(mixed) == ["0.0", "-0.0", "0.0"]
    # a strided column (one rate series of a larger array) is read, not its memory
    block = np.array([[value, 1.0], [value, 2.0]])
    assert float_cells(block[:, 0]) == [_cell(value)] * 2


def test_sweep_csv_through_the_command_line_is_the_row_by_row_text(tmp_path: Any) -> None:
    # the bundled coefficient-form sensor over rates most of which are beyond every
    # profile's reach, and a few saturated ones (ADXRS453: range 300 deg/s)
    from gyrovib import api

    target = tmp_path / "sweep.csv"
    result = invoke("sweep", "--sensor", "adxrs453", "--rate-range", "-320:320:33",
                    "--format", "csv", "-o", target)
    assert result.exit_code == 0
    swept = api.sweep(api.load(), api.rate_range(-320.0, 320.0, 33), sensors=["adxrs453"])
    assert swept.saturated is not None and swept.saturated.any() and not swept.saturated.all()
    assert target.read_text(encoding="utf-8") == row_by_row(swept)


# ---------------------------------------------------------------- beyond the swing


orders_and_phasors = st.lists(
    st.tuples(st.integers(1, 6), st.floats(0.05, 3.0), st.floats(0.0, 2 * math.pi)),
    min_size=1, max_size=4, unique_by=lambda t: t[0])


@settings(deadline=None, max_examples=60)
@given(orders_and_phasors, st.floats(0.5, 3.0))
def test_locked_excess_beyond_the_swing_is_what_the_pieces_give(
        parts: list[tuple[int, float, float]], spread: float) -> None:
    # x3 = Σ Im(p_n e^{jnθ}), |x3| ≤ Σ|p_n|: rates from inside to well beyond the swing,
    # both signs, the bound itself and its neighbours
    n = np.array([o for o, _, _ in parts])
    p = np.array([a * np.exp(1j * phi) for _, a, phi in parts])
    bound = float(np.sum(np.abs(p)))
    rates = np.concatenate([np.linspace(-spread * bound, spread * bound, 41),
                            [bound, -bound, np.nextafter(bound, 0), np.nextafter(bound, 9),
                             bound * (1 + 1e-9), bound * (1 + 2e-9), 0.0]])
    got = locked_abs_excess(rates, n, p)
    every = _abs_excess(rates, n, p)  # the pieces at every rate, as before the skip
    assert got.tobytes() == every.tobytes()
    beyond = np.abs(rates) > bound * (1 + 1e-9)
    assert np.all(got[beyond] == 0.0) and not np.any(np.signbit(got[beyond]))


def test_locked_excess_keeps_the_shape_of_omega() -> None:
    n, p = np.array([1, 2]), np.array([1.0 + 0.5j, 0.25j])
    omega = np.array([[0.1, 5.0, -0.3], [-9.0, 0.0, 1.2]])
    got = locked_abs_excess(omega, n, p)
    assert got.shape == omega.shape
    assert got.tobytes() == _abs_excess(omega.ravel(), n, p).reshape(omega.shape).tobytes()


# ---------------------------------------------------------------- the unit, in place


@pytest.mark.parametrize("unit", ["deg/s", "deg/h", "rad/s", "rpm"])
def test_to_unit_in_place_is_the_copying_conversion(unit: str) -> None:
    rng = np.random.default_rng(7)
    shape = (2, 3, 5)
    arrays = {"additive_terms": rng.normal(size=(*shape, 5)),
              "multiplicative_coefficients": rng.normal(size=(*shape, 3)),
              "additive": rng.normal(size=shape), "multiplicative": rng.normal(size=shape),
              "total": rng.normal(size=shape) * 1e-300, "rms": rng.normal(size=shape) * 1e300,
              "extra_terms": rng.normal(size=(*shape, 3))}
    arrays["total"][0, 0, 0] = -0.0
    arrays["rms"][0, 0, 0] = math.nan
    copied = to_unit(VibrationError(**{k: v.copy() for k, v in arrays.items()}), unit)
    own = VibrationError(**arrays)
    converted = to_unit(own, unit, in_place=True)
    assert converted is own
    for name in arrays:
        assert getattr(converted, name).tobytes() == getattr(copied, name).tobytes(), name
