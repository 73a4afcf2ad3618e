"""Save as Recipe: a .blend keeps a knit's source, settings and pins but not its yarn, the
session keeps its mesh through the save, and opening the file rebuilds the mesh bit for bit."""

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from types import ModuleType

import bpy
import numpy as np
from blender_scenes import SMALL, corner_verts, positions, uv_mesh

_OPEN_WITHOUT_EXTENSION = """
import json, sys, bpy
for path in sys.argv[2:]:
    bpy.ops.wm.open_mainfile(filepath=path)
    assert "bl_ext.user_default.knitwear" not in bpy.context.preferences.addons
    obj = bpy.data.objects[sys.argv[1]]
    print("MESH" + json.dumps([obj.data.name, len(obj.data.vertices), len(obj.data.materials)]))
"""


def _knit_with_material(api: ModuleType) -> bpy.types.Object:
    knit = api.knit_object(uv_mesh(), **SMALL)
    assert len(knit.data.vertices) > 1000 and len(knit.data.materials) == 1
    return knit


def test_a_knit_saved_as_its_recipe_leaves_its_yarn_out_and_rebuilds_it_on_opening(
    api: ModuleType, tmp_path: Path
) -> None:
    knit = _knit_with_material(api)
    name, mesh_name = knit.name, knit.data.name
    material = knit.data.materials[0].name
    before = positions(knit.data)
    triangles = corner_verts(knit.data)
    whole, recipe = tmp_path / "whole.blend", tmp_path / "recipe.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(whole), copy=True)
    knit.knitwear.save_as_recipe = True
    bpy.ops.wm.save_as_mainfile(filepath=str(recipe))
    # The session keeps the knit as it was, under its own name.
    knit = bpy.data.objects[name]
    assert knit.data.name == mesh_name and knit.data.materials[0].name == material
    np.testing.assert_array_equal(positions(knit.data), before)
    assert not any("kept aside" in m.name for m in bpy.data.meshes)
    assert recipe.stat().st_size * 3 < whole.stat().st_size, (
        f"the recipe file ({recipe.stat().st_size} bytes) still holds the yarn "
        f"({whole.stat().st_size} bytes with it)"
    )

    # Opened with the extension: the same mesh, bit for bit, with its name and material.
    bpy.ops.wm.open_mainfile(filepath=str(recipe))
    knit = bpy.data.objects[name]
    assert knit.data.name == mesh_name and knit.data.materials[0].name == material
    np.testing.assert_array_equal(positions(knit.data), before)
    np.testing.assert_array_equal(corner_verts(knit.data), triangles)
    assert knit.knitwear.save_as_recipe, "saving again saves the recipe again"

    # Opened without it: the knit saved as its recipe is there, empty, keeping its name and
    # material; the one saved whole has its yarn.
    env = dict(os.environ, BLENDER_USER_RESOURCES=tempfile.mkdtemp(prefix="no-extension-"))
    done = subprocess.run(
        [sys.executable, "-c", _OPEN_WITHOUT_EXTENSION, name, str(recipe), str(whole)],
        capture_output=True, text=True, env=env, check=False, timeout=300,
    )
    lines = [s for s in done.stdout.splitlines() if s.startswith("MESH")]
    assert len(lines) == 2, done.stdout[-2000:] + done.stderr[-2000:]
    opened = [json.loads(s.removeprefix("MESH")) for s in lines]
    assert opened == [[mesh_name, 0, 1], [mesh_name, len(before), 1]]


def test_a_recipe_that_cannot_be_rebuilt_opens_empty_and_says_why(
    api: ModuleType, tmp_path: Path, capfd: object
) -> None:
    knit = _knit_with_material(api)
    knit.knitwear.save_as_recipe = True
    name = knit.name
    bpy.data.objects.remove(knit.knitwear.source)
    recipe = tmp_path / "orphan.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(recipe))
    assert len(bpy.data.objects[name].data.vertices) > 0, "the session keeps its yarn"
    bpy.ops.wm.open_mainfile(filepath=str(recipe))
    assert len(bpy.data.objects[name].data.vertices) == 0
    out = capfd.readouterr().out  # type: ignore[attr-defined]
    assert f"'{name}', saved as its recipe, cannot be rebuilt" in out
