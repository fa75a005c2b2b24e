"""Long Python-heavy work in worker *processes*, so that it never holds the GUI process's GIL (ADR 0025).

Threads of one process share one GIL: while a worker thread runs Python (the exact Hausdorff measurement, an
operation's rational arithmetic, a project's JSON), every paint of the window waits for it, turn after turn,
and on a busy machine a pan of four views took a second. A job sent here runs in a child process instead; the
worker thread that sent it only waits on a pipe (no GIL held), relays the child's progress and passes a
Cancel on.

A job is a module-level function ``fn(*args, progress)`` (:mod:`mrm.app.process_jobs`): the child imports it
by name. Arguments and results travel pickled with protocol 5, numpy arrays *out of band*: each array's bytes
go through the pipe as one message, written and read with the GIL released, and are never re-encoded.

The children are fresh interpreters (``python -m mrm.app.processes``; a fork of a process running Qt threads
is unsafe), started lazily, at most :data:`MAX_PROCESSES`, each running one job at a time, at a lower
scheduling priority than the window; a Cancel reaches them as SIGUSR1. They end with the window, or with the
parent, whose end closes their pipe. :meth:`ProcessPool.warm` starts one at the window's start-up that loads
the operations and kernels before its first job (ADR 0042).

Every failure comes back to the caller as an exception, never as a hang: a job or a result that does not
pickle (:class:`WorkerError`, the pipe left clean), an exception of the job (itself, or its kind and text when
it does not travel), a child that died (:class:`WorkerError` with its exit status).
"""

from __future__ import annotations

import contextlib
import logging
import os
import pickle
import threading
import time
import traceback
from collections.abc import Callable
from typing import Any

from mrm.core.errors import Cancelled

log = logging.getLogger(__name__)

#: Children at most (the machine has few cores; a third job waits for one of them).
MAX_PROCESSES = 2
#: After a Cancel, how long the child may take to reach its next progress check before it is killed.
CANCEL_GRACE = 3.0
#: How much lower than the window a child is scheduled (nice increment).
CHILD_NICENESS = 10


# ---------------------------------------------------------------------------------------------- the wire
#: Arrays bigger than this go through a file in memory (``/dev/shm``) instead of the pipe: a pipe moves
#: 64 KB per system call, and each call of the receiving thread takes the GIL back from the window's thread,
#: a thousand times for a 77 M-pixel mask. A file is written and read in one call each, the GIL released.
SPILL_BYTES = 1 << 20


#: The prefix of the files arrays are spilled to: ``mrm-spill-<writer's pid>-<random>``. The receiver removes
#: a file as soon as it has read it; the parent removes what a task left behind when its child died or was
#: killed mid-transfer (:meth:`ProcessPool.run`), and at start the files of processes that no longer run
#: (:func:`remove_stale_spills`).
SPILL_PREFIX = "mrm-spill-"


def _spill_dir() -> str:
    """Where big arrays are spilled: ``/dev/shm`` (memory) when writable, else the temp folder."""
    import tempfile

    shm = "/dev/shm"
    return shm if os.path.isdir(shm) and os.access(shm, os.W_OK) else tempfile.gettempdir()


def _spill(raw: memoryview) -> str:
    import tempfile

    fd, path = tempfile.mkstemp(prefix=f"{SPILL_PREFIX}{os.getpid()}-", dir=_spill_dir())
    with os.fdopen(fd, "wb", buffering=0) as fh:
        view = raw.cast("B")
        done = 0
        while done < len(view):
            done += fh.write(view[done:])
    return path


def _unspill(path: str) -> Any:
    import mmap

    size = os.path.getsize(path)
    # Anonymous memory, not bytearray(size): that zero-fills the whole buffer with the GIL held (tens of ms
    # at 77 MB); these pages are touched by the read below, with the GIL released. And not a numpy array:
    # an array unpickled from this buffer then belongs to no other array, so a pixel set keeps it as its
    # mask without a copy (PixelSet.__reduce_ex__).
    data = mmap.mmap(-1, max(1, size))
    view = memoryview(data)
    try:
        with open(path, "rb", buffering=0) as fh:
            done = 0
            while done < size:
                n = fh.readinto(view[done:size])
                if not n:
                    raise EOFError(f"{path}: {done} of {size} bytes")
                done += n
    finally:
        os.unlink(path)
    return view[:size]


class WorkerError(RuntimeError):
    """The worker-process machinery failed: a job or its result that does not pickle, a child that died.

    Not a user error (:class:`~mrm.core.errors.MRMError`): its message says what failed, for the window's
    status bar and inspector, and the traceback goes to the log.
    """


class _Encoded:
    """An object pickled for :func:`send_obj`: its head, its out-of-band arrays, the files of the big ones.

    Encoding comes first and sends nothing: an object that does not pickle fails here, with the pipe still
    clean, so the caller can send something else instead (a child its error, the parent nothing at all).
    """

    def __init__(self, obj: Any) -> None:
        bufs: list[pickle.PickleBuffer] = []
        self.head = pickle.dumps(obj, protocol=5, buffer_callback=bufs.append)
        self.raws = [b.raw() for b in bufs]
        self.files: list[str | None] = []
        try:
            for r in self.raws:
                self.files.append(_spill(r) if r.nbytes > SPILL_BYTES else None)
        except BaseException:
            self.discard()
            raise

    def spilled(self) -> list[str]:
        return [f for f in self.files if f is not None]

    def discard(self) -> None:
        """Remove the spill files (nothing will read them)."""
        remove_spills(self.spilled())

    def send(self, conn: Any) -> list[str]:
        """Send it; returns the spill files (the receiver removes them once read, the sender otherwise)."""
        try:
            conn.send_bytes(pickle.dumps(self.files))
            conn.send_bytes(self.head)
            for r, f in zip(self.raws, self.files, strict=True):
                if f is None:
                    conn.send_bytes(r)
        except BaseException:
            self.discard()  # the receiver will never read them
            raise
        return self.spilled()


def send_obj(conn: Any, obj: Any) -> list[str]:
    """Send ``obj`` pickled (protocol 5); its contiguous arrays out of band, never re-encoded.

    An array of more than :data:`SPILL_BYTES` is written to a file in memory and only its name is sent.
    Returns those files' paths: the receiver removes them once read, the sender if it never reads them.
    """
    return _Encoded(obj).send(conn)


def remove_spills(paths: list[str]) -> None:
    """Remove spill files that may still be there (a receiver removed the ones it read)."""
    for path in paths:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(path)


def _spill_pid(name: str) -> int | None:
    """The writer's process id in a spill file's name, if it has one."""
    pid, sep, _rest = name[len(SPILL_PREFIX) :].partition("-")
    return int(pid) if sep and pid.isdigit() else None


def spills_of(pid: int) -> list[str]:
    """The spill files process ``pid`` wrote that are still there."""
    folder = _spill_dir()
    head = f"{SPILL_PREFIX}{pid}-"
    try:
        names = os.listdir(folder)
    except OSError:
        return []
    return [os.path.join(folder, n) for n in names if n.startswith(head)]


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process: it runs
        return True
    return True


def remove_stale_spills() -> int:
    """Remove the spill files of processes that no longer run (a crash, a kill); returns how many.

    Files of running processes, this one's and other windows' included, are left alone.
    """
    folder = _spill_dir()
    try:
        names = [n for n in os.listdir(folder) if n.startswith(SPILL_PREFIX)]
    except OSError:
        return 0
    removed = 0
    for name in names:
        pid = _spill_pid(name)
        if pid is not None and not _running(pid):
            with contextlib.suppress(OSError):
                os.unlink(os.path.join(folder, name))
                removed += 1
    if removed:
        log.info("removed %d spill files of worker processes that had ended", removed)
    return removed


def _recv_parts(conn: Any) -> tuple[bytes, list[Any]]:
    files = pickle.loads(conn.recv_bytes())
    head = conn.recv_bytes()
    # A small array's bytes are copied into a bytearray (at most SPILL_BYTES): unpickled from bytes it would
    # be read-only, unlike the sender's and a spilled one's, and numba compiles a kernel once more for each
    # read-only argument: the desktop's first 3D operation recompiled the voxelization kernels (ADR 0025).
    return head, [bytearray(conn.recv_bytes()) if f is None else _unspill(f) for f in files]


def recv_obj(conn: Any) -> Any:
    """Receive what :func:`send_obj` sent."""
    head, bufs = _recv_parts(conn)
    return pickle.loads(head, buffers=bufs)


# ---------------------------------------------------------------------------------------------- the child
_CANCEL = threading.Event()  # in a child: set by SIGUSR1, the parent's Cancel


def _portable(exc: BaseException) -> BaseException:
    """``exc`` if it comes back from pickling as itself, else an error of the same kind carrying its text.

    An exception whose constructor takes other arguments than its message pickles but does not unpickle;
    the window would get a TypeError instead of the user's message. A user error stays a user error.
    """
    try:
        pickle.loads(pickle.dumps(exc, protocol=5))
        return exc
    except Exception:
        from mrm.core.errors import MRMError

        log.warning("%s does not travel between processes; sent as its text", type(exc).__name__)
        kind = MRMError if isinstance(exc, MRMError) else RuntimeError
        return kind(str(exc) if kind is MRMError else f"{type(exc).__name__}: {exc}")


def _child_progress(conn: Any) -> Any:
    """The progress a job sees in the child: reports go to the parent, a Cancel comes as a signal."""
    from mrm.app.progress import TaskProgress

    return TaskProgress(lambda fraction, message: send_obj(conn, ("progress", fraction, message)), _CANCEL)


def _warm_child() -> None:
    """Load the operations and the cached kernels before the first job (a child started ahead of need)."""
    try:
        from mrm.app.process_jobs import warm
        from mrm.core.progress import NO_PROGRESS

        warm(NO_PROGRESS)
    except Exception:  # the jobs load what they need anyway; a failed warm-up only costs time
        traceback.print_exc()


def _outcome(fn: Any, result: Any) -> _Encoded:
    """The message carrying a job's result, or, when the result does not pickle, an error saying so."""
    try:
        return _Encoded(("result", result, ""))
    except Exception as exc:
        text = traceback.format_exc()
        name = getattr(fn, "__name__", "the job")
        err = WorkerError(f"the worker process could not send back the result of {name} ({exc})")
        return _Encoded(("error", err, text))


def _child_main(fd_in: int, fd_out: int, warm: bool = False) -> None:
    """The loop of a child: one job at a time until the parent closes the pipe.

    With ``warm``, the child first loads what the jobs need (:func:`_warm_child`); a job sent meanwhile
    waits in the pipe, which is sooner than starting a cold child for it.
    """
    import signal
    from multiprocessing.connection import Connection

    signal.signal(signal.SIGUSR1, lambda *_a: _CANCEL.set())
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl+C in a terminal is for the window, which stops us
    conn_in, conn_out = Connection(fd_in, writable=False), Connection(fd_out, readable=False)
    if warm:
        # At the window's priority: the user's first operation waits for this, and a busy machine starved
        # it for minutes at +10 (ADR 0042). It is a second or two of CPU, once.
        _warm_child()
    with contextlib.suppress(OSError):  # not permitted in some sandboxes: the child then runs at par
        os.nice(CHILD_NICENESS)
    while True:
        try:
            head, bufs = _recv_parts(conn_in)
        except (EOFError, OSError):
            return
        _CANCEL.clear()
        progress = _child_progress(conn_out)
        fn: Any = None
        try:
            fn, args = pickle.loads(head, buffers=bufs)  # a job that does not import is its error
            result = fn(*args, progress)
        except BaseException as exc:
            text = traceback.format_exc()
            message = _Encoded(("error", _portable(exc), text))
        else:
            message = _outcome(fn, result)
        message.send(conn_out)


# ---------------------------------------------------------------------------------------------- the parent
class _Child:
    """One child: ``python -m mrm.app.processes`` with a pipe each way.

    Never a fork of this process, and never a re-run of the parent's main script (which ``multiprocessing``'s
    spawn does).
    """

    def __init__(self, warm: bool = False) -> None:
        import subprocess
        import sys
        from multiprocessing.connection import Connection

        to_child, from_parent = os.pipe()
        to_parent, from_child = os.pipe()
        args = [str(to_child), str(from_child)] + (["--warm"] if warm else [])
        try:
            self.proc = subprocess.Popen(
                [sys.executable, "-m", "mrm.app.processes", *args],
                pass_fds=(to_child, from_child),
                stdin=subprocess.DEVNULL,
            )
        finally:
            os.close(to_child)
            os.close(from_child)
        self.send = Connection(from_parent, readable=False)
        self.recv = Connection(to_parent, writable=False)

    def alive(self) -> bool:
        return self.proc.poll() is None

    def cancel(self) -> None:
        import signal

        if self.alive():
            self.proc.send_signal(signal.SIGUSR1)

    def kill(self) -> None:
        for c in (self.send, self.recv):
            with contextlib.suppress(OSError):
                c.close()
        if self.alive():
            self.proc.kill()
        with contextlib.suppress(Exception):
            self.proc.wait(2.0)


class ProcessPool:
    """Runs jobs in child processes; :meth:`run` is called from worker threads and blocks until the end."""

    def __init__(self, size: int = MAX_PROCESSES) -> None:
        self.size = max(1, int(size))
        self._idle: list[_Child] = []
        self._count = 0
        self._cond = threading.Condition()
        self._closed = False
        self.jobs = 0  # jobs sent to a child so far
        self.pids: set[int] = set()  # the children's process ids

    def _take(self) -> _Child:
        with self._cond:
            while True:
                if self._closed:
                    raise Cancelled("closing")
                while self._idle:
                    c = self._idle.pop()
                    if c.alive():
                        return c
                    self._count -= 1
                if self._count < self.size:
                    self._count += 1
                    break
                self._cond.wait(0.2)
        try:
            return _Child()
        except BaseException:
            with self._cond:
                self._count -= 1
                self._cond.notify()
            raise

    def _give_back(self, child: _Child | None) -> None:
        with self._cond:
            if child is not None and not self._closed:
                self._idle.append(child)
            else:
                self._count -= 1
                if child is not None:
                    child.kill()
            self._cond.notify()

    def warm(self) -> None:
        """Start a child now that loads what the jobs need (the window's start-up); returns at once.

        The child is idle for the pool at once: the first job goes to it, and waits in its pipe for the rest
        of the warm-up, rather than starting a second, cold child (ADR 0042). Nothing is started when a child
        is already there.
        """
        with self._cond:
            if self._closed or self._idle or self._count >= self.size:
                return
            self._count += 1
        try:
            child = _Child(warm=True)
        except BaseException:
            with self._cond:
                self._count -= 1
                self._cond.notify()
            raise
        self._give_back(child)

    def run(self, fn: Callable[..., Any], args: tuple[Any, ...], progress: Any) -> Any:
        """``fn(*args, progress)`` in a child; its progress relayed to ``progress``, a Cancel passed on.

        A child that dies or is killed mid-task takes no spill file with it: the task's own (arguments the
        child did not read) and the child's (results it had begun to send) are removed.
        """
        if progress is not None:
            progress.update()
        name = getattr(fn, "__name__", repr(fn))
        try:  # before a child is taken: what does not pickle costs no child
            job = _Encoded((fn, args))
        except Exception as exc:
            raise WorkerError(f"{name} could not be sent to a worker process ({exc})") from exc
        try:
            child = self._take()
        except BaseException:
            job.discard()
            raise
        ok = False
        sent: list[str] = []
        try:
            sent = job.send(child.send)
            self.jobs += 1
            self.pids.add(child.proc.pid)
            cancelled_at: float | None = None
            while True:
                if child.recv.poll(0.05):
                    try:
                        kind, value, text = recv_obj(child.recv)
                    except (EOFError, OSError):
                        child.proc.wait(2.0)
                        if cancelled_at is not None:
                            raise Cancelled("cancelled") from None
                        raise WorkerError(_ended(name, child.proc.returncode)) from None
                    if kind == "progress":
                        if cancelled_at is None and progress is not None:
                            try:
                                progress.update(value, text)
                            except Cancelled:
                                cancelled_at = time.monotonic()
                                child.cancel()
                        continue
                    ok = True
                    if kind == "result":
                        if cancelled_at is not None:
                            raise Cancelled("cancelled")
                        return value
                    if not isinstance(value, Cancelled):
                        value.__traceback_text__ = text  # the child's traceback, for the log
                    raise value
                if not child.alive():
                    if cancelled_at is not None:
                        raise Cancelled("cancelled")
                    raise WorkerError(_ended(name, child.proc.returncode))
                if cancelled_at is None and progress is not None and getattr(progress, "cancelled", False):
                    cancelled_at = time.monotonic()
                    child.cancel()
                if cancelled_at is not None and time.monotonic() - cancelled_at > CANCEL_GRACE:
                    # A long kernel does not look at its progress: the child is stopped instead.
                    log.info("a worker process did not stop within %.0f s of a cancel: killed", CANCEL_GRACE)
                    raise Cancelled("cancelled")
        finally:
            self._give_back(child if ok else None)
            if not ok:
                child.kill()
                remove_spills(sent + spills_of(child.proc.pid))

    def close(self) -> None:
        """Stop every child (the window closes)."""
        with self._cond:
            self._closed = True
            idle, self._idle = self._idle, []
            self._count -= len(idle)
            self._cond.notify_all()
        for c in idle:
            c.kill()


def _ended(name: str, code: int | None) -> str:
    how = f"killed by signal {-code}" if code is not None and code < 0 else f"exit status {code}"
    return f"the worker process running {name} ended unexpectedly ({how})"


_POOL: ProcessPool | None = None
_POOL_LOCK = threading.Lock()


def pool() -> ProcessPool:
    """The application's process pool (created on first use, after clearing the spills of ended ones)."""
    global _POOL
    with _POOL_LOCK:
        if _POOL is None or _POOL._closed:
            remove_stale_spills()
            _POOL = ProcessPool()
        return _POOL


def close_pool() -> None:
    """Stop the application's worker processes, if any were started."""
    global _POOL
    with _POOL_LOCK:
        p, _POOL = _POOL, None
    if p is not None:
        p.close()


if __name__ == "__main__":
    import sys

    # Run the child's loop in the module imported by its name, not in ``__main__``: what it pickles (a
    # WorkerError) must name a class the window can import.
    from mrm.app import processes

    processes._child_main(int(sys.argv[1]), int(sys.argv[2]), warm="--warm" in sys.argv[3:])
