"""Auto detail in Blender: the scene camera sets each stitch's level, the report counts them,
levels are pinned so an animated knit keeps its topology, stitches left to the texture put
the knitwear texture on the source, and without a camera nothing changes."""

import importlib
from pathlib import Path
from types import ModuleType

import bpy
import numpy as np
import pytest
from blender_scenes import STRIP, aim, camera, positions, receding_camera, strip
from PIL import Image

#: Thresholds twice the defaults', so this strip at 1080p gets every built level.
COARSE = {"detail_full_px": 24.0, "detail_mid_px": 10.0, "detail_texture_px": 2.0}


def test_without_a_camera_the_knit_is_full_detail(api: ModuleType) -> None:
    outcome = api.knit(strip(), **STRIP)
    assert not outcome.auto_detail
    assert outcome.levels["full"] == outcome.stitches
    assert outcome.triangles == outcome.triangles_full_detail
    assert api.LEVELS_PROPERTY not in outcome.object


def test_auto_detail_follows_the_camera_and_the_report_counts_levels(api: ModuleType) -> None:
    source = strip()
    receding_camera()
    full = api.knit(source, detail_mode="FULL", **STRIP)
    assert not full.auto_detail
    outcome = api.knit(source, **STRIP, **COARSE)
    assert outcome.auto_detail
    lv = outcome.levels
    assert sum(lv.values()) == outcome.stitches
    assert lv["full"] > 0 and lv["mid"] > 0 and lv["far"] > 0, lv
    assert outcome.triangles_full_detail == full.triangles
    assert outcome.triangles < full.triangles
    assert len(outcome.object.data.polygons) == outcome.triangles
    levels = np.frombuffer(api.bound_of(outcome.object).levels, dtype=np.uint8)
    assert levels.size == outcome.stitches
    # The operator says what it built.
    bpy.context.view_layer.objects.active = source
    source.select_set(True)
    assert bpy.ops.object.knitwear_knit(**STRIP, **COARSE) == {"FINISHED"}
    knit = bpy.context.active_object
    assert len(knit.data.polygons) == outcome.triangles


def test_levels_are_pinned_so_the_knit_follows_its_source_after_the_camera_moves(
    api: ModuleType,
) -> None:
    source = strip()
    cam = receding_camera()
    first = api.knit(source, **STRIP)
    obj = first.object
    before = positions(obj.data).copy()
    follow = importlib.import_module(f"{api.__package__}.follow")
    # The camera moves: the knit keeps the levels it was made with.
    aim(cam, (0.0, 0.3, 0.5), (0.0, 0.0, 0.0))
    source.location.z += 0.01
    bpy.context.view_layer.update()
    follow.follow(obj)
    after = positions(obj.data)
    np.testing.assert_allclose(after, before, atol=1e-6)  # moved rigidly: same in its space
    # Update re-chooses the levels for the camera as it is now (high above: coarser).
    outcome = api.update(obj)
    assert outcome.auto_detail and outcome.levels["full"] < first.levels["full"]
    assert len(obj.data.polygons) == outcome.triangles


def test_an_animated_camera_is_followed_over_the_frame_range(api: ModuleType) -> None:
    source = strip()
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 10
    cam = camera((0.0, -0.2, 0.12), (0.0, -0.2, 0.0))  # looking down at the near end
    still = api.knit(source, **STRIP)
    assert still.levels["culled"] > 0
    cam.keyframe_insert("location", frame=1)
    cam.location.y = 0.2  # the far end by frame 10
    cam.keyframe_insert("location", frame=10)
    scene.frame_set(1)
    moving = api.knit(source, **STRIP)
    assert moving.levels["culled"] < still.levels["culled"]
    assert scene.frame_current == 1


def test_a_deforming_source_is_built_for_the_frame_that_sees_each_part(
    api: ModuleType, tmp_path: Path
) -> None:
    """A shape key slides the strip under a still camera over frames 1-10: its far end comes
    into the frame only at the end. Each frame's view sees the source in that frame's pose,
    so the far end is built; it used to be culled by the first frame's pose, and the knit,
    following its source, left the end of the shot empty."""
    source = strip()
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 10
    camera((0.0, -0.2, 0.12), (0.0, -0.2, 0.0))  # looking down at the near end
    still = api.knit(source, **STRIP)
    source.shape_key_add(name="Basis")
    slide = source.shape_key_add(name="Slide")
    for point in slide.data:
        point.co.y -= 0.4 / 0.6  # the strip is the unit plane scaled 0.6 along y
    slide.value = 0.0
    slide.keyframe_insert("value", frame=1)
    slide.value = 1.0
    slide.keyframe_insert("value", frame=10)
    scene.frame_set(1)
    moving = api.knit(source, **STRIP)
    assert scene.frame_current == 1
    assert moving.levels["culled"] < still.levels["culled"] // 2, (moving.levels, still.levels)
    # At frame 10 the far end is under the camera, and the knit that follows it is there: it
    # covers the frame as a knit built whole (Detail: Full) does.
    whole = api.knit(source, detail_mode="FULL", **STRIP)
    source.hide_render = True
    scene.frame_set(10)
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.resolution_x, scene.render.resolution_y = 192, 108

    def covered(shown: bpy.types.Object, hidden: bpy.types.Object) -> np.ndarray:
        shown.hide_render, hidden.hide_render = False, True
        for other in (still.object,):
            other.hide_render = True
        scene.render.filepath = str(tmp_path / f"{shown.name}.png")
        bpy.ops.render.render(write_still=True)
        pixels = np.asarray(Image.open(scene.render.filepath).convert("RGB"), dtype=np.float32)
        return np.abs(pixels - pixels[0, 0]).sum(axis=-1) > 30

    full = covered(whole.object, moving.object)
    seen = covered(moving.object, whole.object)
    assert full.mean() > 0.3, full.mean()  # the strip fills the frame's middle
    assert (seen & full).sum() >= 0.98 * full.sum(), (seen.mean(), full.mean())


def test_stitches_below_a_few_pixels_are_left_to_the_knitwear_texture(api: ModuleType) -> None:
    source = strip()
    receding_camera()
    outcome = api.knit(source, **STRIP, **(COARSE | {"detail_texture_px": 9.0}))
    assert outcome.levels["texture"] > 0
    assert outcome.texture_material is not None
    assert source.data.materials[0].name == outcome.texture_material


def test_a_knit_with_every_stitch_left_to_the_texture_is_an_empty_knit_that_works(
    api: ModuleType, addon: ModuleType, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Issue 18: a knit of 0 vertices (every stitch below Texture Below) raised KeyError
    'position' in the frame handler on every frame."""
    source = strip()
    receding_camera()
    far = {"detail_full_px": 1e4, "detail_mid_px": 1e4, "detail_texture_px": 1e4}
    outcome = api.knit(source, **STRIP, **far)
    obj = outcome.object
    assert outcome.levels["texture"] == outcome.stitches > 0
    assert len(obj.data.vertices) == len(obj.data.polygons) == 0
    assert outcome.texture_material is not None
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 3
    capsys.readouterr()
    source.location.z += 0.01  # something to follow
    for frame in (2, 3, 1):
        scene.frame_set(frame)
    assert "Knitwear" not in capsys.readouterr().out
    assert obj.matrix_world.translation.z == pytest.approx(0.01)
    bpy.context.view_layer.objects.active = obj
    assert bpy.ops.object.knitwear_update() == {"FINISHED"}
    cache = addon.bake.bake_animation(
        obj, frame_start=1, frame_end=3, filepath=str(tmp_path / "empty.pc2")
    ).path
    _start, frames = addon.bake.read_pc2(cache)
    assert frames.shape == (3, 0, 3)


def test_back_faces_of_a_closed_mesh_are_culled(api: ModuleType) -> None:
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=0.1)
    sphere = bpy.context.active_object
    camera((0.6, 0.0, 0.0), (0.0, 0.0, 0.0))
    settings = {"size_mode": "COUNTS", "courses": 30, "wales": 60, "frustum_margin": 1.0}
    culled = api.knit(sphere, **settings)
    kept = api.knit(sphere, cull_back_faces=False, **settings)
    assert kept.levels["culled"] == 0
    assert 0.3 * culled.stitches < culled.levels["culled"] < 0.6 * culled.stitches



def test_an_open_surface_is_never_back_face_culled(api: ModuleType) -> None:
    source = strip()
    camera((0.0, 0.0, -0.5), (0.0, 0.0, 0.0))  # from below: the strip's back, which shows
    outcome = api.knit(source, frustum_margin=1.0, **STRIP)
    assert outcome.auto_detail
    assert outcome.levels["culled"] == 0


#: Detail thresholds that put every stitch at one built level.
ONE_LEVEL = {
    "full": {"detail_full_px": 0.0, "detail_mid_px": 0.0, "detail_texture_px": 0.0},
    "mid": {"detail_full_px": 1e4, "detail_mid_px": 0.0, "detail_texture_px": 0.0},
    "far": {"detail_full_px": 1e4, "detail_mid_px": 1e4, "detail_texture_px": 0.0},
}


def _cover_and_colour(
    api: ModuleType, level: str, path: Path, lit: bool = False
) -> tuple[float, np.ndarray]:
    """A 15 cm swatch at the default gauge seen from above at about 8 px a stitch, every
    stitch at ``level``: the share of the swatch's middle the yarn covers, and the mean colour
    there over black (Workbench, flat vertex colours, so only the geometry differs). ``lit``:
    the mean colour of the yarn itself (over the pixels it covers) in EEVEE, under a grey sky
    and a sun from behind the camera's shoulder, so the shading normals count too."""
    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.mesh.primitive_plane_add(size=0.15)
    source = bpy.context.active_object
    camera((0.0, -0.03, 0.3), (0.0, 0.0, 0.0)).data.lens = 35.0
    scene = bpy.context.scene
    scene.render.resolution_x = scene.render.resolution_y = 512
    outcome = api.knit(source, **ONE_LEVEL[level])
    assert outcome.levels[level] == outcome.stitches
    source.hide_render = True
    if lit:
        scene.render.engine = (
            "BLENDER_EEVEE_NEXT" if bpy.app.version < (4, 5) else "BLENDER_EEVEE"
        )
        scene.eevee.taa_render_samples = 16
        scene.world = bpy.data.worlds.new("sky")
        scene.world.color = (0.3, 0.3, 0.3)
        sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
        sun.data.energy = 3.0
        sun.rotation_euler = (0.5, 0.3, 0.0)
        scene.collection.objects.link(sun)
    else:
        scene.render.engine = "BLENDER_WORKBENCH"
        scene.display.render_aa = "8"
        scene.display.shading.light = "FLAT"
        scene.display.shading.color_type = "VERTEX"
    scene.render.film_transparent = True
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    rgba = np.asarray(Image.open(path).convert("RGBA"), np.float64)[160:352, 160:352] / 255.0
    alpha = rgba[..., 3]
    premultiplied = (rgba[..., :3] * alpha[..., None]).reshape(-1, 3)
    if lit:
        return float(alpha.mean()), premultiplied.sum(axis=0) / alpha.sum()
    return float(alpha.mean()), premultiplied.mean(axis=0)


def test_every_built_level_covers_as_much_as_full_detail(
    api: ModuleType, tmp_path: Path
) -> None:
    """Issue 16 item 5: a knit keeps its colour and brightness when its stitches change
    level. A coarser ring and fewer samples per loop thin the yarn on screen (before the fix
    mid covered 9% less than full detail and far 23% less, darkening the knit as it receded);
    each level's radius now makes up for it."""
    full_cover, full_colour = _cover_and_colour(api, "full", tmp_path / "full.png")
    print(f"\nfull detail covers {full_cover:.3f}", end="")
    assert 0.5 < full_cover < 0.98, "the yarn covers most of the frame, with gaps"
    for level in ("mid", "far"):
        cover, colour = _cover_and_colour(api, level, tmp_path / f"{level}.png")
        change = colour / full_colour - 1.0
        print(
            f"\n{level}: cover {cover:.3f} against full detail's {full_cover:.3f} "
            f"({cover / full_cover - 1:+.1%}); mean colour {np.round(change * 100, 1)}%"
        )
        assert abs(cover / full_cover - 1.0) < 0.03, level
        assert np.all(np.abs(change) < 0.03), level


def test_mid_and_far_knits_lit_keep_full_details_colour(
    api: ModuleType, tmp_path: Path
) -> None:
    """Issue 16 item 5, lit: the coarser rings shade like full detail's round yarn. The far
    level's three-point ring, with a corner of every ring out of the fabric, showed the camera
    two faces whose outer halves turn away from it, and far read 8.3% darker in red (3.3% in
    green and blue) than full detail in EEVEE; every other ring turned half a segment
    (`ring_phase` in src/geometry/bundle.rs) spreads the normals as a round yarn's. Mid's
    four-point ring read -2.7% in red and +4.2% in green and blue; five points read within
    1% (the issue asks for 2%)."""
    _, full = _cover_and_colour(api, "full", tmp_path / "full.png", lit=True)
    for level, tolerance in (("mid", 0.02), ("far", 0.035)):
        _, colour = _cover_and_colour(api, level, tmp_path / f"{level}.png", lit=True)
        change = colour / full - 1.0
        print(f"\n{level}, lit in EEVEE: mean colour {np.round(change * 100, 1)}%", end="")
        assert np.all(np.abs(change) < tolerance), level


def test_a_knit_with_no_full_detail_stitch_says_how_to_get_one(api: ModuleType) -> None:
    """A first knit seen from Blender's default camera, metres away, has no stitch at full
    detail: the report says so and how to change it, where a knit with full stitches does
    not."""
    operators = importlib.import_module(api.__name__.rsplit(".", 1)[0] + ".operators")
    source = strip()
    receding_camera()
    near = api.knit(source, **STRIP, **COARSE)
    assert near.levels["full"] > 0
    assert "close enough" not in operators._summary(near)
    far = api.knit(source, **STRIP, **(COARSE | {"detail_full_px": 1e6}))
    assert far.levels["full"] == 0 and far.stitches > 0
    report = operators._summary(far)
    assert "no stitch is close enough to the camera" in report, report
    assert "Detail to Full" in report, report


def test_sampling_the_frames_does_not_make_the_other_knits_follow_each_one(
    api: ModuleType, addon: ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Auto detail steps through up to 25 frames of an animated camera or source, and each
    step ran every knit's frame handler: each knit already in the scene followed its source
    through them all, adding its per-frame cost 25 times to the click (examples/animate.py's
    sleeve: a second knit of it took 2.2 s, a third 3.3 s, against 0.9 s). The frame is put
    back after, so the other knits stay as they were; a frame change of the user's still
    moves them."""
    source = strip()
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 10
    camera((0.0, -0.2, 0.12), (0.0, -0.2, 0.0))
    source.shape_key_add(name="Basis")
    lift = source.shape_key_add(name="Lift")
    for point in lift.data:
        point.co.z += 0.01
    for frame, value in ((1, 0.0), (10, 1.0)):
        lift.value = value
        lift.keyframe_insert("value", frame=frame)
    scene.frame_set(1)
    first = api.knit(source, **STRIP)
    before = positions(first.object.data).copy()
    followed: list[str] = []
    real = addon.follow.follow

    def spy(obj: bpy.types.Object, **kwargs: object) -> object:
        followed.append(obj.name)
        return real(obj, **kwargs)

    monkeypatch.setattr(addon.follow, "follow", spy)
    second = api.knit(source, **STRIP)
    assert second.auto_detail and scene.frame_current == 1
    assert followed == []
    np.testing.assert_array_equal(positions(first.object.data), before)
    scene.frame_set(10)
    assert first.object.name in followed
    assert positions(first.object.data)[:, 2].mean() > before[:, 2].mean() + 0.005
