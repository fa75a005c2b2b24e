"""The document: objects with one source representation each, their derived representations, one history.

* :mod:`mrm.document.objects` — the values: :class:`DocObject`, :class:`Style`, :class:`Settings`;
* :mod:`mrm.document.document` — the :class:`Document` (ordered objects, selection, batched change events);
* :mod:`mrm.document.derive` — the lazy, thread-safe cache of the derived representations;
* :mod:`mrm.document.history` and :mod:`mrm.document.commands` — every edit as an undoable command;
* :mod:`mrm.document.apply` — an operation's results added as one undo step.

Nothing here imports Qt; the views subscribe to the document's :class:`Changes` and push commands.
"""

from mrm.document.document import Changes, Document
from mrm.document.objects import (
    PALETTE,
    DocObject,
    Geometry,
    Settings,
    Source,
    SourceKind,
    Style,
    source_kind,
    validate_geometry,
    validate_source,
)

__all__ = [
    "PALETTE",
    "Changes",
    "DocObject",
    "Document",
    "Geometry",
    "Settings",
    "Source",
    "SourceKind",
    "Style",
    "source_kind",
    "validate_geometry",
    "validate_source",
]
