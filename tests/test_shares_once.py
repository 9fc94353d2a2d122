"""The shares of Δ* are printed once, also when some profile has linear vibration.

Under a profile with linear vibration the g² term takes a share α6 and α1…α5
shrink (docs/model.md section 8); the legend of ``select`` and the report's inputs
print each share once, the value under linear vibration in brackets after it.

Expected values by hand (docs/model.md section 6, default allocation r = 1.5,
w = (1, 1, 1, ½, ½), w6 = 1): c_A = 1.5/√3.25 = 0.8320503; without linear
vibration ‖w‖ = √3.5 = 1.8708287, α1 = c_A/‖w‖ = 0.4447, α4 = ½·0.4447 = 0.2224;
with it ‖w‖ = √4.5 = 2.1213203, α1 = α6 = 0.3922, α4 = 0.1961.
"""

from __future__ import annotations

import re

import gyrovib
from gyrovib import api
from gyrovib.api.report.views import trade_study
from gyrovib.render.bounds import shares_text
from gyrovib.render.report import to_html
from gyrovib.render.select import to_markdown

PROFILES = ("cruise-hard-mounted", "cruise-isolated")  # bundled, both with linear vibration


def test_shares_text_merges_the_two_sets() -> None:
    result = gyrovib.select(gyrovib.load(), budget=10 / 3600, profiles=PROFILES,
                            sensors="generic-navigation-rlg")
    assert result.has_linear
    text = shares_text(result.allocation, linear=True)
    assert text.startswith("A1 α1 = 0.4447 [0.3922], k2 α2 = 0.4447 [0.3922], ")
    assert "m31 α4 = 0.2224 [0.1961]" in text and text.endswith("vre α6 = [0.3922]")
    # the β shares do not move: printed without brackets
    assert "k4 α3 = 0.4447 [0.3922] | β2 = 0.2265," in text
    assert shares_text(result.allocation) == shares_text(result.allocation, linear=False)
    assert "[" not in shares_text(result.allocation)


def test_select_legend_and_report_print_each_share_once() -> None:
    result = gyrovib.select(gyrovib.load(), budget=10 / 3600, profiles=PROFILES,
                            sensors=("generic-navigation-rlg", "adis16460"))
    legend = to_markdown(result).split("Cells: ")[1]
    for alpha in ("α1", "α2", "α3", "α4", "α5", "α6"):
        assert len(re.findall(alpha + " =", legend)) == 1, alpha
    html = to_html(trade_study(api.load(), budget=10 / 3600, profiles=PROFILES,
                               sensors=("generic-navigation-rlg",)))
    inputs = html.split("<h2>Inputs</h2>")[1].split("<h2>")[0]
    assert len(re.findall("α1 =", inputs)) == 1 and "α1 = 0.4447 [0.3922]" in inputs
