"""Baking a knit's animation for machines without the extension, and the example scripts a
technical director starts from (run as a user runs them: separate processes)."""

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from types import ModuleType

import bpy
import numpy as np
import pytest
from blender_scenes import SMALL, camera, positions
from conftest import ROOT, _extension_zip
from test_follow import waving_cloth

# Opens a .blend in a Blender with no extension installed and prints the knit's evaluated
# positions at a frame, as JSON.
_WITHOUT_EXTENSION = """
import json, sys, numpy as np, bpy
bpy.ops.wm.open_mainfile(filepath=sys.argv[1])
assert "bl_ext.user_default.knitwear" not in bpy.context.preferences.addons
bpy.context.scene.frame_set(int(sys.argv[3]))
obj = bpy.data.objects[sys.argv[2]]
mesh = obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
co = np.empty(3 * len(mesh.vertices), np.float32)
mesh.vertices.foreach_get("co", co)
print("POSITIONS" + json.dumps(co.tolist()))
"""


def _evaluated_positions(obj: bpy.types.Object) -> np.ndarray:
    mesh = obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
    try:
        return positions(mesh)
    finally:
        obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh_clear()


def test_a_baked_knit_replays_its_animation_without_the_extension(
    api: ModuleType, addon: ModuleType, tmp_path: Path
) -> None:
    scene = bpy.context.scene
    knit = api.knit_object(waving_cloth(), **SMALL)
    scene.frame_end = 10
    blend = tmp_path / "baked.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    knit = bpy.data.objects[knit.name]
    followed = {}
    for frame in (3, 7):
        scene.frame_set(frame)
        followed[frame] = positions(knit.data)
    scene.frame_set(1)

    bpy.context.view_layer.objects.active = knit
    assert bpy.ops.object.knitwear_bake() == {"FINISHED"}
    cache = tmp_path / f"{bpy.path.clean_name(knit.name)}.pc2"
    start, frames = addon.bake.read_pc2(cache)
    assert start == scene.frame_start and len(frames) == scene.frame_end - scene.frame_start + 1
    np.testing.assert_array_equal(frames[7 - start], followed[7])
    assert knit.modifiers[0].type == "MESH_CACHE" and not knit.knitwear.follow_source
    # The cache carries positions only: the baked knit shades with the normals Blender
    # computes from them, not with custom normals of the frame it was following at.
    assert "custom_normal" not in knit.data.attributes
    # Nor fibre directions: the rest pose's would point the highlight wrong as it waves.
    assert "yarn_tangent" not in knit.data.attributes
    scene.frame_set(7)
    np.testing.assert_array_equal(_evaluated_positions(knit), followed[7])
    bpy.ops.wm.save_mainfile()

    env = dict(os.environ, BLENDER_USER_RESOURCES=tempfile.mkdtemp(prefix="no-extension-"))
    done = subprocess.run(
        [sys.executable, "-c", _WITHOUT_EXTENSION, str(blend), knit.name, "3"],
        capture_output=True, text=True, env=env, check=False, timeout=300,
    )
    line = next((s for s in done.stdout.splitlines() if s.startswith("POSITIONS")), None)
    assert line is not None, done.stdout[-2000:] + done.stderr[-2000:]
    elsewhere = np.array(json.loads(line.removeprefix("POSITIONS")), np.float32).reshape(-1, 3)
    np.testing.assert_array_equal(elsewhere, followed[3])


def test_baking_an_unsaved_file_needs_a_path(api: ModuleType) -> None:
    knit = api.knit_object(waving_cloth(), **SMALL)
    bpy.context.view_layer.objects.active = knit
    modifiers = [m.name for m in knit.modifiers]
    try:
        bpy.ops.object.knitwear_bake()
    except RuntimeError as err:
        assert "save the .blend first" in str(err)
    else:
        raise AssertionError("baking an unsaved file with a relative path did not fail")
    assert [m.name for m in knit.modifiers] == modifiers and knit.knitwear.follow_source


def _run_example(script: str, *args: str) -> str:
    env = dict(os.environ, BLENDER_USER_RESOURCES="")  # the example makes its own
    done = subprocess.run(
        [sys.executable, str(ROOT / "examples" / script), "--zip", str(_extension_zip()), *args],
        capture_output=True, text=True, env=env, check=False, timeout=600,
    )
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    return done.stdout


def test_the_animation_example_renders_a_bending_sleeve(tmp_path: Path) -> None:
    from PIL import Image

    out = _run_example(
        "animate.py", "--frames", "1", "3", "--size", "96", "72", "--gauge", "6",
        "--out", str(tmp_path), "--bake",
    )
    assert "rendered 3 frames" in out
    # The bake's check finds the inner elbow (bent 70 degrees at frame 2) squashing the rows.
    assert (tmp_path / "sleeve.pc2").exists() and "baked frames 1-3" in out
    assert "yarn passes through yarn in frame 2:" in out, out
    frames = sorted(tmp_path.glob("frame_*.png"))
    assert len(frames) == 3 and (tmp_path / "sleeve.blend").exists()
    straight, bent = (np.asarray(Image.open(frames[i]), np.float32) for i in (0, 1))
    assert np.abs(straight - bent).mean() > 1.0, "the sleeve did not bend"


def test_the_contact_sheet_example_renders_every_pattern_and_colourway(tmp_path: Path) -> None:
    from PIL import Image

    _run_example(
        "contact_sheet.py", "--patterns", "seed", "garter", "--colourways", "nordic", "sea",
        "--tile", "64", "48", "--out", str(tmp_path),
    )
    tiles = {p.name for p in tmp_path.glob("*.png")} - {"contact_sheet.png"}
    assert tiles == {f"{p}_{c}.png" for p in ("seed", "garter") for c in ("nordic", "sea")}
    sheet = Image.open(tmp_path / "contact_sheet.png")
    assert sheet.size == (160 + 2 * 64, 24 + 2 * 48)


def test_a_failed_bake_keeps_the_earlier_cache(
    api: ModuleType, addon: ModuleType, tmp_path: Path
) -> None:
    scene = bpy.context.scene
    source = waving_cloth()
    knit = api.knit_object(source, **SMALL)
    scene.frame_end = 4
    cache = tmp_path / "knit.pc2"
    addon.bake.bake_animation(knit, frame_start=1, frame_end=4, filepath=str(cache))
    before = cache.read_bytes()
    knit.knitwear.follow_source = True
    bpy.data.objects.remove(source)  # now the knit cannot follow: the bake must fail
    # knitwear is importable only once the extension is installed (the `addon` fixture).
    import knitwear

    with pytest.raises(knitwear.KnitError):
        addon.bake.bake_animation(knit, frame_start=1, frame_end=4, filepath=str(cache))
    assert cache.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["knit.pc2"], "a partial file was left"
    assert [m.type for m in knit.modifiers].count("MESH_CACHE") == 1
    assert knit.knitwear.follow_source


@pytest.mark.parametrize("where", ["folder", "under a file"])
def test_baking_to_a_path_that_cannot_be_a_file_is_a_clear_error(
    api: ModuleType, addon: ModuleType, tmp_path: Path, where: str
) -> None:
    """Issue 18: a folder gave a raw OSError traceback and left a large "<folder>.partial"
    behind."""
    import knitwear

    knit = api.knit_object(waving_cloth(), **SMALL)
    bpy.context.scene.frame_end = 3
    folder = tmp_path / "caches"
    folder.mkdir()
    (tmp_path / "notes.txt").write_text("a file, not a folder")
    target = folder if where == "folder" else tmp_path / "notes.txt" / "knit.pc2"
    before = positions(knit.data).copy()
    listing = sorted(p.name for p in tmp_path.rglob("*"))
    with pytest.raises(knitwear.KnitError, match="cannot write the point cache") as raised:
        addon.bake.bake_animation(knit, frame_start=1, frame_end=3, filepath=str(target))
    assert str(target) in str(raised.value)
    # The operator reports it (headless, an ERROR report raises RuntimeError).
    bpy.context.view_layer.objects.active = knit
    with pytest.raises(RuntimeError, match="cannot write the point cache"):
        bpy.ops.object.knitwear_bake(filepath=str(target))
    assert sorted(p.name for p in tmp_path.rglob("*")) == listing, "a partial file was left"
    assert not any(m.type == "MESH_CACHE" for m in knit.modifiers)
    assert knit.knitwear.follow_source and bpy.context.scene.frame_current == 1
    np.testing.assert_array_equal(positions(knit.data), before)


# Opens a .blend in a Blender with no extension installed and renders its scene camera at a
# frame to a PNG.
_RENDER_WITHOUT_EXTENSION = """
import sys, bpy
bpy.ops.wm.open_mainfile(filepath=sys.argv[1])
assert "bl_ext.user_default.knitwear" not in bpy.context.preferences.addons
scene = bpy.context.scene
scene.frame_set(int(sys.argv[3]))
scene.render.filepath = sys.argv[2]
bpy.ops.render.render(write_still=True)
"""


def _workbench(path: Path) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(path).convert("RGBA"), dtype=np.int16)


def test_a_baked_scene_packed_by_bat_renders_on_a_farm_without_the_extension(
    api: ModuleType, tmp_path: Path
) -> None:
    """Issue 21: the scene a farm gets. Blender's own farm (Flamenco) ships a .blend with what
    it needs as packed by blender-asset-tracer (BAT); the pack must carry the knit's point
    cache and render, from another folder and in a Blender without the extension, the image
    the artist rendered."""
    scene = bpy.context.scene
    source = waving_cloth()
    knit = api.knit_object(source, **SMALL)
    source.hide_render = True
    camera((0.0, -0.75, 0.55), (0.0, 0.0, 0.0))
    scene.render.resolution_x, scene.render.resolution_y = 240, 180
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.film_transparent = True
    scene.display.shading.color_type = "VERTEX"
    scene.render.image_settings.file_format = "PNG"
    scene.frame_end = 10
    project = tmp_path / "project"
    project.mkdir()
    blend = project / "scene.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    knit = bpy.data.objects[knit.name]
    bpy.context.view_layer.objects.active = knit
    assert bpy.ops.object.knitwear_bake() == {"FINISHED"}  # the cache goes next to the .blend
    bpy.ops.wm.save_mainfile()
    frames = {}
    for frame in (1, 7):
        scene.frame_set(frame)
        scene.render.filepath = str(tmp_path / f"artist_{frame}.png")
        bpy.ops.render.render(write_still=True)
        frames[frame] = _workbench(tmp_path / f"artist_{frame}.png")
    artist = frames[7]

    # BAT's own command line, as a farm submission runs it (it loads the file in bpy).
    target = tmp_path / "farm" / "pack"
    packed = subprocess.run(
        # With the bpy module, BAT runs in this Python and reads its arguments after "--".
        [str(Path(sys.executable).parent / "bat"), "--", "pack", "--project", str(project),
         str(blend), str(target)],
        capture_output=True, text=True, check=False, timeout=300,
    )
    assert packed.returncode == 0, packed.stdout[-2000:] + packed.stderr[-2000:]
    cache = f"{bpy.path.clean_name(knit.name)}.pc2"
    assert (target / cache).is_file(), sorted(p.name for p in target.rglob("*"))
    # Only the pack is left to read: the artist's folder is gone.
    project.rename(tmp_path / "moved")

    env = dict(os.environ, BLENDER_USER_RESOURCES=tempfile.mkdtemp(prefix="no-extension-"))
    farm = tmp_path / "farm.png"
    done = subprocess.run(
        [sys.executable, "-c", _RENDER_WITHOUT_EXTENSION, str(target / "scene.blend"),
         str(farm), "7"],
        capture_output=True, text=True, env=env, check=False, timeout=300,
        cwd=tmp_path / "farm",
    )
    assert done.returncode == 0 and farm.exists(), done.stdout[-2000:] + done.stderr[-2000:]
    rendered = _workbench(farm)
    difference = np.abs(rendered - artist)
    differ = np.count_nonzero(difference.max(axis=2))
    print(f"pack render against the artist's: max {difference.max()}, {differ} of "
          f"{difference.shape[0] * difference.shape[1]} pixels differ")
    # The knit fills much of the frame, and frame 7 shows the wave (the knit as knitted, flat,
    # is frame 1): a pack without the cache would render the flat knit.
    assert np.count_nonzero(artist[..., 3]) > 0.3 * artist[..., 3].size
    assert np.count_nonzero(np.abs(frames[1] - artist).max(axis=2)) > 0.05 * artist[..., 3].size
    np.testing.assert_array_equal(rendered, artist)


def _squashing_plane(height: float) -> bpy.types.Object:
    """A 10 x 8 cm plane whose shape key squashes it to ``height`` of its height at frame 3
    and lets it go by frame 5."""
    bpy.ops.mesh.primitive_plane_add(size=1.0)
    source = bpy.context.active_object
    source.scale = (0.10, 0.08, 1.0)
    source.shape_key_add(name="Basis")
    squash = source.shape_key_add(name="Squash")
    for point in squash.data:
        point.co.y *= height
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 5
    for frame, value in ((1, 0.0), (3, 1.0), (5, 0.0)):
        squash.value = value
        squash.keyframe_insert("value", frame=frame)
    scene.frame_set(1)
    return source


def test_the_bake_says_in_which_frames_yarn_passes_through_yarn(
    api: ModuleType, addon: ModuleType, tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    """Issue 23: a surface that squashes its rows (an inner elbow) pushed yarn through yarn
    and nothing said so. Squashed to 35% of its height at frame 3, a plane's knit passes
    yarn through yarn there: the bake measures each frame and names the frames."""
    knit = api.knit_object(_squashing_plane(0.35))
    baked = addon.bake.bake_animation(
        knit, frame_start=1, frame_end=5, filepath=str(tmp_path / "squash.pc2")
    )
    assert [c.frame for c in baked.clearance] == [1, 2, 3, 4, 5]
    at = {c.frame: c for c in baked.clearance}
    assert at[1].min > 0.7 and at[5].min == at[1].min, baked.clearance
    assert at[3].min < at[2].min < at[1].min and at[3].min < 0.5, baked.clearance
    bad = [c.frame for c in baked.passing_through()]
    assert 3 in bad and 1 not in bad and 5 not in bad, baked.clearance
    summary = baked.summary()
    assert summary is not None and "at frame 3" in summary, summary
    # The operator warns with it; without the check nothing is measured.
    bpy.context.view_layer.objects.active = knit
    capfd.readouterr()
    assert bpy.ops.object.knitwear_bake(filepath=str(tmp_path / "op.pc2")) == {"FINISHED"}
    assert summary in capfd.readouterr().out
    quiet = addon.bake.bake_animation(
        knit, frame_start=1, frame_end=5, filepath=str(tmp_path / "q.pc2"), check_clearance=False
    )
    assert quiet.clearance == [] and quiet.summary() is None
    # It still stands for the cache's path, as the Path it used to be.
    assert Path(quiet) == quiet.path == tmp_path / "q.pc2"
    _start, frames = addon.bake.read_pc2(quiet)
    assert frames.shape == (5, len(knit.data.vertices), 3)
    assert f"against {at[1].min:.2f} at best in the others" in summary, summary
    # Squashed to 90%, the rows still clear: the bake says nothing.
    gentle = api.knit_object(_squashing_plane(0.9))
    calm = addon.bake.bake_animation(
        gentle, frame_start=1, frame_end=5, filepath=str(tmp_path / "calm.pc2")
    )
    assert len(calm.clearance) == 5 and calm.summary() is None, calm.clearance


def test_a_knit_that_collides_in_every_frame_is_not_blamed_on_the_animation(
    api: ModuleType, addon: ModuleType, tmp_path: Path
) -> None:
    """A UV sphere's rows keep their full count up to the poles, where the stitches collide
    (clearance 0) in any pose: the bake says so for every frame, and points at the knit, not
    at the surface's squash."""
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=0.05)
    sphere = bpy.context.active_object
    sphere.keyframe_insert("rotation_euler", frame=1)
    sphere.rotation_euler.z = 1.0
    sphere.keyframe_insert("rotation_euler", frame=2)
    bpy.context.scene.frame_set(1)
    knit = api.knit_object(sphere)
    baked = addon.bake.bake_animation(
        knit, frame_start=1, frame_end=2, filepath=str(tmp_path / "sphere.pc2")
    )
    assert all(c.min < 0.5 for c in baked.clearance), baked.clearance
    summary = baked.summary()
    assert summary is not None and "every baked frame" in summary, summary
    assert "squashes" not in summary and "poles" in summary
