"""Regenerate docs/img/report.png: the bundled report, rendered by headless Chromium.

    .venv/bin/python tools/screenshot_report.py [--budget 10deg/h] [--chromium PATH]

Writes the report of the bundled catalogues (``gyrovib report --budget
10deg/h``) to a temporary file and takes a 1280×2000 screenshot of its top
with the Chromium that tests/test_browser.py uses (Debian: ``apt-get install
chromium``). Exit status 2 when no Chromium is found.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from click.testing import CliRunner

from gyrovib.cli.main import cli

ROOT = Path(__file__).resolve().parents[1]
CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")


def chromium_command(binary: str, profile: Path, page: Path, png: Path,
                     size: str = "1280,2000") -> list[str]:
    """Headless Chromium, offline and quiet, logging console messages to stderr."""
    return [binary, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
            "--no-first-run", "--disable-background-networking", "--disable-component-update",
            "--disable-sync", f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0",
            "--hide-scrollbars", f"--screenshot={png}", f"--window-size={size}",
            page.resolve().as_uri()]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--budget", default="10deg/h")
    parser.add_argument("--chromium", default=None)
    parser.add_argument("--output", default=str(ROOT / "docs" / "img" / "report.png"))
    args = parser.parse_args()
    binary = args.chromium or next(filter(None, map(shutil.which, CANDIDATES)), None)
    if binary is None:
        print("no Chromium found: apt-get install chromium, or give --chromium PATH",
              file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        page = Path(tmp) / "report.html"
        done = CliRunner().invoke(cli, ["report", "--budget", args.budget, "-o", str(page)])
        if done.exit_code != 0:
            print(done.output, file=sys.stderr)
            return 2
        subprocess.run(chromium_command(binary, Path(tmp) / "profile", page, Path(args.output)),
                       check=True, capture_output=True, timeout=120)
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
