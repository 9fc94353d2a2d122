"""``--jobs N`` (docs/fleet.md): workers that start once and run one BLAS thread each, a
failure in a worker named by its recording, and a signal that stops the workers too.

The speed itself is measured by benchmarks/bench_fleet.py, not here."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
import traceback
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.conftest import invoke
from tests.test_cli_terminal import clean_env

pytest.importorskip("scipy.signal")
pytest.importorskip("threadpoolctl")

FS = 250.0
linux_only = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="workers are forked (and so patched) on Linux only")


@pytest.fixture(scope="module")
def logs(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    """Four 20-second recordings of Gaussian noise and a 31.3 Hz tone (.npy columns)."""
    folder = tmp_path_factory.mktemp("jobs")
    rng = np.random.default_rng(40)
    paths = []
    for name in "abcd":
        t = np.arange(int(20 * FS)) / FS
        rate = rng.normal(0.0, 0.3, (t.size, 3))
        rate += np.outer(np.sin(2 * np.pi * 31.3 * t), (0.2, 0.2, 0.4))
        np.save(folder / f"{name}.npy", rate)
        paths.append(folder / f"{name}.npy")
    return paths


# ----------------------------------------------------------------- steps run in workers
# (module functions: a worker started by forkserver or spawn finds them by name)


def _threads(path: str, options: Any) -> tuple[int, list[int]]:
    """The process running the step and the thread counts of its BLAS/OpenMP libraries."""
    from threadpoolctl import threadpool_info

    return os.getpid(), sorted({int(lib["num_threads"]) for lib in threadpool_info()})


def _crashing(path: str, options: Any) -> str:
    if path.endswith("c"):
        raise IndexError("index 7 is out of bounds for axis 0 with size 7")
    return path


def _dying(path: str, options: Any) -> str:
    if path.endswith("c"):
        os.kill(os.getpid(), signal.SIGKILL)
    return path


def _user_error(path: str, options: Any) -> str:
    from gyrovib.errors import OptionError

    if path.endswith(("c", "d")):
        raise OptionError(f"no vibration above the crossover in {path[-1]}")
    return path


# ----------------------------------------------------------------- workers


def test_workers_start_once_and_run_one_blas_thread() -> None:
    """Ten paths on two workers: at most two processes, neither this one, each with every
    BLAS/OpenMP library at one thread; --jobs 1 runs the step here, at one thread too,
    and puts the limits back afterwards."""
    from threadpoolctl import threadpool_info

    from gyrovib.api.fleet.run import run_recordings

    paths = [f"log-{k}" for k in range(10)]
    before = [lib["num_threads"] for lib in threadpool_info()]
    two = run_recordings(paths, None, jobs=2, step=_threads)
    pids = {pid for pid, _ in two}
    assert len(pids) <= 2 and os.getpid() not in pids
    assert all(threads == [1] for _, threads in two)
    one = run_recordings(paths, None, jobs=1, step=_threads)
    assert {pid for pid, _ in one} == {os.getpid()}
    assert all(threads == [1] for _, threads in one)
    assert [lib["num_threads"] for lib in threadpool_info()] == before


@pytest.mark.parametrize(("module", "name", "args"), [
    # the commands import the library when they run: patched where they take it from
    ("gyrovib.api.recordings.fit", "fit_recording", ["profile"]),
    ("gyrovib.api.recordings.analysis", "analyze_recording",
     ["analyze", "--sensor", "adxrs645", "--recording"]),
])
def test_one_recording_is_fitted_at_one_blas_thread(
        logs: list[Path], monkeypatch: pytest.MonkeyPatch, module: str, name: str,
        args: list[str]) -> None:
    """A single recording (no workers: the command's own process, --jobs 1) is fitted with
    every BLAS/OpenMP library at one thread; the limits are put back afterwards."""
    import importlib

    from threadpoolctl import threadpool_info

    target = importlib.import_module(module)
    real = getattr(target, name)
    seen: list[list[int]] = []

    def counting(*a: Any, **k: Any) -> Any:
        seen.append(sorted({int(lib["num_threads"]) for lib in threadpool_info()}))
        return real(*a, **k)

    monkeypatch.setattr(target, name, counting)
    before = [lib["num_threads"] for lib in threadpool_info()]
    result = invoke(*args, logs[0], "--fs", FS, "--format", "json")
    assert result.exit_code == 0, result.stderr
    assert seen == [[1]]
    assert [lib["num_threads"] for lib in threadpool_info()] == before


@pytest.mark.parametrize("jobs", [1, 2])
def test_an_unexpected_exception_names_its_recording(jobs: int) -> None:
    from gyrovib.api.fleet.run import run_recordings
    from gyrovib.errors import Crash

    with pytest.raises(Crash) as raised:
        run_recordings(["a", "b", "c", "d"], None, jobs=jobs, step=_crashing)
    crash = raised.value
    assert (crash.file, crash.kind) == ("c", "IndexError")
    assert crash.detail == "index 7 is out of bounds for axis 0 with size 7"
    # the exception (from a worker: its traceback) is the cause: GYROVIB_DEBUG=1 prints it
    assert crash.__cause__ is not None
    assert "in _crashing" in "".join(traceback.format_exception(crash.__cause__))


def test_a_worker_that_dies_is_named_by_its_recording() -> None:
    from gyrovib.api.fleet.run import run_recordings
    from gyrovib.errors import Crash

    with pytest.raises(Crash) as raised:
        run_recordings(["a", "b", "c", "d", "e", "f"], None, jobs=2, step=_dying)
    assert raised.value.file == "c"
    assert raised.value.kind == "worker process died"
    assert "killed by SIGKILL" in raised.value.detail


@pytest.mark.parametrize("jobs", [1, 2])
def test_the_first_user_error_in_input_order_is_placed_at_its_recording(jobs: int) -> None:
    """A user error that names no file is placed at the recording whose step raised it;
    of two, the first in input order is raised whichever finished first."""
    from gyrovib.api.fleet.run import run_recordings
    from gyrovib.errors import OptionError

    with pytest.raises(OptionError) as raised:
        run_recordings(["a", "b", "c", "d"], None, jobs=jobs, step=_user_error)
    assert [str(p) for p in raised.value.problems] == [
        "c: no vibration above the crossover in c"]


@linux_only
@pytest.mark.parametrize(("exc", "status", "words"), [
    (IndexError("index 3 is out of bounds"), 3,
     "internal error: IndexError: index 3 is out of bounds; this is a bug in gyrovib"),
    (MemoryError(), 2, "error: out of memory"),
])
def test_the_command_line_names_the_recording_whatever_jobs(
        logs: list[Path], monkeypatch: pytest.MonkeyPatch, exc: BaseException, status: int,
        words: str) -> None:
    """A crash while reading c.npy (the reader patched here; forked workers inherit the
    patch): --jobs 1 and --jobs 2 give the same status and the same one line."""
    from gyrovib.api.fleet import run

    real = run.read_recording

    def broken(path: str, **options: Any) -> Any:
        if path.endswith("c.npy"):
            raise exc
        return real(path, **options)

    monkeypatch.setattr(run, "read_recording", broken)
    outcomes = []
    for jobs in (1, 2):
        result = invoke("profile", *logs, "--fs", FS, "--jobs", jobs)
        outcomes.append((result.exit_code, result.stdout, result.stderr))
    assert outcomes[0] == outcomes[1]
    code, out, err = outcomes[0]
    assert code == status and out == ""
    assert err.startswith(f"{logs[2]}: {words}"), err
    assert len(err.splitlines()) == 1


# ----------------------------------------------------------------- signals

#: ``gyrovib profile`` whose reader announces itself, then sleeps two minutes: a run
#: that waited for its workers (or its queue) would take minutes, not seconds.
SLOW = "\n".join([
    "import os, sys, time",
    "from gyrovib.api.fleet import run",
    "def slow(path, **options):",
    "    sys.stderr.write(f'started {os.getpid()}\\n'); sys.stderr.flush()",
    "    time.sleep(120)",
    "run.read_recording = slow",
    "from gyrovib.cli.main import main",
    "main(sys.argv[1:])",
])


def _gone(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] == "Z"  # dead, not yet reaped
    except FileNotFoundError:
        return True


@linux_only
@pytest.mark.parametrize(("sig", "to_group", "status", "word"), [
    (signal.SIGINT, True, 130, "interrupted"),     # Ctrl-C: the whole process group
    (signal.SIGTERM, False, 143, "terminated"),    # kill PID: the command alone
    (signal.SIGTERM, True, 143, "terminated"),     # a supervisor stopping the group
    (signal.SIGHUP, False, 129, "hung up"),
])
def test_a_signal_stops_the_run_and_its_workers(tmp_path: Path, sig: int, to_group: bool,
                                                status: int, word: str) -> None:
    """Twenty recordings on two workers, each taking two minutes: the signal, sent once
    both workers are busy, ends the command with its status and one line, and neither
    worker outlives it. (The time this takes is measured by hand: docs/fleet.md.)"""
    paths = []
    for k in range(20):
        paths.append(tmp_path / f"log-{k:02d}.npy")
        paths[-1].write_text(f"recording {k}\n")
    process = subprocess.Popen(
        [sys.executable, "-c", SLOW, "profile", *map(str, paths), "--fs", "250", "--jobs", "2"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=clean_env(),
        cwd=tmp_path, start_new_session=True)
    watchdog = threading.Timer(240, process.kill)  # a hang fails the test, not the suite
    watchdog.start()
    try:
        assert process.stderr is not None
        workers = set()
        while len(workers) < 2:
            line = process.stderr.readline()
            assert line.startswith("started "), line + process.stderr.read()
            workers.add(int(line.split()[1]))
        if to_group:
            os.killpg(process.pid, sig)
        else:
            process.send_signal(sig)
        out, err = process.communicate(timeout=90)
    finally:
        watchdog.cancel()
    assert process.returncode == status, err
    assert err.strip() == f"gyrovib: {word}" and out == ""
    deadline = time.monotonic() + 30  # generous: the command reaps them before it exits
    while not all(_gone(pid) for pid in workers) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert all(_gone(pid) for pid in workers)


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_bad_option_among_several_recordings_names_the_option_and_the_file(
        logs: list[Path], jobs: int) -> None:
    # the library words it crossover=0 (its argument); through the workers the command
    # line still words it as its option, placed at the recording whose step refused it
    r = invoke("profile", *logs[:2], "--fs", FS, "--crossover", 0, "--jobs", jobs)
    assert r.exit_code == 2, r.stderr
    assert f"{logs[0]}: --crossover 0: give a positive frequency" in r.stderr
    assert "crossover=0" not in r.stderr
