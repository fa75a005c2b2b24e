"""Background work in worker processes always ends where the user waits for it (issue 27, item 1).

The issue: on the fig09-10 example, clicking "EDco: E ∩ E'" left the inspector at "Measured: computing…" for
minutes; its worker process had died pickling the account back ("Can't pickle local object
'euclidean_discrete_corefinement.<locals>.union'"), and the error, not a user error, was re-raised in a Qt
slot and lost. ``mrm account`` gives 0.442 in seconds.
"""

from __future__ import annotations

import contextlib
import io
import json

import pytest
from PySide6.QtCore import Qt

from mrm.app import process_jobs
from mrm.document.commands import AddObject
from mrm.io.project import load_project
from mrm.ops.account import account_of
from mrm.resources import examples_dir
from tests.app import process_job_fixtures as jobs
from tests.app.helpers import HANG_MS, click_object, square

FIG09 = examples_dir() / "fig09-10-union-corefinement.mrm"
PART = "EDco: E ∩ E'"


def test_measuring_a_co_refinement_part_ends_with_the_value_mrm_account_gives(make_window, qtbot):
    from mrm.cli import run_cli

    # What the library and `mrm account` say, computed here from the file.
    (part,) = load_project(FIG09).find(PART)
    expected = account_of(part.provenance, measure=True).measured.value
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert run_cli(["account", str(FIG09), "--object", PART, "--json", "-q"]) == 0
    assert json.loads(out.getvalue())["measured"] == pytest.approx(expected, rel=0, abs=0)
    win = make_window(threaded=True)
    assert win.files.open(FIG09, ask=False)
    (obj,) = win.doc.find(PART)
    insp = win.inspector
    with qtbot.waitSignal(insp.measureEnded, timeout=HANG_MS) as ended:
        click_object(qtbot, win, obj.id)
    assert ended.args == ["measured"], insp.measured_label.text()
    assert win.doc.selection == (obj.id,)
    assert f"H = {expected:.4g}" in insp.measured_label.text()  # 0.4421
    assert insp.measurement.measured.value == expected


def _result(win):  # type: ignore[no-untyped-def]
    """A DSS result with its provenance (made through the model, as Apply does)."""
    from mrm.document.apply import apply_operation
    from mrm.ops.scaling import DSSParams

    a = win.doc.make_object(square(0, 0, 5), name="A")
    win.doc.push(AddObject(a))
    (new,) = apply_operation(win.doc, "dss", [a.id], DSSParams(alpha=2.0))
    return win.doc.get(new)


@pytest.mark.parametrize(
    ("job", "says"),
    [
        (jobs.unpicklable_result, "could not send back the result of unpicklable_result"),
        (jobs.buggy, "unsupported operand type(s) for +: 'int' and 'str' — an internal error (TypeError)"),
        (jobs.dying_measure, "ended unexpectedly (exit status 3)"),
    ],
    ids=["unpicklable-result", "exception", "process-dies"],
)
def test_a_measurement_failing_in_its_worker_process_says_so_in_the_inspector(
    make_window, qtbot, expect_failures, job, says
):
    win = make_window(threaded=True)
    result = _result(win)
    insp = win.inspector
    insp.measure_job = job  # the job the window hands the inspector, failing in the worker process
    with qtbot.waitSignal(insp.measureEnded, timeout=HANG_MS) as ended:
        click_object(qtbot, win, result.id)
    assert ended.args == ["failed"]
    text = insp.measured_label.text()
    assert "computing" not in text and "could not be computed" in text and says in text, text
    assert not insp.is_measuring()
    # The traceback (the worker's own) went to the log.
    (logged,) = expect_failures()
    assert f"measuring {result.name} failed" in logged and "Traceback" in logged
    # The pool is still usable: the real measurement runs next.
    insp.measure_job = process_jobs.measure
    with qtbot.waitSignal(insp.measureEnded, timeout=HANG_MS) as ended:
        qtbot.mouseClick(insp.measure_button, Qt.MouseButton.LeftButton)
    assert ended.args == ["measured"]


def test_a_job_whose_arguments_do_not_pickle_reaches_the_status_bar(make_window, qtbot, expect_failures):
    """A task with no error callback of its own: the window's status bar says what failed."""
    win = make_window(threaded=True)
    runner = win.runner
    with qtbot.waitSignal(runner.taskFailed, timeout=HANG_MS):
        runner.submit("job", lambda p: runner.call(jobs.echo, (lambda: 1,), p), label="Echoing")
    message = win.status.currentMessage()
    assert message.startswith("Echoing: echo could not be sent to a worker process"), message
    assert len(expect_failures()) == 1
