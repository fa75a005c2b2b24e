"""Editing a voxel object: delete a component, fill a cavity, replace its voxels — each one undo step."""

from __future__ import annotations

import numpy as np
import pytest

from mrm.core.errors import ParameterError
from mrm.core.grids import VoxelSet
from mrm.document import Document
from mrm.document.commands import AddObject, SetSource
from mrm.reps.region_3d import region_3d_of


def _hollow_cube_and_a_bar() -> VoxelSet:
    m = np.zeros((9, 9, 16), bool)
    m[1:8, 1:8, 1:8] = True
    m[3:6, 3:6, 3:6] = False  # a 3³ cavity
    m[4, 4, 4] = True  # a voxel floating in it: a component nested in the cavity
    m[2:5, 2:5, 11:14] = True  # a separate 3³ cube
    return VoxelSet(m, (10, 20, 30))


def test_a_component_and_a_cavity_are_found_by_the_region_and_edited_in_one_undo_step() -> None:
    vs = _hollow_cube_and_a_bar()
    region = region_3d_of(vs.mask, vs.origin)
    assert [c.voxels for c in region.components] == [7**3 - 27, 27, 1]  # in raster order of their first voxel
    hollow = next(c for c in region.components if c.cavities)
    cavity = region.cavity_voxels(hollow.label, 0)
    assert cavity.count == 26 and not (cavity & vs).count  # the cavity less the voxel nested in it
    doc = Document()
    obj = doc.make_object(vs, name="solid")
    doc.push(AddObject(obj))
    doc.push(SetSource(obj.id, vs | cavity, label="Fill cavity"))
    filled = doc.get(obj.id).source
    after = region_3d_of(filled.mask, filled.origin)
    assert after.n_cavities == 0 and after.n_components == 2 and filled.count == vs.count + 26
    cube = region.component_voxels(2)
    doc.push(SetSource(obj.id, filled - cube, label="Delete component"))
    assert doc.get(obj.id).source.count == 7**3
    assert doc.history.undo_label() == "Delete component"
    doc.history.undo()
    assert doc.get(obj.id).source == filled
    doc.history.undo()
    assert doc.get(obj.id).source == vs  # undo restores the voxels exactly


def test_a_missing_component_or_cavity_is_one_line() -> None:
    vs = _hollow_cube_and_a_bar()
    region = region_3d_of(vs.mask, vs.origin)
    with pytest.raises(ParameterError, match="no component 4"):
        region.component_voxels(4)
    with pytest.raises(ParameterError, match="no cavity"):
        region.cavity_voxels(3, 0)
