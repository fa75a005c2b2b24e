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
parent, whose end closes their pipe.
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


def send_obj(conn: Any, obj: Any) -> list[str]:
    """Send ``obj`` pickled (protocol 5); its contiguous arrays out of band, never re-encoded.

    An array of more than :data:`SPILL_BYTES` is written to a file in memory and only its name is sent.
    Returns those files' paths: the receiver removes them once read, the sender if it never reads them.
    """
    bufs: list[pickle.PickleBuffer] = []
    head = pickle.dumps(obj, protocol=5, buffer_callback=bufs.append)
    raws = [b.raw() for b in bufs]
    files: list[str | None] = []
    try:
        for r in raws:
            files.append(_spill(r) if r.nbytes > SPILL_BYTES else None)
        conn.send_bytes(pickle.dumps(files))
        conn.send_bytes(head)
        for r, f in zip(raws, files, strict=True):
            if f is None:
                conn.send_bytes(r)
    except BaseException:
        remove_spills([f for f in files if f is not None])  # the receiver will never read them
        raise
    return [f for f in files if f is not None]


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
    return head, [conn.recv_bytes() if f is None else _unspill(f) for f in files]


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


def _child_main(fd_in: int, fd_out: int) -> None:
    """The loop of a child: one job at a time until the parent closes the pipe."""
    import signal
    from multiprocessing.connection import Connection

    with contextlib.suppress(OSError):  # not permitted in some sandboxes: the child then runs at par
        os.nice(CHILD_NICENESS)
    signal.signal(signal.SIGUSR1, lambda *_a: _CANCEL.set())
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl+C in a terminal is for the window, which stops us
    conn_in, conn_out = Connection(fd_in, writable=False), Connection(fd_out, readable=False)
    while True:
        try:
            head, bufs = _recv_parts(conn_in)
        except (EOFError, OSError):
            return
        _CANCEL.clear()
        progress = _child_progress(conn_out)
        try:
            fn, args = pickle.loads(head, buffers=bufs)  # a job that does not import is its error
            result = fn(*args, progress)
        except BaseException as exc:
            text = traceback.format_exc()
            send_obj(conn_out, ("error", _portable(exc), text))
        else:
            send_obj(conn_out, ("result", result, ""))


# ---------------------------------------------------------------------------------------------- the parent
class _Child:
    """One child: ``python -m mrm.app.processes`` with a pipe each way.

    Never a fork of this process, and never a re-run of the parent's main script (which ``multiprocessing``'s
    spawn does).
    """

    def __init__(self) -> None:
        import subprocess
        import sys
        from multiprocessing.connection import Connection

        to_child, from_parent = os.pipe()
        to_parent, from_child = os.pipe()
        try:
            self.proc = subprocess.Popen(
                [sys.executable, "-m", "mrm.app.processes", str(to_child), str(from_child)],
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
        """Start a child now (the window's start-up), so that the first job does not wait for it."""
        child = self._take()
        self._give_back(child)

    def run(self, fn: Callable[..., Any], args: tuple[Any, ...], progress: Any) -> Any:
        """``fn(*args, progress)`` in a child; its progress relayed to ``progress``, a Cancel passed on.

        A child that dies or is killed mid-task takes no spill file with it: the task's own (arguments the
        child did not read) and the child's (results it had begun to send) are removed.
        """
        if progress is not None:
            progress.update()
        child = self._take()
        ok = False
        sent: list[str] = []
        try:
            sent = send_obj(child.send, (fn, args))
            self.jobs += 1
            self.pids.add(child.proc.pid)
            cancelled_at: float | None = None
            while True:
                if child.recv.poll(0.05):
                    try:
                        kind, value, text = recv_obj(child.recv)
                    except (EOFError, OSError):
                        child.proc.wait(2.0)
                        code = child.proc.returncode
                        raise RuntimeError(f"the worker process ended unexpectedly (exit {code})") from None
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
                    raise RuntimeError(
                        f"the worker process ended unexpectedly (exit {child.proc.returncode})"
                    )
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

    _child_main(int(sys.argv[1]), int(sys.argv[2]))
