"""Colours shared by the views (no Qt: the numpy mesh builders of the 3D views read them too)."""

from __future__ import annotations

#: Component colours after the object's own (a qualitative palette, Tableau 10 reordered): the plane region
#: view's components, a label map's labels, the 3D views' components and plane segments.
COMPONENT_COLOURS = (
    "#4e79a7",
    "#f28e2b",
    "#59a14f",
    "#e15759",
    "#b07aa1",
    "#76b7b2",
    "#edc948",
    "#9c755f",
    "#ff9da7",
    "#bab0ac",
)

#: The chosen digital segment's highlight, in the plane analytical view and the 3D one.
CHOSEN_SEGMENT_COLOUR = "#ffb000"
