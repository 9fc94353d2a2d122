"""One Study, many views: every command's numbers are the Study's, and the report
prepares each profile once.

The expected numbers come from the Study itself (api/evaluation/evaluate.py) and, for each
sensor, from ``analyze`` of that sensor alone (its own one-sensor study: the
grouping by response cannot change a sensor's numbers).
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import numpy as np
import pytest

import gyrovib
from gyrovib import api
from gyrovib.api.evaluation import evaluate
from gyrovib.api.report.views import trade_study
from gyrovib.api.study import study as study_module
from gyrovib.api.study.prepare import float_guard, input_response
from gyrovib.api.study.study import Study

#: Coefficients, output coefficients (with an input-side response: a second group),
#: and a datasheet; a tone, a random profile and one with linear vibration, all at
#: Ω_K3 = 5 deg/s so that a sweep at 5 deg/s meets analyze.
MIXED = """
gyrovib: 1
sensors:
  - id: coef
    range: 300
    coefficients: {A1: 1e-3, k2: 1e-4, k3: 1e-6, k5: -1e-12, m31: 1e-5}
    g2_sensitivity: {G33: 0.01}
  - id: output
    output_coefficients: {K1: 3, K2: 1e-3, M32: 2e-5}
    response: {at: input, table: [[10, 1.0], [100, 0.5]]}
  - id: sheet
    specs:
      range: 40
      nonlinearity: {value: 0.1, unit: "%FS", fit: least-squares, measure: max, of: range}
      vre: 0.001
profiles:
  - id: tone
    rate: [0, 0, 5]
    harmonic: [{frequency: 100, amplitude: [1, 0, 30]}]
  - id: random
    rate: [0, 0, 5]
    random: {rms: [0.5, 0.2, 2]}
  - id: lin
    rate: [0, 0, 5]
    random: {rms: [0.5, 0.5, 1.0]}
    acceleration:
      random: {rms: [1.0, 2.0, 0.5]}
"""

BUDGET = 0.05  # deg/s


def _analyzed(parts: dict[str, np.ndarray], name: str) -> np.ndarray:
    """The Study's ``name`` as analyze writes it: unknown (NaN) where a sensor's g² figure
    is (docs/output.md): 'output' gives none, and 'lin' has a linear vibration."""
    out = np.array(parts[name], dtype=float)
    out[1, 2] = np.nan
    return out


@pytest.fixture(scope="module")
def mixed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("study") / "mixed.gyrovib.yaml"
    path.write_text(MIXED, encoding="utf-8")
    return path


def _study_numbers(catalog: api.Catalog) -> tuple[dict[str, np.ndarray], np.ndarray]:
    study = Study.of(catalog)
    with float_guard():
        prepared = study.prepare(methods=("exact",))
        return evaluate.errors(study, prepared, "exact"), evaluate.saturation(
            prepared).saturated


def test_the_study_has_every_form_and_two_groups(mixed: Path) -> None:
    catalog = api.load([mixed])
    study = Study.of(catalog)
    forms = {form.source: rows.tolist() for form, rows in evaluate.form_rows(study.sensors)}
    assert forms == {"coefficients": [0, 1], "specs": [2]}
    with float_guard():
        assert len(study.prepare().groups) == 2  # ν_sensor ≡ 1, and 'output''s input response


def test_every_command_agrees_with_the_study(mixed: Path) -> None:
    catalog = api.load([mixed])
    parts, saturated = _study_numbers(catalog)
    analysis = api.analyze(catalog)
    total, rms = _analyzed(parts, "total"), _analyzed(parts, "rms")
    assert np.isfinite(parts["total"]).all()  # the Study computes the g² term as 0 there
    np.testing.assert_array_equal(analysis.error.total, total)
    np.testing.assert_array_equal(analysis.error.rms, rms)
    np.testing.assert_array_equal(analysis.saturated, saturated)
    assert analysis.sources == ("coefficients", "coefficients", "specs")
    # each sensor alone (its own study, one group) gives the same numbers
    for i, sid in enumerate(analysis.sensors):
        alone = api.analyze(catalog, sensors=[sid])
        np.testing.assert_allclose(alone.error.total[0], total[i], rtol=1e-9)
        np.testing.assert_allclose(alone.error.rms[0], rms[i], rtol=1e-9)
    selection = api.select(catalog, budget=BUDGET, criterion="both")
    np.testing.assert_array_equal(selection.rms, parts["rms"])
    assert selection.total is not None
    np.testing.assert_array_equal(selection.total, np.abs(parts["total"]))
    np.testing.assert_array_equal(selection.saturated, saturated)
    alone_bounds = api.bounds(catalog, budget=BUDGET)
    for name in ("A1", "k2", "k3", "k4", "k5", "m31", "m32"):
        np.testing.assert_array_equal(getattr(selection.profile_bounds, name),
                                      getattr(alone_bounds.bounds, name))
    swept = api.sweep(catalog, [5.0])  # as analyze: the unknown g² cell NaN there too
    np.testing.assert_allclose(swept.exact.total[..., 0], total, rtol=1e-9)
    np.testing.assert_allclose(swept.exact.rms[..., 0], rms, rtol=1e-9)
    np.testing.assert_array_equal(swept.saturated[..., 0], saturated)
    # the notebook's functions are the same views
    np.testing.assert_array_equal(gyrovib.analyze(str(mixed)).error.total, total)
    np.testing.assert_array_equal(gyrovib.select(str(mixed), budget=BUDGET).rms, parts["rms"])


def test_the_trade_study_is_the_commands(mixed: Path) -> None:
    catalog = api.load([mixed])
    parts, _ = _study_numbers(catalog)
    study = trade_study(catalog, budget=BUDGET, sweep_rates=[-5.0, 5.0])
    np.testing.assert_array_equal(study.analysis.error.total, _analyzed(parts, "total"))
    np.testing.assert_array_equal(study.selection.rms, parts["rms"])
    swept = api.sweep(catalog, [-5.0, 5.0])
    # the report draws Δ_V(RMS) of its method: the sweep's, the datasheet's per-term bound
    np.testing.assert_allclose(study.sweep.exact.rms, swept.exact.rms, rtol=1e-9)
    # what it does not draw is unknown, not zero: the datasheet's worst |Δ_V| per rate
    # and the other method
    assert np.isnan(study.sweep.exact.total[2]).all()
    # 'output' gives no g² figure and 'lin' has a linear vibration: unknown at every rate
    assert np.isnan(study.sweep.exact.total[1, 2]).all()
    known = np.ones(study.sweep.exact.total.shape[:2], dtype=bool)
    known[1, 2] = known[2] = False
    assert np.isfinite(study.sweep.exact.total[known]).all()
    assert np.isnan(study.sweep.paper.rms).all()


def test_report_prepares_each_profile_once(monkeypatch: pytest.MonkeyPatch) -> None:
    catalog = api.load()
    seen: Counter[tuple[str, bool]] = Counter()
    real = study_module.profile_vibration

    def counting(entry, response=None):  # type: ignore[no-untyped-def]
        seen[(entry.profile.id, response is None)] += 1
        return real(entry, response)

    monkeypatch.setattr(study_module, "profile_vibration", counting)
    trade_study(catalog, budget=10 / 3600)
    responses = {input_response(e) for e in catalog.sensors} | {None}
    # once per profile and distinct response at the nonlinear element (the bundled
    # sensors have none at the input: once per profile); before the Study, 70 calls
    assert len(responses) == 1
    assert sorted(seen) == sorted((p.profile.id, True) for p in catalog.profiles)
    assert set(seen.values()) == {1}
