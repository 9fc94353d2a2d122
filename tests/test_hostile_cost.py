"""Cost bounded by the input's size: what the format allows either
runs quickly or is refused before any computation, at the offending key.

The timed sizes (and the before/after figures) are in benchmarks/bench_hostile.py;
here each case is a located exit 2 or a small but discriminating run. The
limits are gyrovib's own constants (the models' MAX_ORDER, core/harmonics.py MAX_GROUPS;
core/phases.py MAX_SEARCH_COST), so a test fails if a refusal goes missing or
lands on another line.
"""

from __future__ import annotations

import contextlib
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import Result

from tests.conftest import invoke

SENSOR = """gyrovib: 1
units: {rate: deg/s}
sensors:
  - id: s
    range: 500
    coefficients: {A1: 1.0e-3, k2: 2.0e-4, k3: 1.0e-5, k4: -3.0e-7, k5: 1.0e-8}
"""
HEAD = """gyrovib: 1
units: {rate: deg/s}
profiles:
  - id: p
    rate: [0, 0, 0.5]
    harmonics:
"""


def one_group(orders: list[tuple[int, str]], amplitude: float = 1.0) -> str:
    """A profile with one locked group (a mapping): ``(order, phase)`` per order;
    the orders start on line 9 of the file."""
    lines = [HEAD, "      fundamental: 20\n", "      orders:\n"]
    for n, phase in orders:
        lines.append(f"        - {{order: {n}, amplitude: [0, 0, {amplitude}], phase: {phase}}}\n")
    return "".join(lines)


def groups(count: int) -> str:
    """``count`` locked groups of orders 1 and 2 (a list); group g's
    ``fundamental`` value on line 7 + 4g, column 22."""
    lines = [HEAD]
    for g in range(count):
        lines += [f"      - fundamental: {10 * g + 13}\n", "        orders:\n",
                  "          - {order: 1, amplitude: [0, 0, 0.5], phase: [0, 0, 0]}\n",
                  "          - {order: 2, amplitude: [0, 0, 0.3], phase: [0, 0, 30]}\n"]
    return "".join(lines)


def files(tmp_path: Path, profile: str) -> tuple[Path, Path]:
    s = tmp_path / "s.yaml"
    p = tmp_path / "p.yaml"
    s.write_text(SENSOR, encoding="utf-8")
    p.write_text(profile, encoding="utf-8")
    return s, p


def run(*args: object) -> Result:
    """One command, in-process (the times are benchmarks/bench_hostile.py's)."""
    return invoke(*args)


def refused_at(result: Result, path: Path, line: int, column: int, *words: str) -> None:
    assert result.exit_code == 2, result.stderr
    first = result.stderr.strip().splitlines()[0]
    assert first.startswith(f"{path}:{line}:{column}: "), first
    for word in words:
        assert word in first, first


COMMANDS = [("analyze",), ("select", "--budget", "1"), ("sweep", "--format", "csv"),
            ("bounds", "--budget", "1")]


@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: c[0])
@pytest.mark.parametrize("order", [1000, 100_000, 10**9, 10**20])
def test_a_high_harmonic_order_is_refused_at_its_key(tmp_path: Path, command: tuple[str, ...],
                                                     order: int) -> None:
    # today: orders 1 and 1,000 run for minutes, 10^5 and 10^9 run out of memory
    # (unlocated), 10^20 is an internal error (exit 3)
    s, p = files(tmp_path, one_group([(1, "[0, 0, 0]"), (order, "[0, 0, 0]")]))
    result = run(*command, s, p)
    # line 10 is the second order; its `order:` value starts at column 19
    refused_at(result, p, 10, 19, "must not be greater than 64", f"got {order}")


def test_order_64_runs_a_sweep_inside_the_swing_quickly(tmp_path: Path) -> None:
    # every rate inside the swing: one eigenvalue problem of degree 128 per rate
    # before (37.8 s for 401 rates); the group's stationary points once now
    s, p = files(tmp_path, one_group([(1, "[0, 0, 0]"), (64, "[0, 0, 0]")]))
    result = run("sweep", s, p, "--format", "csv", "--rate-range", "-3:3:41")
    assert result.exit_code == 0, result.stderr
    rows = result.stdout.strip().splitlines()[1:]
    assert len(rows) == 41 and all(r.split(",")[3] not in ("", "nan") for r in rows)


@pytest.mark.parametrize("count", [8, 16, 64])
def test_phase_worst_on_many_orders_is_refused_at_the_first_worst_phase(
        tmp_path: Path, count: int) -> None:
    # today: 8 orders pass 30 s, 16 reach 8.2 GB and "out of memory", 64 exit 3 (meshgrid's
    # 32-dimension limit)
    orders = [(n, "worst") for n in range(1, count + 1)]
    s, p = files(tmp_path, one_group(orders, 0.1))
    # (eight orders: analyze's one search per sensor is allowed, select's
    # synthesis search, four objectives more, is not)
    for command in COMMANDS[:2] if count > 8 else COMMANDS[1:2]:
        result = run(*command, s, p)
        # the first order (line 9), its `phase:` value at column 53
        refused_at(result, p, 9, 53, f"{count - 1} unknown relative phases",
                   "more than the 3,000")


def test_phase_worst_default_sweep_is_refused_and_a_short_one_runs(tmp_path: Path) -> None:
    # today a 5-rate sweep of four worst orders took 20.7 s; the default 401 rates
    # would take an hour: refused, saying how many rates (the timed four-order
    # select and 5-rate sweep are in benchmarks/bench_hostile.py)
    s, p = files(tmp_path, one_group([(n, "worst") for n in range(1, 5)]))
    refused_at(run("sweep", s, p), p, 9, 53, "at 401 rates")
    s, p = files(tmp_path, one_group([(1, "[0, 0, 0]"), (2, "worst")]))
    result = run("sweep", s, p, "--format", "csv", "--rate-range", "-3:3:3")
    assert result.exit_code == 0, result.stderr
    assert len(result.stdout.strip().splitlines()) == 4


@pytest.mark.parametrize("count", [3, 4, 5])
def test_more_than_two_locked_groups_without_a_random_part_are_refused_at_the_third(
        tmp_path: Path, count: int) -> None:
    # today: 4 groups make sweep ignore SIGTERM, 5 end in an unlocated "out of memory";
    # with a random part they run (the groups beyond the first are folded into its
    # table: tests/test_vessel.py checks the value against a brute force)
    s, p = files(tmp_path, groups(count))
    for command in COMMANDS:
        result = run(*command, s, p)
        refused_at(result, p, 15, 22, f"{count} phase-locked groups and no random part")


def test_three_locked_groups_with_a_random_part_run(tmp_path: Path) -> None:
    text = mixture(3, [], 0.3)
    s, p = files(tmp_path, text)
    result = run("sweep", s, p, "--format", "csv", "--rate-range", "-1:1:5")
    assert result.exit_code == 0, result.stderr
    assert len(result.stdout.strip().splitlines()) == 6


def test_two_groups_run(tmp_path: Path) -> None:
    s, p = files(tmp_path, groups(2))
    result = run("sweep", s, p, "--format", "csv", "--rate-range", "-1:1:21")
    assert result.exit_code == 0, result.stderr
    assert re.search(r"^s,p,-1\.0,", result.stdout, re.M)


def test_tone_on_a_tiny_random_part_is_quick_and_exact() -> None:
    # a = 100, σ = 1e-3: the phase grid needed ~a/σ nodes per rate (4 million,
    # capped; the default 401-rate sweep took 91 s). Reference: scipy's adaptive
    # quad of E(Ω) = ∫ φ(z)·k(Ω + σz) dz, with k(m) = <|m + a·sin θ|> − m the tone's
    # signed excess written out by hand (arcsine law: (2/π)(m·asin(m/a) + √(a²−m²)) − m
    # inside, 0 above a, −2m below −a), up to the edge (quad's error estimate
    # ≤ 1e-12). (The same mean over θ with the Gaussian in closed form cancels
    # against Ω and quad misjudges its own error there by 1e-7.)
    import math

    import numpy as np
    from scipy import integrate

    from gyrovib.core.statistics import rectified_excess

    a, sigma = 100.0, 1e-3
    rates = np.array([0.0, 37.5, 99.0, 99.999, 100.0, 100.002, 100.01])

    def k(m: float) -> float:
        if m >= a:
            return 0.0
        if m <= -a:
            return -2.0 * m
        if m <= 0:
            return 2 / math.pi * (m * math.asin(m / a) + math.sqrt(a * a - m * m)) - m
        # above 0 the same, as a sum of positive terms (no cancellation near a):
        # t = √((a−m)/(a+m)), k = (2/π)((a − m)·t + 2m·(t − atan t))
        t = math.sqrt((a - m) / (a + m))
        rest = sum((-1) ** j * t ** (2 * j + 3) / (2 * j + 3) for j in range(12)) \
            if t < 0.05 else t - math.atan(t)
        return 2 / math.pi * ((a - m) * t + 2 * m * rest)

    def reference(w: float) -> float:
        def f(z: float) -> float:
            return math.exp(-z * z / 2) / math.sqrt(2 * math.pi) * k(w + sigma * z)
        hi = min(40.0, (a - w) / sigma)
        lo = -40.0 if hi > -5.0 else hi - 12.0  # (φ(hi − 12)/φ(hi) < e^-100)
        value, _ = integrate.quad(f, lo, hi, epsabs=0, epsrel=1e-12, limit=500)
        return float(value)

    got = rectified_excess(np.linspace(-200, 200, 401), [a], sigma)  # 91 s before, 0.06 s now
    assert got.shape == (401,)
    direct = rectified_excess(rates, [a], sigma)
    for w, value in zip(rates, direct, strict=True):
        want = reference(float(w))
        assert value == pytest.approx(want, rel=1e-9, abs=1e-300), w


def _wait_for_cpu(process: subprocess.Popen[str], seconds: float) -> None:
    """Until ``process`` has used ``seconds`` of CPU (Linux's /proc), or has ended; where
    /proc is not there, ``seconds`` of wall time. On a loaded machine a wall-clock wait
    may end before the process has even loaded its catalogue."""
    stat = Path(f"/proc/{process.pid}/stat")
    if not stat.exists():
        time.sleep(seconds)
        return
    tick = os.sysconf("SC_CLK_TCK")
    deadline = time.monotonic() + 300
    while process.poll() is None and time.monotonic() < deadline:
        with contextlib.suppress(OSError, IndexError, ValueError):
            fields = stat.read_text().rsplit(")", 1)[1].split()
            if (int(fields[11]) + int(fields[12])) / tick >= seconds:  # utime + stime
                return
        time.sleep(0.05)


@pytest.mark.parametrize("sig, code", [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_a_signal_acts_inside_long_numeric_work(tmp_path: Path, sig: int,
                                                                  code: int) -> None:
    # 3,000 datasheet sensors of all-different ranges under 2 profiles: select runs
    # their envelope programmes for half a minute or more; today the audit saw
    # SIGTERM take 26 s inside one long numpy call (orders 1 and 1,000)
    lines = ["gyrovib: 1\nunits: {rate: deg/s}\nsensors:\n"]
    for i in range(3000):
        lines.append(f"  - id: spec{i:05d}\n    specs:\n      range: {100 + 0.37 * i:.2f}\n"
                     "      nonlinearity: {value: 0.1, unit: \"%FS\", fit: least-squares, "
                     "measure: max, of: range}\n")
    (tmp_path / "s.yaml").write_text("".join(lines), encoding="utf-8")
    # eight profiles (tones and random parts at different carrier rates), so the run
    # outlasts the wait below by far on a fast machine too (about 2 s a profile pair)
    (tmp_path / "p.yaml").write_text(
        "gyrovib: 1\nunits: {rate: deg/s}\nprofiles:\n" + "".join(
            f"  - id: tone{k}\n    rate: [0, 0, {0.5 + k}]\n    harmonic:\n"
            "      - {frequency: 95, amplitude: [1.2, 0.8, 2.5]}\n"
            f"  - id: random{k}\n    rate: [0, 0, {2 + k}]\n    random: {{rms: [0.5, 0.5, 1.0]}}\n"
            for k in range(4)),
        encoding="utf-8")
    process = subprocess.Popen(
        [sys.executable, "-m", "gyrovib", "select", "s.yaml", "p.yaml", "--budget", "1",
         "--format", "csv", "-o", str(tmp_path / "out.csv")],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path)
    _wait_for_cpu(process, 2.0)  # past start-up and loading, inside the work
    if process.poll() is not None:
        _, err = process.communicate()
        pytest.fail(f"finished before the signal, status {process.returncode}: {err[-600:]}")
    process.send_signal(sig)
    _, err = process.communicate(timeout=30)
    assert process.returncode == code, err
    assert not (tmp_path / "out.csv").exists()


def test_a_long_sweep_is_refused_up_front_saying_how_many_rates_fit() -> None:
    # the bundled catalogue at the allowed maximum of 20,000 rates passed 30 s and
    # 4.1 GB; 2,000 rates took 23 s (its four datasheet sensors' envelope programmes)
    from gyrovib.api.commands.sweep import MAX_SWEEP_CELLS, MAX_SWEEP_PROGRAMMES

    result = run("sweep", "--rate-range", "-200:200:20000", "--format", "csv")
    assert result.exit_code == 2, result.stderr
    assert result.stderr.startswith("gyrovib: error: --rate-range: 20,000 rates × 14 profiles")
    assert f"more than the {MAX_SWEEP_CELLS:,}" in result.stderr
    assert f"at most {MAX_SWEEP_CELLS // (14 * 9):,} rates" in result.stderr
    result = run("sweep", "--rate-range", "-200:200:2000", "--format", "csv")
    assert result.exit_code == 2, result.stderr
    assert f"more than the {MAX_SWEEP_PROGRAMMES:,}" in result.stderr
    assert f"at most {MAX_SWEEP_PROGRAMMES // (4 * 14 * 2):,} rates" in result.stderr


def spec_catalogue(count: int) -> str:
    """``count`` datasheet sensors, every range different (100 + 0.37·i deg/s)."""
    lines = ["gyrovib: 1\nunits: {rate: deg/s}\nsensors:\n"]
    for i in range(count):
        lines.append(f"  - id: spec{i:05d}\n    specs:\n      range: {100 + 0.37 * i:.2f}\n"
                     "      nonlinearity: {value: 0.1, unit: \"%FS\", fit: least-squares, "
                     "measure: max, of: range}\n")
    return "".join(lines)


TWO_PROFILES = """gyrovib: 1
units: {rate: deg/s}
profiles:
  - id: tone
    rate: [0, 0, 0.5]
    harmonic:
      - {frequency: 95, amplitude: [1.2, 0.8, 2.5]}
  - id: random
    rate: [0, 0, 2]
    random: {rms: [0.5, 0.5, 1.0]}
"""


def test_datasheet_bounds_of_many_ranges_in_one_call_equal_one_by_one() -> None:
    # reference: core/envelope.py spec_bounds, one definition at a time (checked
    # against scipy's linprog in tests/test_envelope_reference.py); the batch shares
    # the programmes of neighbouring ranges (3,000 spec sensors: select past 30 s → 9 s)
    import numpy as np

    from gyrovib.core.envelope import spec_bounds, spec_bounds_many

    rng = np.random.default_rng(4)
    terms = rng.normal(size=(2, 8, 5)) * np.array([1.0, 0.3, 0.1, 0.03, 0.01])
    g2 = np.array([0.0, 0.2])
    ranges = [100.0 + 37.3 * i for i in range(12)]
    fits = ["least-squares", "endpoint", "minimax"] * 4
    measures = ["max"] * 12
    ofs = ["range", "span", "rate"] * 4
    nl, vre = spec_bounds_many(0.05, terms, g2, ranges, fits, measures, ofs)
    for k in range(12):
        one = spec_bounds(0.05, terms, g2, ranges[k], fits[k], measures[k], ofs[k])
        assert nl[k] == pytest.approx(one.nonlinearity, rel=1e-12)
        assert vre[k] == pytest.approx(one.vre, rel=1e-12)


def test_select_of_datasheet_sensors_with_all_different_ranges(tmp_path: Path) -> None:
    # 100 sensors × 2 profiles: 5.1 s before (one envelope call per range, each
    # cold), 2.1 s now in a subprocess; in-process here, within 2 s
    s = tmp_path / "s.yaml"
    p = tmp_path / "p.yaml"
    s.write_text(spec_catalogue(100), encoding="utf-8")
    p.write_text(TWO_PROFILES, encoding="utf-8")
    result = run("select", s, p, "--budget", "1", "--format", "csv")
    assert result.exit_code in (0, 1), result.stderr
    assert len(result.stdout.strip().splitlines()) == 1 + 100 * 2


def test_a_report_over_many_sensors_charts_the_best_ranked(tmp_path: Path) -> None:
    # 3,000 sensors: the report's sweep of every sensor held 2.9 million results
    # (refused by the sweep's size check); its charts now draw the SWEEP_SENSORS best
    import gyrovib
    from gyrovib.api.report.views import SWEEP_SENSORS

    s = tmp_path / "s.yaml"
    p = tmp_path / "p.yaml"
    lines = ["gyrovib: 1\nunits: {rate: deg/s}\nsensors:\n"]
    for i in range(SWEEP_SENSORS + 3):  # k2 decides the ranking: each a different one
        lines.append(f"  - id: c{i:02d}\n    range: 500\n"
                     f"    coefficients: {{A1: 1.0e-3, k2: {1e-4 * (1 + (7 * i) % 15):.1e}}}\n")
    s.write_text("".join(lines), encoding="utf-8")
    p.write_text(TWO_PROFILES, encoding="utf-8")
    catalog = gyrovib.load([s, p])
    from gyrovib.api.report.views import trade_study

    study = trade_study(catalog, budget=1.0)
    ranked = [study.selection.sensors[i] for i in study.selection.ranking[:SWEEP_SENSORS]]
    assert list(study.sweep.sensors) == sorted(ranked, key=study.selection.sensors.index)


def mixture(groups_: int, tones: list[float], rms: float | None) -> str:
    """``groups_`` locked groups of orders 1 and 2 (a list), independent ``tones`` (x3
    amplitudes) and a random part of RMS ``rms`` on x3 (none if None)."""
    lines = [groups(groups_)]
    if tones:
        lines.append("    harmonic:\n")
        lines += [f"      - {{frequency: {50 + 10 * i}, amplitude: [0, 0, {a}]}}\n"
                  for i, a in enumerate(tones)]
    if rms is not None:
        lines.append(f"    random: {{rms: [0, 0, {rms}]}}\n")
    return "".join(lines)


def test_two_groups_a_tone_and_a_random_part_sweep_quickly(tmp_path: Path) -> None:
    # two groups + a tone + a random PSD: the default 401-rate sweep took 50 s and
    # 645 MB (report 42 s): each of 401 × 256 × 72 points a tone-on-Gaussian mean.
    # The tone and the Gaussian are now tabulated once in c; 1.4 s in a subprocess.
    s, p = files(tmp_path, mixture(2, [1.0], 2.2))
    result = run("sweep", s, p, "--format", "csv", "--rate-range", "-3:3:101")
    assert result.exit_code == 0, result.stderr
    rows = [r.split(",") for r in result.stdout.strip().splitlines()[1:]]
    assert len(rows) == 101 and all(r[3] not in ("", "nan") for r in rows)


def test_locked_mixture_excess_matches_brute_force() -> None:
    # Reference: the folded-normal mean σ√(2/π)e^(−u²) − m·erfc(u) (written out, with
    # scipy's erfc) averaged over a midpoint grid of every phase — 256 per group and
    # per tone (the integrand is analytic: the rule converges geometrically; 128 and
    # 256 agree to 1e-15 here). Rates inside the swing, at its edge and in the tail.
    import math

    import numpy as np
    from scipy import special

    from gyrovib.core.harmonic_mixtures import locked_mixture_excess
    from gyrovib.core.harmonics import locked_group

    g1 = locked_group([1, 2, 3, 4], [[0, 0, 1.0], [0, 0, 0.6], [0, 0, 0.35], [0, 0, 0.2]],
                      [[0, 0, 10], [0, 0, 75], [0, 0, -30], [0, 0, 160]])
    g2 = locked_group([1, 3], [[0, 0, 0.4], [0, 0, 0.2]], [[0, 0, 30], [0, 0, 0]])
    mid = 2 * math.pi * (np.arange(256) + 0.5) / 256

    def x3(orders: tuple[int, ...], amps: tuple[float, ...], phases: tuple[float, ...]
           ) -> np.ndarray:
        return sum(a * np.sin(n * mid + math.radians(f))
                   for n, a, f in zip(orders, amps, phases, strict=True))

    y1 = x3((1, 2, 3, 4), (1.0, 0.6, 0.35, 0.2), (10, 75, -30, 160))
    y2 = x3((1, 3), (0.4, 0.2), (30, 0))
    for groups_, shifts, tones, sigma in (([g1], [y1], [0.5], 0.3),
                                          ([g1, g2], [y1, y2], [0.5], 0.3),
                                          ([g1, g2], [y1, y2], [], 0.3)):
        for omega in (0.0, 0.4, -0.8, 2.0, -3.5, 5.0):
            total = np.array([omega])
            for y in [*shifts, *(a * np.sin(mid) for a in tones)]:
                total = (total[:, None] + y[None, :]).ravel()
            m = total if omega >= 0 else -total
            u = m / (sigma * math.sqrt(2))
            want = float(np.mean(sigma * math.sqrt(2 / math.pi) * np.exp(-u * u)
                                 - m * special.erfc(u)))
            got = float(locked_mixture_excess(np.array([omega]), groups_, tones, sigma)[0])
            assert got == pytest.approx(want, rel=1e-11), (len(groups_), tones, omega)


@pytest.mark.parametrize("tones, rms, words", [
    # (the second group is folded into the table of the tone on the random part: a table
    # of 2·(Σa + 40σ + peak)·16/σ values times its 16,384 nodes)
    ([1.0], 0.01, ["2 phase-locked groups on a random part of RMS 0.01",
                   "would fold the groups beyond the first", "more than the 67,108,864"]),
    ([1.0], None, ["two phase-locked groups with independent tones and no random part",
                   "give at most 4 rates"]),
    # (σ = 1e-6 against a = 1: (1 + 4e-5)·16/σ = 16 million values of the tones' excess)
    ([1.0], 1e-6, ["2 phase-locked groups with 1 independent tone (largest 1)",
                   "would tabulate 16,000,648 values", "more than the 32,768"]),
])
def test_two_groups_with_tones_beyond_the_budget_are_refused(
        tmp_path: Path, tones: list[float], rms: float | None, words: list[str]) -> None:
    # a narrow random part (or none) under two groups and a tone: 23 GB / 13 GB and
    # killed past 60 s before; refused now at the profile, saying why and the limit
    s, p = files(tmp_path, mixture(2, tones, rms))
    result = run("sweep", s, p, "--format", "csv")
    refused_at(result, p, 4, 9, "profile 'p'", *words)
