"""Python-heavy work runs in worker processes (ADR 0025): results, errors and Cancel come back intact.

The window's operations, inspector measurements and big project files go through
:class:`mrm.app.processes.ProcessPool`, so a worker never holds the GIL the window's painting needs.
"""

from __future__ import annotations

import os
import threading
import time

import numpy as np
import pytest

from mrm.app import processes
from mrm.app.tasks import TaskProgress
from mrm.core.errors import Cancelled, ParameterError
from mrm.core.grids import PixelSet
from tests.app import process_job_fixtures as jobs


@pytest.fixture
def pool():  # type: ignore[no-untyped-def]
    p = processes.ProcessPool(2)
    yield p
    p.close()


def _local_job(progress):  # type: ignore[no-untyped-def]
    return 1  # pytest imports this module under a name the child does not know


def test_a_job_runs_in_another_process_and_arrays_come_back_exactly(pool):  # type: ignore[no-untyped-def]
    spill = processes._spill_dir()
    before = {f for f in os.listdir(spill) if f.startswith(processes.SPILL_PREFIX)}
    pid = pool.run(jobs.whoami, (), TaskProgress())
    assert pid != os.getpid() and pid in pool.pids
    rng = np.random.default_rng(5)
    mask = rng.random((1500, 1700)) < 0.5  # 2.5 M pixels: sent out of band, as raw bytes
    ps = PixelSet(mask, (-40, 7))
    back = pool.run(jobs.echo, (ps,), TaskProgress())
    assert back == ps and back is not ps
    assert not back.mask.flags.writeable  # still a frozen pixel set
    assert back.origin == (-40, 7) and back.count == ps.count
    # The mask went both ways through a file in memory, removed once read.
    assert ps.mask.nbytes > processes.SPILL_BYTES
    assert {f for f in os.listdir(spill) if f.startswith(processes.SPILL_PREFIX)} <= before


def test_progress_is_relayed_and_a_cancel_stops_the_job(pool):  # type: ignore[no-untyped-def]
    seen: list[float] = []
    progress = TaskProgress(lambda f, _m: seen.append(f))
    threading.Timer(0.8, progress.cancel).start()
    t0 = time.monotonic()
    with pytest.raises(Cancelled):
        pool.run(jobs.counting, (30.0,), progress)
    assert time.monotonic() - t0 < 10  # not the 30 s of the job
    assert seen and 0 < max(seen) < 1
    # The child is reused for the next job.
    assert pool.run(jobs.counting, (0.05,), TaskProgress()) == "finished"


def test_a_job_deaf_to_cancel_is_stopped_by_killing_its_process(pool):  # type: ignore[no-untyped-def]
    progress = TaskProgress()
    threading.Timer(0.5, progress.cancel).start()
    t0 = time.monotonic()
    with pytest.raises(Cancelled):
        pool.run(jobs.deaf, (60.0,), progress)
    assert time.monotonic() - t0 < processes.CANCEL_GRACE + 5
    assert pool.run(jobs.whoami, (), TaskProgress()) != os.getpid()  # a fresh child


def test_errors_come_back_as_themselves_and_a_dead_child_is_replaced(pool):  # type: ignore[no-untyped-def]
    with pytest.raises(ParameterError, match="α must be positive, got -3"):
        pool.run(jobs.refusing, (), TaskProgress())
    with pytest.raises(RuntimeError, match="ended unexpectedly"):
        pool.run(jobs.dying, (), TaskProgress())
    with pytest.raises(ModuleNotFoundError):  # a job the child cannot import is refused, the child lives on
        pool.run(_local_job, (), TaskProgress())
    assert pool.run(jobs.whoami, (), TaskProgress()) != os.getpid()


def test_the_window_applies_an_operation_in_a_worker_process(make_window, qtbot):  # type: ignore[no-untyped-def]
    from PySide6 import QtCore

    from mrm.document.commands import AddObject
    from tests.app.helpers import colour_at, is_background, task_done, wait_drawn

    win = make_window(threaded=True)
    yy, xx = np.mgrid[0:60, 0:60]
    obj = win.doc.make_object(PixelSet((xx - 30) ** 2 + (yy - 30) ** 2 < 25**2, (0, 0)), name="disk")
    win.doc.push(AddObject(obj, select=True))
    before = processes.pool().jobs
    panel = win.operations
    panel.select_operation("dss")
    panel.control("alpha").set_value(2.0)
    with task_done(qtbot, win.runner, "operation"):
        qtbot.mouseClick(panel.apply_button, QtCore.Qt.MouseButton.LeftButton)
    assert len(win.doc) == 2
    assert processes.pool().jobs > before
    assert os.getpid() not in processes.pool().pids
    result = win.doc.objects[-1]
    assert result.provenance is not None and result.provenance.operation == "dss"
    # Twice the size: the scaled disk covers (60, 60), which the input did not.
    win.fit_all()
    wait_drawn(qtbot, win)
    assert not is_background(win.views.discrete, colour_at(win.views.discrete, 60, 60))


def _spills() -> set[str]:
    folder = processes._spill_dir()
    return {f for f in os.listdir(folder) if f.startswith(processes.SPILL_PREFIX)}


def test_a_child_dying_or_killed_mid_transfer_leaves_no_spill_file(pool):  # type: ignore[no-untyped-def]
    """The issue: a child killed while an array was on its way left a file of its size in /dev/shm."""
    before = _spills()
    with pytest.raises(RuntimeError, match="ended unexpectedly"):
        pool.run(jobs.dying_mid_transfer, (), TaskProgress())
    assert _spills() <= before
    progress = TaskProgress()
    threading.Timer(0.8, progress.cancel).start()
    with pytest.raises(Cancelled):
        pool.run(jobs.spilling_then_deaf, (60.0,), progress)
    assert _spills() <= before
    # Arguments sent to a child that died before reading them are removed too.
    child = pool._take()
    child.proc.kill()
    child.proc.wait(5)
    pool._give_back(child)  # an idle child that died meanwhile
    big = np.ones(2 * processes.SPILL_BYTES, np.uint8)
    for _ in range(2):  # the dead child may be taken again before a fresh one starts
        try:
            assert pool.run(jobs.echo, (big,), TaskProgress()).sum() == big.sum()
            break
        except (RuntimeError, OSError):
            pass
    assert _spills() <= before


def test_spill_files_of_ended_processes_are_removed_at_start(tmp_path):  # type: ignore[no-untyped-def]
    import subprocess
    import sys

    gone = subprocess.Popen([sys.executable, "-c", "pass"])
    gone.wait()
    folder = processes._spill_dir()
    stale = os.path.join(folder, f"{processes.SPILL_PREFIX}{gone.pid}-test")
    live = os.path.join(folder, f"{processes.SPILL_PREFIX}{os.getpid()}-test")
    for path in (stale, live):
        with open(path, "wb") as fh:
            fh.write(b"x" * 100)
    try:
        processes.close_pool()
        processes.pool()  # the window's first job creates the pool
        assert not os.path.exists(stale)
        assert os.path.exists(live)  # a running process's file (this one's) is left alone
    finally:
        processes.close_pool()
        processes.remove_spills([stale, live])


def test_a_received_pixel_set_keeps_the_received_memory_and_pickles_at_every_protocol():
    """A 77 M-pixel result was copied twice on its way (sender and receiver, 77 MB of fresh memory each): now
    its mask travels as a buffer and the receiver keeps the memory it read the spill into."""
    import mmap
    import pickle
    from multiprocessing import Pipe

    rng = np.random.default_rng(4)
    m = rng.random((1500, 900)) < 0.5  # 1.35 MB: spilled (over SPILL_BYTES)
    m[0, 0] = m[-1, -1] = True
    ps = PixelSet(m, (-7, 12))
    a, b = Pipe()
    sender = threading.Thread(target=lambda: processes.send_obj(a, ("result", ps, "")))
    sender.start()
    _kind, got, _text = processes.recv_obj(b)
    sender.join()
    assert got == ps and got.origin == ps.origin and not got.mask.flags.writeable
    root = got.mask
    while isinstance(root, np.ndarray) and root.base is not None:
        root = root.base
    assert isinstance(root, mmap.mmap)  # the spill's memory itself, not a copy of it
    for protocol in range(2, pickle.HIGHEST_PROTOCOL + 1):
        back = pickle.loads(pickle.dumps(ps, protocol=protocol))
        assert back == ps and not back.mask.flags.writeable


def test_freed_memory_is_kept_for_the_next_arrays_in_the_window_and_its_workers(monkeypatch):
    """Unmapping every freed array made each derivation fault gigabytes in again, which on a VM reporting
    free pages to its host stalled the whole machine: the window keeps freed memory, and passes the
    setting on to its worker processes; MRM_KEEP_MEMORY=0 turns it off."""
    import ctypes.util
    import sys

    from mrm.app.application import MALLOC_ENV, keep_freed_memory

    for key in MALLOC_ENV:
        monkeypatch.delenv(key, raising=False)
    monkeypatch.setenv("MRM_KEEP_MEMORY", "0")
    assert not keep_freed_memory() and not any(k in os.environ for k in MALLOC_ENV)
    monkeypatch.delenv("MRM_KEEP_MEMORY")
    glibc = sys.platform.startswith("linux") and "libc" in (ctypes.util.find_library("c") or "")
    assert keep_freed_memory() == glibc
    if glibc:
        assert all(os.environ[k] == v for k, v in MALLOC_ENV.items())  # what a child process starts with


def test_a_size_limit_error_reaches_the_window_with_its_message(pool):  # type: ignore[no-untyped-def]
    # It used to arrive as "TypeError: SizeLimitError.__init__() missing … 'limit'" (DSS 4.5 of DSS 20 of
    # the horse in the window), a traceback instead of the message that says what to change.
    from mrm.core.errors import SizeLimitError

    with pytest.raises(SizeLimitError, match=r"DSS_4\.5 would cover 158,000,000 pixels") as info:
        pool.run(jobs.over_limit, (), TaskProgress())
    assert (info.value.estimated, info.value.limit) == (158_000_000, 100_000_000)
    # An exception the window cannot rebuild comes back as its text; the pool goes on working.
    with pytest.raises(RuntimeError, match="_Stubborn: stubborn 1 2"):
        pool.run(jobs.unpicklable_error, (), TaskProgress())
    assert pool.run(jobs.whoami, (), TaskProgress()) != os.getpid()


def test_a_warmed_child_takes_the_first_job_with_the_operations_loaded(pool):  # type: ignore[no-untyped-def]
    """Issue 27: the first operation after a start waited for a cold child (8–9 s on 193 pixels)."""
    pool.warm()
    pool.warm()  # one child is there already: no second one
    assert pool._count == 1
    pid, loaded, nice = pool.run(jobs.modules_loaded, (), TaskProgress())
    assert loaded  # it loaded the operations before its first job, not during it
    assert pool.pids == {pid} and pool._count == 1  # the job went to the warmed child
    # Its warm-up ran at the window's priority (a loaded machine starved it for minutes at +10); its jobs
    # run below the window.
    assert nice == min(19, os.nice(0) + processes.CHILD_NICENESS)
    # A child started for a job does not warm up first: it is the job's own imports that load.
    pool2 = processes.ProcessPool(1)
    try:
        _pid, loaded2, _nice = pool2.run(jobs.modules_loaded, (), TaskProgress())
        assert not loaded2
    finally:
        pool2.close()


def test_arrays_come_back_writable_as_they_were_sent_small_or_big(pool):  # type: ignore[no-untyped-def]
    """A small array came back read-only (unpickled from bytes) and a big one writable (spilled): numba
    compiles a kernel again for each read-only argument, so the desktop's first 3D operation after the
    warm-up recompiled the voxelization kernels for the triangles it received."""
    triangles = np.arange(30, dtype=np.int64).reshape(10, 3)
    big = np.ones(2 * processes.SPILL_BYTES, np.uint8)
    small_back, big_back = pool.run(jobs.echo, ((triangles, big),), TaskProgress())
    assert np.array_equal(small_back, triangles) and small_back.dtype == np.int64
    assert small_back.flags.writeable and small_back.flags.c_contiguous
    assert big_back.flags.writeable and big_back.sum() == big.sum()
    frozen = PixelSet(np.ones((3, 4), bool), (0, 0))
    assert not pool.run(jobs.echo, (frozen,), TaskProgress()).mask.flags.writeable  # a frozen value stays so
