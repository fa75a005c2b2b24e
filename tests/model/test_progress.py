"""The one progress protocol: reports, clamping, cancel from another thread, sub-ranges."""

from __future__ import annotations

import threading

import pytest

from mrm.core.errors import Cancelled
from mrm.core.progress import NO_PROGRESS, Progress, ProgressLike

# ----------------------------------------------------------------------------------------------------------
# Progress and cancel
# ----------------------------------------------------------------------------------------------------------


def test_progress_reports_clamps_and_never_goes_back() -> None:
    seen: list[tuple[float, str]] = []
    p = Progress(lambda f, m: seen.append((f, m)))
    p.update(0.25, "a")
    p.update(2.0)
    p.update(0.1, "b")
    p.update(float("nan"))
    assert seen == [(0.25, "a"), (1.0, "a"), (1.0, "b"), (1.0, "b")]
    assert p.fraction == 1.0 and p.message == "b" and not p.cancelled


def test_cancel_from_another_thread_stops_the_work_at_its_next_report() -> None:
    p = Progress()
    reports = []
    started = threading.Event()

    def work() -> None:
        try:
            for i in range(10**9):
                p.update(i / 10**9)
                reports.append(i)
                started.set()
        except Cancelled:
            reports.append(-1)

    t = threading.Thread(target=work)
    t.start()
    started.wait(5)
    p.cancel()
    t.join(5)
    assert not t.is_alive() and reports[-1] == -1 and p.cancelled
    with pytest.raises(Cancelled):
        p.check()


def test_concurrent_updates_are_consistent() -> None:
    p = Progress()

    def work(k: int) -> None:
        for i in range(2000):
            p.update((i + k) / 4000, f"w{k}")

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert p.fraction == (1999 + 3) / 4000 and p.message.startswith("w")


def test_sub_progress_maps_and_shares_the_cancel() -> None:
    seen: list[float] = []
    p = Progress(lambda f, m: seen.append(f))
    half = p.sub(0.5, 1.0)
    half.update(0.5)
    quarter = half.sub(0.0, 0.5)
    quarter.update(1.0)
    assert seen == [0.75, 0.75]
    half.sub(0.5, 1.0).update(1.0)
    assert seen[-1] == 1.0
    p.cancel()
    assert half.cancelled and quarter.cancelled
    with pytest.raises(Cancelled):
        quarter.update(0.2)


def test_the_null_progress_never_cancels() -> None:
    for i in range(3):
        NO_PROGRESS.update(i / 2, "x")
    assert not NO_PROGRESS.cancelled and NO_PROGRESS.sub(0, 1) is NO_PROGRESS
    assert isinstance(Progress(), ProgressLike) and isinstance(NO_PROGRESS, ProgressLike)


def test_a_stop_flag_is_set_by_a_cancel_and_says_the_last_dropped_report():
    # What a compiled kernel reads to stop (mrm.core.progress.stop_flag): 0 until the progress is cancelled,
    # 1 soon after; and the report a throttled progress dropped just before the kernel reaches the window.
    import time

    from mrm.core.progress import stop_flag

    seen: list[str] = []
    progress = Progress(lambda _f, m: seen.append(m), min_interval=0.05)
    progress.update(0.5, "computing the Euclidean representation")
    progress.update(None, "simplifying a safety net")  # dropped: 50 ms have not passed
    assert seen == ["computing the Euclidean representation"]
    with stop_flag(progress) as flag:
        deadline = time.monotonic() + 10
        while seen[-1] != "simplifying a safety net" and time.monotonic() < deadline:
            time.sleep(0.01)  # the kernel, reporting nothing
        assert seen[-1] == "simplifying a safety net" and flag[0] == 0
        progress.cancel()
        while flag[0] == 0 and time.monotonic() < deadline:
            time.sleep(0.01)
        assert flag[0] == 1
    with stop_flag(None) as flag:  # nothing to cancel: 0, and no thread
        assert flag[0] == 0
