"""Large rate tables: the reader in blocks and the fit in blocks give what one pass gives.

The reader reads plain blocks of rows at once and any other line one by one
(gyrovib.api.ratetable.reading); the fit factors the design block by block (CholeskyQR2,
Householder QR when ill-conditioned; gyrovib.core.fit). The expected values here are
the same table read or fitted in one block (the block sizes made large), and the
line numbers of the file as written.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gyrovib.api.ratetable import reading as ratetable
from gyrovib.api.ratetable.reading import RateTableError, read_rate_table
from gyrovib.core import fit as core_fit
from tests.conftest import invoke

LEVELS = np.array([-300.0, -200.0, -100.0, -50.0, -20.0, 0.0, 20.0, 50.0, 100.0, 200.0, 300.0])


def rows(unit: str, n: int, seed: int) -> list[str]:
    """``n`` rows of a unit with eq. (2) k0 = 0.1, A1 = 2e-3, k2 = 3e-6, k3 = -4e-9, K1 = 25,
    rates drawn from LEVELS, noise 0.05."""
    rng = np.random.default_rng(seed)
    w = LEVELS[rng.integers(0, LEVELS.size, n)]
    u = 25.0 * (0.1 + w + 1e-3 * np.abs(w) + 3e-6 * w**2 - 4e-9 * w**3)
    u += rng.normal(0.0, 0.05, n)
    return [f"{unit},{a:g},{b:.4f}" for a, b in zip(w, u, strict=True)]


@pytest.fixture
def small_blocks(monkeypatch: pytest.MonkeyPatch) -> None:
    """Blocks of ~200 characters (a few dozen rows) and of 7 design rows."""
    monkeypatch.setattr(ratetable, "BLOCK_CHARS", 200)
    monkeypatch.setattr(core_fit, "BLOCK_ROWS", 7)


def interleaved(tmp_path: Path) -> Path:
    """Two units interleaved, a comment and a blank line and a quoted cell in the middle."""
    a, b = rows("a", 300, 1), rows("b", 300, 2)
    body = [r for pair in zip(a, b, strict=True) for r in pair]
    body[200:200] = ["# a comment in the middle", "", '"a",20,500.5']
    path = tmp_path / "mixed.csv"
    path.write_text("# made here\nunit,rate,output\n" + "\n".join(body) + "\n",
                    encoding="utf-8")
    return path


def test_blocks_read_what_one_pass_reads(tmp_path: Path, monkeypatch: pytest.MonkeyPatch
                                         ) -> None:
    path = interleaved(tmp_path)
    whole = read_rate_table(path)  # the defaults: the file is one quick block or two
    monkeypatch.setattr(ratetable, "BLOCK_CHARS", 200)
    parts = read_rate_table(path)
    assert parts.units == whole.units == ("a", "b")  # order of first appearance
    for k in range(2):
        np.testing.assert_array_equal(parts.rate[k], whole.rate[k])
        np.testing.assert_array_equal(parts.output[k], whole.output[k])
        np.testing.assert_array_equal(parts.lines[k], whole.lines[k])
    text = path.read_text(encoding="utf-8").splitlines()
    # the line numbers are the file's: the quoted row "a",20,500.5 is line 205
    # (2 header lines, 200 rows, the comment and the blank line before it)
    at = int(np.flatnonzero(whole.lines[0] == 205)[0])
    assert text[204] == '"a",20,500.5' and whole.output[0][at] == 500.5
    assert whole.rate[0].size == 301 and whole.rate[1].size == 300


def test_a_bad_cell_far_down_is_located(tmp_path: Path, small_blocks: None) -> None:
    body = rows("a", 2000, 3)
    body[1500] = "a,20,12..5"
    body[1800] = "a,twenty,1"
    path = tmp_path / "bad.csv"
    path.write_text("unit,rate,output\n" + "\n".join(body) + "\n", encoding="utf-8")
    with pytest.raises(RateTableError) as caught:
        read_rate_table(path)
    assert [str(p) for p in caught.value.problems] == [
        f"{path}:1502:6: output: '12..5' is not a number",  # header line + 1501st row
        f"{path}:1802:3: rate: 'twenty' is not a number"]


def test_ragged_and_non_finite_rows_inside_a_block_are_located(tmp_path: Path) -> None:
    body = rows("a", 100, 4)
    body[10] = "a,20"
    body[20] = "a,20,inf"
    body[30] = "a b,20,1"
    path = tmp_path / "ragged.csv"
    path.write_text("unit,rate,output\n" + "\n".join(body) + "\n", encoding="utf-8")
    with pytest.raises(RateTableError) as caught:
        read_rate_table(path)
    assert [(p.line, p.column) for p in caught.value.problems] == [(12, 1), (22, 6), (32, 1)]


def test_the_size_limit(tmp_path: Path) -> None:
    """docs/rate-table.md: a file over 16 MiB is refused before it is parsed."""
    path = tmp_path / "huge.csv"
    line = b"1,25.0\n"
    path.write_bytes(b"rate,output\n" + line * (ratetable.MAX_BYTES // len(line) + 1))
    result = invoke("fit", path)
    assert result.exit_code == 2
    assert f"{path}: the file is larger than 16 MiB" in result.stderr


def test_fit_in_blocks_is_the_fit_in_one(tmp_path: Path, monkeypatch: pytest.MonkeyPatch
                                         ) -> None:
    path = interleaved(tmp_path)
    table = read_rate_table(path)
    one = core_fit.fit_rate_table(table.rate[0], table.output[0], 3)
    monkeypatch.setattr(core_fit, "BLOCK_ROWS", 7)
    parts = core_fit.fit_rate_table(table.rate[0], table.output[0], 3)
    scale = np.maximum(np.abs(one.values), one.sigma)  # round-off, on the scale of σ
    assert np.all(np.abs(parts.values - one.values) <= 1e-10 * scale)
    np.testing.assert_allclose(parts.sigma, one.sigma, rtol=1e-10)
    np.testing.assert_allclose(parts.residuals, one.residuals, rtol=0,
                               atol=1e-9 * np.max(np.abs(table.output[0])))


def test_cholesky_qr_and_householder_agree() -> None:
    """Both factorisations of one design: R up to the signs of its rows, and Qᵀv likewise."""
    rng = np.random.default_rng(5)
    w = LEVELS[rng.integers(0, LEVELS.size, 500)]
    v = np.sin(w / 100.0) + rng.normal(0.0, 0.01, w.size)
    scaling = core_fit._scaling(w, 5, None, ())
    quick = core_fit._cholesky_qr(w, v, 5, None, scaling)
    assert quick is not None  # a well-conditioned design: no fallback
    r_h, qtv_h = core_fit._householder(w, v, 5, None, scaling)
    signs = np.sign(np.diag(quick[0])) * np.sign(np.diag(r_h))
    np.testing.assert_allclose(quick[0], signs[:, None] * r_h, rtol=1e-10,
                               atol=1e-12 * np.max(np.abs(r_h)))
    np.testing.assert_allclose(quick[1], signs * qtv_h, rtol=1e-9, atol=1e-12)


def test_an_ill_conditioned_design_falls_back_to_householder() -> None:
    """Rates at ±1 and within 1e-4 of ±1 (and 0): |x| and x² nearly coincide over them, the
    scaled design's condition number is far above 1e7, so CholeskyQR2 declines and the
    Householder factorisation is used (here it too finds the columns dependent)."""
    w = np.array([-1.0, -1.0 + 1e-9, 0.0, 1.0 - 1e-9, 1.0] * 4)
    scaling = core_fit._scaling(w, 2, None, ())
    assert core_fit._cholesky_qr(w, w, 2, None, scaling) is None
