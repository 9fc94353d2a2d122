"""The worker processes of ``--jobs N`` (docs/fleet.md).

:func:`run_in_processes` starts N worker processes once for the whole run and hands
each a path and the next one (a worker holds one recording at a time; the second path
waits in its pipe so that it need not wait for its caller); a worker answers with the
step's result only (a fit is tens of kB, never the samples) and is then given the next
path. Every worker, and the
calling process while it runs the step itself (:func:`one_thread`), runs one
BLAS/OpenMP thread: N processes use N cores, and no more.

Workers are started by ``fork`` on Linux — a copy of this process, numpy, scipy and
gyrovib already imported, ready in milliseconds — and by ``forkserver`` (``spawn``
where there is none) elsewhere, where forking a process that has loaded system
frameworks is unsafe. A worker ignores SIGINT and SIGHUP (a Ctrl-C reaches the
whole process group: the caller decides) and dies on SIGTERM; whatever ends the
run early — a failure, or an exception such as a signal's ``KeyboardInterrupt`` in
the caller — terminates the workers before it propagates. A worker whose caller
has gone (killed outright) notices within a second of finishing its current
recording, and exits.

What goes wrong in a worker comes back as data naming its recording: a user error
(:class:`Failed`, re-raised as the same :class:`~gyrovib.errors.GyrovibError`), or
an unexpected exception or a worker that died (:class:`Crashed`, raised as
:class:`~gyrovib.errors.Crash`, the worker's traceback as its cause).
"""

from __future__ import annotations

import contextlib
import dataclasses
import os
import pickle
import signal
import sys
import traceback
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any

from gyrovib.errors import Crash, GyrovibError, OptionError, Problem
from gyrovib.frozen import Frozen
from gyrovib.progress import advance, receiving

#: The environment variables that set the thread count of the BLAS and OpenMP
#: libraries a worker may load after it starts (threadpoolctl limits those loaded).
THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS",
                    "BLIS_NUM_THREADS", "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS")

#: The signals held back while workers start (those of them the platform has).
_SIGNALS = tuple(getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP")
                 if hasattr(signal, name))

#: Paths a worker holds at most: the one it runs and the next, so that it need not wait
#: for its caller (busy, or not given a core at once) between two recordings.
_AHEAD = 2

#: Seconds an idle worker waits for its next path before it checks its caller is alive.
_ALIVE_CHECK = 1.0


@contextlib.contextmanager
def one_thread() -> Iterator[None]:
    """Inside the block every BLAS and OpenMP library loaded in this process runs one
    thread (threadpoolctl); the limits are restored after it. The modules a fit loads
    lazily (scipy.signal and its BLAS) are loaded first, so that they are limited too."""
    # lazy: the thread limits of a run over recordings only
    from threadpoolctl import threadpool_limits

    load_step_modules()
    with threadpool_limits(limits=1):
        yield


def load_step_modules() -> None:
    """Import the modules a fit loads lazily (scipy.signal), if they are installed: a
    worker forked afterwards has them, and the thread limits reach their libraries."""
    with contextlib.suppress(ImportError):  # without scipy the step says what to install
        import scipy.signal  # noqa: F401


# ----------------------------------------------------------------- outcomes


@dataclass(frozen=True, eq=False, repr=False)
class Failed(Frozen):
    """A user error raised by the step: its class and problems."""

    kind: type[GyrovibError]
    problems: tuple[Problem, ...]
    #: An :class:`~gyrovib.errors.OptionError`'s argument, value, reason and others, so
    #: that the command line can still word it with its options.
    option: tuple[str | None, str | None, str | None, tuple[str, ...]] | None = None

    def error(self, path: str) -> GyrovibError:
        if self.option is not None:
            argument, value, reason, others = self.option
            return OptionError(self.problems, argument=argument, value=value,
                               reason=reason, others=others)
        try:
            return self.kind(self.problems)
        except TypeError:  # a subclass with another signature: the root keeps the words
            return GyrovibError(self.problems)


@dataclass(frozen=True, eq=False, repr=False)
class Crashed(Frozen):
    """Not a user error: the step raised an unexpected exception (``kind`` its type name,
    ``detail`` its message, ``trace`` its traceback as text) or its worker died."""

    kind: str
    detail: str
    trace: str = ""

    def error(self, path: str) -> Crash:
        crash = Crash(path, self.kind, self.detail)
        if self.trace:
            crash.__cause__ = RemoteTraceback(self.trace)
        return crash


class RemoteTraceback(Exception):
    """The traceback of an exception raised in a worker, shown as the cause of the
    :class:`~gyrovib.errors.Crash` raised here."""

    def __str__(self) -> str:
        return "\n" + str(self.args[0]).rstrip("\n")


def located(exc: GyrovibError, path: str) -> GyrovibError:
    """``exc`` with its problems that name no file placed at ``path`` (the recording whose
    step raised it): among many recordings, the message says which."""
    if all(p.file is not None for p in exc.problems):
        return exc
    return _failed(exc, path).error(path)


def _failed(exc: GyrovibError, path: str) -> Failed:
    """``exc`` as a :class:`Failed`, its problems placed at ``path``."""
    option = ((exc.argument, exc.value, exc.template, exc.others)
              if isinstance(exc, OptionError) and exc.template is not None else None)
    return Failed(type(exc), _placed(exc.problems, path), option)


def _placed(problems: tuple[Problem, ...], path: str) -> tuple[Problem, ...]:
    return tuple(p if p.file is not None else dataclasses.replace(p, file=path)
                 for p in problems)


def outcome(step: Callable[[str, Any], Any], path: str, options: Any) -> Any:
    """``step(path, options)``, or what went wrong as a :class:`Failed` (its problems
    placed at ``path`` when they name no file) or a :class:`Crashed` (a
    ``KeyboardInterrupt`` or ``SystemExit`` still propagates)."""
    try:
        return step(path, options)
    except GyrovibError as exc:
        return _failed(exc, path)
    except Exception as exc:
        return Crashed(type(exc).__name__, str(exc), traceback.format_exc())


def raise_failure(result: Any, path: str) -> None:
    """Raise what ``result`` says went wrong with ``path``, if it is a failure."""
    if isinstance(result, Failed | Crashed):
        raise result.error(path)


# ----------------------------------------------------------------- a worker


def _serve(conn: Any, step: Callable[[str, Any], Any], options: Any) -> None:
    """A worker's life: set its signals and thread limits once, then for each
    ``(index, path)`` received send back ``(index, outcome)``, until told to stop
    (None), its caller is gone, or the connection closes."""
    caller = os.getppid()  # the command, or the forkserver that forked this worker for it
    for signum in _SIGNALS:
        signal.signal(signum, signal.SIG_DFL if signum == signal.SIGTERM else signal.SIG_IGN)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, _SIGNALS)
    for name in THREAD_VARIABLES:
        os.environ[name] = "1"
    with receiving(None), one_thread():  # progress is the caller's to report
        while True:
            try:
                while not conn.poll(_ALIVE_CHECK):
                    if os.getppid() != caller:
                        return
                task = conn.recv()
            except (EOFError, OSError):
                return
            if task is None:
                return
            index, path = task
            result = outcome(step, path, options)
            try:
                data = pickle.dumps((index, result), protocol=pickle.HIGHEST_PROTOCOL)
            except Exception as exc:  # a result that does not pickle is a bug, located
                data = pickle.dumps((index, Crashed(type(exc).__name__, str(exc),
                                                    traceback.format_exc())))
            try:
                conn.send_bytes(data)
            except OSError:  # the caller has gone
                return


class _Worker:
    """A worker process, its end of the connection and the indices it was given."""

    __slots__ = ("conn", "process", "tasks")

    def __init__(self, process: Any, conn: Any) -> None:
        self.process = process
        self.conn = conn
        self.tasks: deque[int] = deque()


def _context() -> Any:
    # lazy: the process pool of --jobs only
    import multiprocessing

    methods = multiprocessing.get_all_start_methods()
    if sys.platform.startswith("linux") and "fork" in methods:
        return multiprocessing.get_context("fork")
    return multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")


@contextlib.contextmanager
def _signals_blocked() -> Iterator[None]:
    """SIGINT, SIGTERM and SIGHUP held back while workers start: a forked worker must not
    run its caller's handlers before it has set its own (it unblocks them then)."""
    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, _SIGNALS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def _start(count: int, step: Callable[[str, Any], Any], options: Any) -> list[_Worker]:
    context = _context()
    if context.get_start_method() == "fork":
        load_step_modules()  # once here, not once per worker
    workers: list[_Worker] = []
    try:
        with _signals_blocked():  # a signal held back here is raised as the block ends
            for _ in range(count):
                mine, theirs = context.Pipe()
                process = context.Process(target=_serve, args=(theirs, step, options),
                                          daemon=True, name="gyrovib-worker")
                workers.append(_Worker(process, mine))
                process.start()
                theirs.close()
    except BaseException:
        _stop(workers, at_once=True)
        raise
    return workers


def _stop(workers: Sequence[_Worker], *, at_once: bool) -> None:
    """Ask the workers to stop (``at_once``: terminate them), then reap them; a worker still
    there after a moment is killed."""
    for w in workers:
        if w.process.pid is None:
            continue
        if at_once:
            w.process.terminate()
        else:
            with contextlib.suppress(OSError):
                w.conn.send(None)
    for w in workers:
        if w.process.pid is None:
            continue
        w.process.join(1.0)
        if w.process.exitcode is None:
            w.process.kill()
            w.process.join(1.0)
        w.conn.close()


def _died(process: Any) -> Crashed:
    code = process.exitcode
    if code is not None and code < 0:
        try:
            how = f"killed by {signal.Signals(-code).name}"
        except ValueError:
            how = f"killed by signal {-code}"
    else:
        how = f"exit status {code}"
    return Crashed("worker process died", f"{how} while handling this recording")


# ----------------------------------------------------------------- the caller


def run_in_processes(paths: Sequence[str], options: Any, jobs: int,
                     step: Callable[[str, Any], Any], label: str) -> list[Any]:
    """``outcome(step, path, options)`` for every path in ``jobs`` worker processes, in
    input order (progress under ``label``). At the first failure no further path is
    handed out; the list then ends at the first failure in input order (the paths
    before it done), and the workers are terminated."""
    total = len(paths)
    outcomes: list[Any] = [None] * total
    first_bad = total
    done = given = 0
    workers = _start(min(jobs, total), step, options)
    at_once = True
    try:
        for w in workers:
            given = _give(w, paths, given, len(workers))
        while any(j < first_bad for w in workers for j in w.tasks):
            for w, index, result in _answers(workers):
                outcomes[index] = result
                done += 1
                advance(label, done, total)
                if isinstance(result, Failed | Crashed):
                    first_bad = min(first_bad, index)
                elif first_bad == total:
                    given = _give(w, paths, given, len(workers))
        at_once = first_bad < total
    finally:
        _stop(workers, at_once=at_once)
    return outcomes[:first_bad + 1]


def _give(worker: _Worker, paths: Sequence[str], given: int, workers: int) -> int:
    """Hand ``worker`` paths up to :data:`_AHEAD` (one once no more than one a worker is
    left: the last ones go to whichever worker is free first); the count given."""
    while given < len(paths) and len(worker.tasks) < (_AHEAD if len(paths) - given > workers
                                                      else 1):
        worker.conn.send((given, paths[given]))
        worker.tasks.append(given)
        given += 1
    return given


def _answers(workers: list[_Worker]) -> Iterator[tuple[_Worker, int, Any]]:
    """Wait for at least one answer: ``(worker, index, outcome)`` for each received; a
    worker that died answers :class:`Crashed` for the path it had and leaves ``workers``."""
    from multiprocessing.connection import wait

    busy = [w for w in workers if w.tasks]
    ready = set(wait([w.conn for w in busy] + [w.process.sentinel for w in busy]))
    for w in busy:
        if w.conn in ready or w.process.sentinel in ready:
            try:
                if w.conn.poll():
                    index, result = pickle.loads(w.conn.recv_bytes())
                    w.tasks.popleft()
                    yield w, index, result
                    continue
            except (EOFError, OSError):
                pass
            if w.process.sentinel in ready or not w.process.is_alive():
                w.process.join(1.0)
                index = w.tasks.popleft()
                w.tasks.clear()
                workers.remove(w)
                _stop([w], at_once=True)
                yield w, index, _died(w.process)
