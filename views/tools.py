"""The catalogue of editing tools: one of each (select, polygon, vertices, brush, one-click tools, measure).

The shared base is :mod:`mrm.views.tool_base`; each tool (or family) has its module.
"""

from __future__ import annotations

from mrm.views.brush_tool import BrushTool
from mrm.views.click_tools import DeleteComponentTool, FillHoleTool, PickPointTool
from mrm.views.measure import MeasureTool
from mrm.views.polygon_tool import PolygonTool
from mrm.views.select_tool import SelectTool
from mrm.views.tool_base import Tool, ToolHost
from mrm.views.vertex_tool import VertexTool


def make_tools(host: ToolHost) -> dict[str, Tool]:
    """One instance of every tool, by name."""
    tools: list[Tool] = [
        SelectTool(host),
        PolygonTool(host),
        VertexTool(host),
        BrushTool(host, True),
        BrushTool(host, False),
        FillHoleTool(host),
        DeleteComponentTool(host),
        PickPointTool(host),
        MeasureTool(host),
    ]
    return {t.name: t for t in tools}
