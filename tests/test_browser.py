"""The bundled report in a real browser: headless Chromium, no console message, a screenshot.

Chromium started with ``--enable-logging=stderr --v=0`` writes every console
message of the page (errors, ``Uncaught`` exceptions, refused loads) to
stderr as an ``INFO:CONSOLE`` line; the report has no script and loads
nothing, so there must be none. The probe itself is checked on a page with a
deliberate error. Skipped where no Chromium is installed (Debian:
``apt-get install chromium``; ``.ci/run`` installs it where it can).
"""

from __future__ import annotations

import re
import shutil
import struct
import subprocess
from pathlib import Path

import pytest

from gyrovib import api
from gyrovib.api.trade_study import trade_study
from gyrovib.render.report import to_html

CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
CHROMIUM = next(filter(None, map(shutil.which, CANDIDATES)), None)

pytestmark = pytest.mark.skipif(
    CHROMIUM is None,
    reason="no Chromium on PATH (chromium, chromium-browser, google-chrome): "
           "apt-get install chromium to run the browser test",
)

CONSOLE = re.compile(r":CONSOLE[:(]|Uncaught")


def render(page: Path, tmp_path: Path, size: tuple[int, int]) -> tuple[bytes, list[str]]:
    """Screenshot of ``page`` (PNG bytes) and the console lines Chromium logged."""
    assert CHROMIUM is not None
    png = tmp_path / (page.stem + ".png")
    done = subprocess.run(
        [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
         "--no-first-run", "--disable-background-networking", "--disable-component-update",
         "--disable-sync", f"--user-data-dir={tmp_path / 'profile'}", "--enable-logging=stderr",
         "--v=0", f"--screenshot={png}", f"--window-size={size[0]},{size[1]}",
         page.resolve().as_uri()],
        capture_output=True, text=True, timeout=180, check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return png.read_bytes(), [line for line in done.stderr.splitlines() if CONSOLE.search(line)]


def png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    width, height = struct.unpack(">II", data[16:24])  # IHDR: the first chunk
    return width, height


def test_bundled_report_renders_without_console_errors(tmp_path):
    page = tmp_path / "report.html"
    page.write_text(to_html(trade_study(api.load(), budget=10 / 3600)), encoding="utf-8")
    data, console = render(page, tmp_path, (1280, 2000))
    assert console == []
    assert png_size(data) == (1280, 2000)
    assert len(data) > 20_000  # a blank page compresses to a few kB


def test_the_probe_sees_console_errors(tmp_path):
    page = tmp_path / "broken.html"
    page.write_text("<!DOCTYPE html><p>x</p><script>undefinedFunction()</script>",
                    encoding="utf-8")
    _, console = render(page, tmp_path, (400, 300))
    assert any("Uncaught ReferenceError" in line for line in console), console
