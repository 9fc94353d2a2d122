"""The distributions: built from a tree without symbolic links, the wheel carries
the bundled catalogues as real files and the license; the sdist carries the
tests and docs, and its tests pass from the unpacked sdist.

Building takes a few seconds (``python -m build --no-isolation``, with the
setuptools and build of the test extras): marked slow, still in the default run.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

import pytest

pytest.importorskip("build")

ROOT = Path(__file__).resolve().parent.parent
CATALOGUES = ("missions.gyrovib.yaml", "profiles.gyrovib.yaml", "sensors.gyrovib.yaml")
IGNORE = shutil.ignore_patterns(".git", ".venv*", "__pycache__", "*.egg-info", "build", "dist",
                                ".pytest_cache", ".hypothesis", ".mypy_cache", ".ruff_cache",
                                ".benchmarks")


@pytest.fixture(scope="module")
def dists(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path, Path]:
    """(source copy, sdist, wheel): the wheel is built from the sdist, as pip does."""
    work = tmp_path_factory.mktemp("dist")
    tree = work / "tree"
    shutil.copytree(ROOT, tree, symlinks=True, ignore=IGNORE)
    out = work / "out"
    done = subprocess.run([sys.executable, "-m", "build", "--no-isolation", "--outdir",
                           str(out), str(tree)], capture_output=True, text=True, timeout=300,
                          check=False)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    (sdist,) = out.glob("gyrovib-*.tar.gz")
    (wheel,) = out.glob("gyrovib-*.whl")
    return tree, sdist, wheel


@pytest.mark.slow
def test_the_source_tree_has_no_symbolic_link(dists: tuple[Path, Path, Path]) -> None:
    # a clone with core.symlinks=false would turn a link into a text file
    tree, _, _ = dists
    links = [p for p in tree.rglob("*") if p.is_symlink()]
    assert links == []
    assert not (tree / "catalogs").exists()  # one copy: the package data


@pytest.mark.slow
def test_wheel_has_the_catalogues_and_the_license(dists: tuple[Path, Path, Path]) -> None:
    tree, _, wheel = dists
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
        for name in CATALOGUES:
            data = archive.read(f"gyrovib/catalogs/{name}")
            assert data == (tree / "src" / "gyrovib" / "catalogs" / name).read_bytes()
            assert b"gyrovib: 1" in data
        metadata = archive.read(next(n for n in names if n.endswith(".dist-info/METADATA")))
        assert b"License-Expression: MIT" in metadata
        assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)
        for info in archive.infolist():  # no member is a symbolic link
            assert (info.external_attr >> 16) & 0o170000 != 0o120000, info.filename


@pytest.mark.slow
def test_installed_wheel_finds_its_catalogues(dists: tuple[Path, Path, Path],
                                              tmp_path: Path) -> None:
    _, _, wheel = dists
    with zipfile.ZipFile(wheel) as archive:
        archive.extractall(tmp_path / "site")
    env = {**os.environ, "PYTHONPATH": str(tmp_path / "site")}
    where = subprocess.run([sys.executable, "-c", "import gyrovib; print(gyrovib.__file__)"],
                           capture_output=True, text=True, env=env, cwd=tmp_path, check=True)
    assert where.stdout.startswith(str(tmp_path / "site")), where.stdout
    # without FILE arguments: the bundled catalogues (a symlinked build crashed here, exit 3)
    done = subprocess.run([sys.executable, "-m", "gyrovib", "analyze", "--format", "csv"],
                          capture_output=True, text=True, timeout=120, check=False, env=env,
                          cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert len(done.stdout.splitlines()) == 1 + 9 * 14  # header + 9 sensors × 14 profiles


@pytest.mark.slow
def test_sdist_has_tests_docs_and_license_and_its_tests_pass(
        dists: tuple[Path, Path, Path], tmp_path: Path) -> None:
    _, sdist, _ = dists
    with tarfile.open(sdist) as archive:
        members = archive.getmembers()
        assert not [m.name for m in members if m.issym() or m.islnk()]
        archive.extractall(tmp_path, filter="data")
    (top,) = tmp_path.iterdir()
    for path in ("LICENSE", "README.md", "docs/ci.md", "tests/conftest.py",
                 "tests/test_docs_commands.py", *(f"src/gyrovib/catalogs/{c}" for c in CATALOGUES)):
        assert (top / path).is_file(), path
    env = {**os.environ, "PYTHONPATH": str(top / "src")}
    where = subprocess.run([sys.executable, "-c", "import gyrovib; print(gyrovib.__file__)"],
                           capture_output=True, text=True, env=env, cwd=top, check=True)
    assert where.stdout.startswith(str(top)), where.stdout  # the sdist's code, not ours
    # a quick, representative part of the suite: the loader on the bundled catalogues,
    # and the documented commands run from the unpacked tree
    done = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider",
         "tests/test_loader.py", "tests/test_docs_commands.py"],
        capture_output=True, text=True, env=env, cwd=top, timeout=300, check=False)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-2000:]
    assert " passed" in done.stdout.splitlines()[-1]
