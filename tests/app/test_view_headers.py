"""The views' headers: a text that does not fit is elided (whole in the tool tip), never cut mid-word.

A new user's screenshot showed the 3D discrete view's header as "Discrete voxe voxels": its subtitle and its
"coarser level: blocks of 2³ voxels" were both cut, squeezed by the Slice/Paint/Erase buttons. The plane views
share the header (mrm.views.view_header).
"""

from __future__ import annotations

from mrm.document.commands import AddObject
from tests.app.helpers import square


def _shown_or_elided(label) -> bool:  # type: ignore[no-untyped-def]
    """Drawn whole, or a prefix ending in "…" with the whole text in the tool tip."""
    shown, whole = label.displayed_text(), label.text()
    if shown == whole:
        return True
    return shown.endswith("…") and whole.startswith(shown[:-1]) and label.toolTip() == whole


def test_a_narrow_views_header_elides_its_subtitle_and_keeps_it_in_the_tool_tip(make_window, qtbot):
    win = make_window(size=(1400, 800))
    view = max(win.views.visible_views(), key=lambda v: len(v.subtitle))  # "digital straight segments"…
    subtitle = view.subtitle_label
    qtbot.waitUntil(lambda: subtitle.displayed_text() == subtitle.text(), timeout=5000)
    whole = subtitle.text()
    assert len(whole) > 15 and subtitle.toolTip() == ""
    win.resize(500, 800)  # as narrow as it goes: four views in it, the headers get little room
    qtbot.waitUntil(lambda: subtitle.displayed_text() != whole, timeout=5000)
    assert _shown_or_elided(subtitle) and subtitle.displayed_text().endswith("…")
    win.resize(1400, 800)
    qtbot.waitUntil(lambda: subtitle.displayed_text() == whole, timeout=5000)
    assert subtitle.toolTip() == ""


def test_a_failure_in_a_views_header_is_red_and_elided_with_every_failure_in_the_tool_tip(make_window, qtbot):
    from mrm.views.view_header import ERROR_COLOUR

    win = make_window(size=(1400, 800))
    obj = win.doc.make_object(square(0, 0), name="A")
    win.doc.push(AddObject(obj))
    view = win.views.discrete
    message = "A: the discretization would need 10,000,000,000 pixels, more than the limit " * 3
    view.header.show_status(message, f"{message}\nB: another failure", error=True)
    status = view.status_label
    qtbot.waitUntil(lambda: status.displayed_text() != "", timeout=5000)
    assert status.displayed_text().endswith("…") and status.toolTip().endswith("B: another failure")
    img = status.grab().toImage()
    red = sum(
        1
        for x in range(img.width())
        for y in range(img.height())
        if img.pixelColor(x, y).red() > 150 and img.pixelColor(x, y).green() < 100
    )
    assert red > 20, f"the failure is drawn in {ERROR_COLOUR}"
    view.header.show_status("computing…")
    assert status.displayed_text() == "computing…" and status.toolTip() == ""
