"""The report describes and plots every profile, and prints each warning once: a
locked-harmonic profile is charted (not called "no vibration"), linear spectra are plotted, and
a warning shared by many sensors is not repeated for each."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.conftest import invoke


@pytest.fixture(scope="module")
def bundled_html(tmp_path_factory: pytest.TempPathFactory) -> str:
    """`gyrovib report --budget 10deg/h -o all.html` of the bundled catalogues, run once
    for the module: both tests read the same command's file (the report is a pure
    function of the catalogues and the budget), so one run checks what two did."""
    target: Path = tmp_path_factory.mktemp("report") / "all.html"
    done = invoke("report", "--budget", "10deg/h", "-o", str(target))
    assert done.exit_code == 0, done.stderr
    return target.read_text(encoding="utf-8")


def test_the_report_describes_and_plots_every_profile(bundled_html: str) -> None:
    # every bundled profile gets a chart of its vibration: rotor-harmonics (locked
    # orders only) its orders at n·f0, the shaker tests their linear PSD in g²/Hz
    html = bundled_html
    sections = html.split('<section class="profile"')[1:]
    assert len(sections) == 14
    for section in sections:
        assert "Spectrum: " in section or "Linear vibration: " in section, section[:200]
        assert "no vibration" not in section
    rotor = next(s for s in sections if "rotor-harmonics" in s[:300])
    assert "phase-locked harmonics: f0 = " in rotor and "Spectrum: rotor-harmonics" in rotor
    shaker = next(s for s in sections if "adis16460-vre-test" in s[:300])
    assert "Linear vibration: adis16460-vre-test" in shaker and "(g)²/Hz" in shaker
    # identical warnings once each, with their cells
    warnings = html.split('<ul class="warnings">')[1].split("</ul>")[0]
    items = warnings.split("<li>")[1:]
    assert len(items) == len(set(items)) <= 5


def test_the_matrix_splits_to_fit_a_printed_page(bundled_html: str) -> None:
    # 14 profiles: two pass/fail tables of at most 7 profile columns, each with the
    # sensor and overall columns, on A4 landscape pages
    html = bundled_html
    assert "@page { size: A4 landscape;" in html
    matrices = html.split('<table class="matrix">')[1:]
    assert len(matrices) == 2
    profiles = []
    for table in matrices:
        head = table.split("</thead>")[0]
        cells = [c.split("</th>")[0] for c in head.split("<th>")[1:]]
        assert cells[:2] == ["sensor", "overall"] and len(cells) - 2 <= 7
        profiles += cells[2:]
    assert len(profiles) == 14 == len(set(profiles))


def test_every_term_has_its_own_colour() -> None:
    # A1 and q3·Ω³ shared a colour (11 terms, 10 colours)
    from gyrovib.render.report import term_names
    from gyrovib.render.svg import color

    names = term_names(linear=True, locked=True)
    assert len(names) == 11
    assert len({color(k) for k in range(len(names))}) == len(names)
