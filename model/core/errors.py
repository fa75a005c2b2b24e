"""Exceptions of the model layer.

Every error a user can cause (bad file, bad geometry, absurd parameter) is an :class:`MRMError`; the CLI
turns it into a one-line message and exit status 2, the GUI into a message box. Anything else is a bug.
"""

from __future__ import annotations


class MRMError(Exception):
    """Base class of every error caused by input (files, geometry, parameters)."""


class InvalidGeometryError(MRMError, ValueError):
    """A Euclidean geometry that cannot be used: invalid polygon, NaN or infinite coordinates."""


class SizeLimitError(MRMError):
    """A result would exceed the configured pixel limit; raised before any memory is allocated.

    Parameters
    ----------
    estimated : int
        The number of pixels the result would have had (or its bounding box holds).
    limit : int
        The limit in force.
    what : str
        A short description of what was being computed.
    unit : str
        What is counted: "pixels" or "voxels".
    """

    def __init__(self, estimated: int, limit: int, what: str = "result", unit: str = "pixels") -> None:
        self.estimated = int(estimated)
        self.limit = int(limit)
        self.what = what
        self.unit = unit
        super().__init__(
            f"{what} would cover {self.estimated:,} {unit}, more than the limit of {self.limit:,}; "
            "reduce the scale or raise the limit"
        )

    def __reduce__(self) -> tuple[type[SizeLimitError], tuple[int, int, str, str]]:
        # Pickled with its own arguments: the worker processes send it to the window (the default
        # reduction passes the message alone, which this constructor cannot take).
        return (type(self), (self.estimated, self.limit, self.what, self.unit))


class FileFormatError(MRMError):
    """A file that cannot be read: corrupt, hostile, wrong type or from a newer version."""


class ParameterError(MRMError, ValueError):
    """An operation parameter out of its domain (non-finite, non-positive, out of bounds)."""


class Cancelled(MRMError):
    """Raised by a progress object's ``update()`` after the user cancelled the task."""


class LimitError(MRMError, ValueError):
    """An edit, operation, import or export would go beyond one of the limits of :mod:`mrm.core.limits`.

    Raised before anything is changed or written, so the document and the files stay as they were.
    """


class NotApplicableError(MRMError, ValueError):
    """What was asked does not apply to an object of this kind; the message says what to do instead.

    A label map has no pixels to paint, no digital straight segments of its own, and is no input of the
    paper's operations.
    """
