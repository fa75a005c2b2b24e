"""What the window says when background work fails, and what it logs.

A user error (:class:`~mrm.core.errors.MRMError`) is shown as its message. Anything else — a bug, a job or
result that could not cross to or from a worker process, a worker process that died — is shown as what failed
plus "an internal error", and its traceback (the worker's, where it was raised) goes to the log. Either way
the panel that waited for the work stops waiting: nothing stays "computing…".
"""

from __future__ import annotations

import logging
import traceback

from mrm.core.errors import MRMError

#: The attribute :func:`log_failure` sets on its log records (the GUI tests fail on an unexpected one).
FAILURE_RECORD = "mrm_unexpected_failure"


def failure_message(exc: BaseException) -> str:
    """One line for the user: a user error's message, else what failed and where the details are."""
    if isinstance(exc, MRMError):
        return str(exc)
    text = str(exc) or type(exc).__name__
    return f"{text} — an internal error ({type(exc).__name__}); the details are in the log"


def traceback_text(exc: BaseException) -> str:
    """The traceback of ``exc`` where it was raised: in a worker thread, or in a worker process."""
    text = getattr(exc, "__traceback_text__", "")
    return text or "".join(traceback.format_exception(exc))


def log_failure(logger: logging.Logger, what: str, exc: BaseException) -> None:
    """Log an unexpected failure of ``what`` with its traceback (a user error is not logged)."""
    if isinstance(exc, MRMError):
        return
    logger.error("%s failed:\n%s", what, traceback_text(exc), extra={FAILURE_RECORD: True})
