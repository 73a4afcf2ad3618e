"""Plush in Blender: the operator grows a pile mesh (attributes, UVs, material) on NURBS and UV
surfaces, errors change nothing, the slice choice matches the criterion for a known camera,
the plush follows the camera with fixed topology, and at grazing views the adaptive slices
hide more of the background than horizontal slices alone (Workbench render)."""

import math
from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Any

import bpy
import numpy as np
import pytest
from blender_scenes import (
    ADDON_MODULE,
    corner_verts,
    data_counts,
    mesh_without_uvs,
    nurbs_patch,
    positions,
    snapshot,
    uv_mesh,
)
from mathutils import Vector
from PIL import Image

#: A small plush: 12 x 10 stitches, 4 slices per pile.
SMALL: dict[str, Any] = {"size_mode": "COUNTS", "courses": 12, "wales": 10, "slices": 4}


@pytest.fixture(scope="module")
def plush(addon: ModuleType) -> ModuleType:
    import importlib

    return importlib.import_module(f"{ADDON_MODULE}.plush")


def add_camera(
    location: tuple[float, float, float],
    target: tuple[float, float, float] = (0.0, 0.0, 0.0),
    *,
    ortho: bool = False,
    lens: float = 50.0,
) -> bpy.types.Object:
    """A scene camera at ``location`` looking at ``target``."""
    data = bpy.data.cameras.new("Camera")
    data.lens = lens
    if ortho:
        data.type = "ORTHO"
    camera = bpy.data.objects.new("Camera", data)
    bpy.context.scene.collection.objects.link(camera)
    aim(camera, location, target)
    bpy.context.scene.camera = camera
    return camera


def aim(
    camera: bpy.types.Object,
    location: tuple[float, float, float],
    target: tuple[float, float, float] = (0.0, 0.0, 0.0),
) -> None:
    camera.location = location
    direction = Vector(target) - Vector(location)
    camera.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
    bpy.context.view_layer.update()


def _floats(collection: bpy.types.bpy_prop_collection, attr: str, width: int) -> np.ndarray:
    out = np.empty(len(collection) * width, dtype=np.float32)
    collection.foreach_get(attr, out)
    return out.reshape(-1, width) if width > 1 else out


def mask_of(mesh: bpy.types.Mesh) -> np.ndarray:
    return _floats(mesh.attributes["plush_mask"].data, "value", 1)


@pytest.mark.parametrize("make_source", [nurbs_patch, uv_mesh], ids=["nurbs_patch", "uv_mesh"])
def test_operator_grows_a_plush_mesh(
    make_source: Callable[[], bpy.types.Object], plush: ModuleType
) -> None:
    source = make_source()
    add_camera((3.0, -3.0, 2.0))
    bpy.context.view_layer.objects.active = source
    before = snapshot(source)
    assert bpy.ops.object.knitwear_plush(**SMALL) == {"FINISHED"}
    obj = bpy.context.active_object
    assert obj is not source and obj.name == f"{source.name}.plush"
    assert snapshot(source) == before, "growing plush must not change the source"
    stored = obj.knitwear_plush
    assert stored.is_plush and stored.source == source
    assert (stored.courses, stored.wales, stored.slices) == (12, 10, 4)

    mesh = obj.data
    piles = len(mesh.vertices) // (4 * 4)
    assert piles > 0 and len(mesh.vertices) == piles * 4 * 4
    assert len(mesh.polygons) == piles * 4 * 2, "two triangles per slice quad"
    col = mesh.color_attributes["Col"]
    assert (col.data_type, col.domain) == ("FLOAT_COLOR", "POINT")
    colours = _floats(col.data, "color", 4)
    assert np.all(colours[:, :3] >= 0) and colours[:, 0].max() > 0.1
    mask = mesh.attributes["plush_mask"]
    assert (mask.data_type, mask.domain) == ("FLOAT", "POINT")
    assert set(np.unique(mask_of(mesh))) <= {0.0, 1.0}

    # UVs per corner: each quad (0,0), (1,0), (1,1), (0,1), written through the triangles.
    uv_map = mesh.uv_layers["UVMap"]
    assert uv_map.active_render
    uvs = _floats(uv_map.uv, "vector", 2)
    corner_vertex = corner_verts(mesh)
    quad_corner = corner_vertex % 4
    expected = np.array([(0, 0), (1, 0), (1, 1), (0, 1)], dtype=np.float32)[quad_corner]
    np.testing.assert_array_equal(uvs, expected)

    material = mesh.materials[0]
    assert material.name == "Knitwear Plush"
    assert material.surface_render_method in {"DITHERED", "BLENDED"}
    bsdf = material.node_tree.nodes["Principled BSDF"]
    assert bsdf.inputs["Alpha"].is_linked and bsdf.inputs["Base Color"].is_linked
    names = {n.attribute_name for n in material.node_tree.nodes if n.type == "ATTRIBUTE"}
    assert "plush_mask" in names
    assert mesh.validate() is False, "validate() found something to fix"


def test_operator_and_function_agree_and_share_the_material(plush: ModuleType) -> None:
    source = nurbs_patch()
    add_camera((2.0, 1.0, 1.5))
    bpy.context.view_layer.objects.active = source
    assert bpy.ops.object.knitwear_plush(**SMALL, seed=3) == {"FINISHED"}
    clicked = bpy.context.active_object
    scripted = plush.knit_plush(source, **SMALL, seed=3)
    np.testing.assert_array_equal(positions(scripted.data), positions(clicked.data))
    np.testing.assert_array_equal(mask_of(scripted.data), mask_of(clicked.data))
    assert scripted.data.materials[0] == clicked.data.materials[0]
    assert sum(m.name.startswith("Knitwear Plush") for m in bpy.data.materials) == 1


ERRORS: dict[str, tuple[Callable[[], bpy.types.Object], dict[str, Any], str, str]] = {
    "no uv map": (mesh_without_uvs, SMALL, "SurfaceError", "UV map"),
    "absurd count": (
        uv_mesh, SMALL | {"courses": 10**6, "wales": 10**6}, "KnitError", ""
    ),
    "absurd count on a surface": (
        nurbs_patch, SMALL | {"courses": 10**6, "wales": 10**6}, "KnitError", ""
    ),
    "bad noise scales": (nurbs_patch, SMALL | {"noise_scales": "1 two"}, "ParameterError", "1 two"),
    "missing press image": (
        nurbs_patch, SMALL | {"press_image_name": "no such image"}, "ParameterError", "no such"
    ),
}


def test_the_gauge_is_named_as_the_knits_and_the_old_names_still_work(
    plush: ModuleType, core: ModuleType
) -> None:
    """Plush and knit both say gauge_stitches / gauge_rows, and both refuse a gauge that is
    not positive before the core runs; a script written with the plush's old gauge_wales /
    gauge_courses gets the same plush and a DeprecationWarning."""
    source = nurbs_patch()
    before = _blend_state(source)
    with pytest.raises(core.ParameterError, match="gauge must be positive"):
        plush.knit_plush(source, size_mode="GAUGE", gauge_stitches=0.0)
    assert _blend_state(source) == before
    gauge = {"size_mode": "GAUGE", "slices": 4, "seed": 1}
    new = plush.knit_plush(source, **gauge, gauge_stitches=30.0, gauge_rows=40.0)
    with pytest.warns(DeprecationWarning, match="gauge_(wales|courses) is now called"):
        old = plush.knit_plush(source, **gauge, gauge_wales=30.0, gauge_courses=40.0)
    assert len(new.data.vertices) > 0
    np.testing.assert_array_equal(positions(old.data), positions(new.data))


def _blend_state(source: bpy.types.Object) -> tuple[dict[str, int], dict[str, Any], str]:
    return data_counts(), snapshot(source), bpy.context.active_object.name


@pytest.mark.parametrize("case", ERRORS.values(), ids=ERRORS.keys())
def test_errors_report_and_change_nothing(
    case: tuple[Callable[[], bpy.types.Object], dict[str, Any], str, str],
    plush: ModuleType,
    core: ModuleType,
) -> None:
    make_source, settings, error, words = case
    source = make_source()
    before = _blend_state(source)
    with pytest.raises(RuntimeError, match="Error") as raised:
        bpy.ops.object.knitwear_plush(**settings)
    assert words in str(raised.value)
    assert _blend_state(source) == before
    with pytest.raises(getattr(core, error)) as raised_api:
        plush.knit_plush(source, **settings)
    assert words in str(raised_api.value)
    assert _blend_state(source) == before


def expected_horizontal(field: Any, eye: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The criterion, recomputed: horizontal iff 2 r |cos a| >= (1 + b) l sin a, with a the
    angle between the pile and the ray from its root to the eye and b the pile's threshold
    across the band where the kinds mix; and the margin of each pile."""
    ray = eye[None, :] - field.roots
    ray /= np.linalg.norm(ray, axis=1, keepdims=True)
    cos_a = np.abs(np.sum(ray * field.directions, axis=1))
    sin_a = np.sqrt(np.clip(1.0 - cos_a**2, 0.0, 1.0))
    band = 1.0 + field.blends
    margin = 2 * field.pile_radius * cos_a - band * field.pile_length / field.slices * sin_a
    return margin >= 0, margin


def test_slice_choice_matches_the_criterion_for_the_scene_camera(plush: ModuleType) -> None:
    source = nurbs_patch()
    source.scale = (1.5, 1.0, 1.0)  # the scale is baked: the eye must be in the baked space
    camera = add_camera((3.0, 0.5, 0.4))
    outcome = plush.plush(source, **SMALL | {"courses": 30, "wales": 30})
    obj, result = outcome.object, outcome.result
    field = result.field
    eye = np.array(obj.matrix_world.inverted() @ camera.matrix_world.translation, np.float32)
    horizontal, margin = expected_horizontal(field, eye)
    got = result.horizontal.astype(bool)
    disagree = got != horizontal
    assert np.all(np.abs(margin[disagree]) < 1e-5), "only float ties may differ"
    assert 0 < got.sum() < len(got), "the camera should give both kinds of slices"
    assert outcome.horizontal == got.sum() and outcome.vertical == len(got) - got.sum()
    # The mesh's mask says the same per pile: 0 round (horizontal), 1 rectangular.
    per_pile = mask_of(obj.data).reshape(len(got), -1)
    assert np.all(per_pile == (~got)[:, None])

    # And for another camera, through the view update.
    aim(camera, (-0.5, -3.0, 0.3))
    assert plush.update_plush_view(obj)
    horizontal, margin = expected_horizontal(
        field, np.array(obj.matrix_world.inverted() @ camera.matrix_world.translation)
    )
    per_pile = mask_of(obj.data).reshape(len(got), -1)[:, 0] == 0
    assert np.all(np.abs(margin[per_pile != horizontal]) < 1e-5)


def test_the_plush_follows_the_camera_with_fixed_topology(plush: ModuleType) -> None:
    scene = bpy.context.scene
    source = nurbs_patch()
    camera = add_camera((3.0, -1.0, 1.5))
    obj = plush.knit_plush(source, **SMALL)
    at_start, mask_start = positions(obj.data), mask_of(obj.data)
    triangles = corner_verts(obj.data)
    topology = obj.data["knitwear_topology"]

    # A camera keyed from above at frame 1 to grazing side-on at frame 10.
    for frame, location in ((1, (0.3, 0.2, 20.0)), (10, (4.0, 0.3, 0.3))):
        aim(camera, location)
        camera.keyframe_insert("location", frame=frame)
        camera.keyframe_insert("rotation_euler", frame=frame)
    scene.frame_set(1)
    from_above, mask_above = positions(obj.data), mask_of(obj.data)
    assert not np.array_equal(from_above, at_start), "frame 1 moved the camera: new view"
    # From above most piles are over the band where slice kinds mix (at 4 slices a pile
    # leaning 40 degrees is in it); side-on most are under it.
    print(f"vertical share from above {mask_above.mean():.3f}", end=" ")
    assert mask_above.mean() < 0.3, "seen from above most piles have horizontal slices"
    scene.frame_set(10)
    side_on = positions(obj.data)
    assert not np.array_equal(side_on, from_above)
    print(f"side-on {mask_of(obj.data).mean():.3f}")
    assert mask_of(obj.data).mean() > 0.5, "seen side-on most piles turn vertical"
    np.testing.assert_array_equal(corner_verts(obj.data), triangles)
    assert obj.data["knitwear_topology"] == topology
    assert len(obj.data.vertices) == len(at_start)

    # Back at frame 1: exactly the same buffers, also after the cache is lost (a file opened
    # on another machine re-grows the field from the stored settings).
    scene.frame_set(1)
    np.testing.assert_array_equal(positions(obj.data), from_above)
    plush._fields.clear()
    scene.frame_set(10)
    np.testing.assert_array_equal(positions(obj.data), side_on)

    # An explicit update with a hand-moved camera (no animation).
    camera.animation_data_clear()
    aim(camera, (3.0, -1.0, 1.5))
    assert plush.update_plush_view(obj)
    np.testing.assert_array_equal(positions(obj.data), at_start)
    np.testing.assert_array_equal(mask_of(obj.data), mask_start)
    assert not plush.update_plush_view(obj), "same view: nothing to write"


def test_follow_camera_off_and_errors_do_not_break_frames(plush: ModuleType) -> None:
    scene = bpy.context.scene
    source = nurbs_patch()
    camera = add_camera((3.0, -1.0, 1.5))
    obj = plush.knit_plush(source, **SMALL)
    obj.knitwear_plush.follow_camera = False
    before = positions(obj.data)
    aim(camera, (0.0, 0.0, 4.0))
    scene.frame_set(5)
    np.testing.assert_array_equal(positions(obj.data), before)
    obj.knitwear_plush.follow_camera = True
    bpy.data.objects.remove(source)  # cannot re-grow: reported, frames go on
    plush._fields.clear()
    scene.frame_set(6)
    np.testing.assert_array_equal(positions(obj.data), before)


def test_press_map_bends_the_pile(plush: ModuleType) -> None:
    source = nurbs_patch()
    image = bpy.data.images.new("Press", 16, 16, float_buffer=True)
    pixels = np.zeros((16, 16, 4), np.float32)
    pixels[..., 3] = 1.0
    pixels[:, :8, :3] = 1.0  # the left half (u < 0.5) pressed
    image.pixels.foreach_set(pixels.ravel())
    free = plush.plush(source, **SMALL | {"slices": 2}).result.field
    pressed = plush.plush(
        source, **SMALL | {"slices": 2, "press_image_name": "Press"}
    ).result.field
    tilt_free = np.sum(free.directions * free.normals, axis=1)
    tilt_pressed = np.sum(pressed.directions * pressed.normals, axis=1)
    left = free.root_uvs[:, 0] < 0.45
    right = free.root_uvs[:, 0] > 0.55
    assert np.all(tilt_pressed[left] < tilt_free[left] - 0.1), "pressed piles lie flatter"
    np.testing.assert_allclose(tilt_pressed[right], tilt_free[right], atol=1e-6)


# --- coverage at grazing views -------------------------------------------------------------

#: Camera elevation above the fabric plane (within 15 degrees: grazing).
GRAZING_DEG = 8.0
RESOLUTION = (160, 90)


def _render_alpha(path: Path) -> np.ndarray:
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = True
    scene.display.render_aa = "OFF"
    scene.display.shading.light = "FLAT"
    scene.display.shading.color_type = "VERTEX"
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    return np.asarray(Image.open(path).convert("RGBA"), dtype=np.float32)[..., 3] / 255.0


def _flat_patch() -> bpy.types.Object:
    source = nurbs_patch()
    for point in source.data.splines[0].points:
        x, y, _z, w = point.co
        point.co = (x, y, 0.0, w)
    return source


def test_adaptive_slices_hide_more_background_at_grazing_views(
    plush: ModuleType, tmp_path: Path
) -> None:
    source = _flat_patch()
    settings = {"size_mode": "COUNTS", "courses": 40, "wales": 40, "slices": 6}
    # Every pile horizontal: the view along each normal (no camera yet).
    flat = plush.plush(source, **settings)
    assert flat.vertical == 0
    flat.object.knitwear_plush.follow_camera = False
    # The grazing camera, side-on to the mean lean, where vertical slices pay off.
    lean = flat.result.field.directions.mean(axis=0)
    side = Vector((-lean[1], lean[0], 0.0)).normalized()
    elevation, distance = math.radians(GRAZING_DEG), 1.8
    eye = side * (distance * math.cos(elevation)) + Vector((0, 0, distance * math.sin(elevation)))
    add_camera(tuple(eye), lens=30.0)
    adaptive = plush.plush(source, **settings)
    assert adaptive.vertical > adaptive.piles // 4, "the grazing view turns piles vertical"

    def alpha_of(shown: bpy.types.Object | None, name: str) -> np.ndarray:
        for obj in (source, adaptive.object, flat.object):
            obj.hide_render = obj is not shown
        return _render_alpha(tmp_path / f"{name}.png")

    # The pile's screen region: per image column, from the lowest to the highest pixel that
    # the surface or either plush covers (the bounding region of the fabric and its pile).
    renders = {
        "surface": alpha_of(source, "surface") > 0.5,
        "adaptive": alpha_of(adaptive.object, "adaptive") > 0.5,
        "horizontal only": alpha_of(flat.object, "horizontal") > 0.5,
    }
    union = renders["surface"] | renders["adaptive"] | renders["horizontal only"]
    rows = np.arange(union.shape[0])[:, None]
    has = union.any(axis=0)
    top = np.where(has, np.argmax(union, axis=0), 0)
    bottom = np.where(has, union.shape[0] - 1 - np.argmax(union[::-1], axis=0), -1)
    footprint = (rows >= top) & (rows <= bottom)
    assert renders["surface"].sum() > 200, "the surface is visible from the camera"
    background = {
        name: float(np.mean(~renders[name][footprint]))
        for name in ("adaptive", "horizontal only")
    }
    print(
        f"\nbackground through the pile at {GRAZING_DEG:g} deg, {RESOLUTION[0]}x"
        f"{RESOLUTION[1]} px over {int(footprint.sum())} footprint pixels: adaptive "
        f"{background['adaptive']:.1%} ({adaptive.vertical:,} of {adaptive.piles:,} piles "
        f"vertical), horizontal only {background['horizontal only']:.1%}"
    )
    assert background["adaptive"] < background["horizontal only"]


def test_the_pile_noise_is_an_image_a_user_can_open(plush: ModuleType) -> None:
    obj = plush.knit_plush(nurbs_patch(), **SMALL, seed=4)
    bpy.context.view_layer.objects.active = obj
    assert bpy.ops.object.knitwear_plush_noise() == {"FINISHED"}
    image = bpy.data.images[f"{obj.name} Pile Noise"]
    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    rgb = pixels.reshape(height, width, 4)[..., :3]
    # (v + 1) / 2 of unit vectors within theta_max of +z: blue well above the middle, and the
    # vectors it encodes are unit length.
    v = 2 * rgb - 1
    np.testing.assert_allclose(np.linalg.norm(v, axis=-1), 1.0, atol=1e-4)
    assert (rgb[..., 2] > 0.5 + 0.5 * np.cos(np.radians(45))).all()
    assert rgb[..., :2].std() > 0.01, "the noise is flat"


def test_cycles_renders_the_plush_in_its_colour(plush: ModuleType, tmp_path: Path) -> None:
    source = nurbs_patch()
    source.hide_render = True
    plush.knit_plush(source, **SMALL, color_1=(0.6, 0.02, 0.02))
    add_camera((0.0, -0.4, 2.5))
    scene = bpy.context.scene
    world = bpy.data.worlds.new("White")
    world.color = (1.0, 1.0, 1.0)
    scene.world = world
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 4
    scene.cycles.use_denoising = False
    scene.render.resolution_x = scene.render.resolution_y = 48
    scene.render.film_transparent = True
    scene.view_settings.view_transform = "Standard"
    scene.render.filepath = str(tmp_path / "plush_cycles.png")
    bpy.ops.render.render(write_still=True)
    pixels = np.asarray(Image.open(tmp_path / "plush_cycles.png").convert("RGBA"), np.float32)
    alpha = pixels[..., 3] / 255
    covered = alpha > 0.5
    assert covered.mean() > 0.1, f"the plush covers only {covered.mean():.0%} of the frame"
    r, g, b = np.median(pixels[covered][:, :3], axis=0)
    assert r > 3 * max(g, b), f"median colour {(r, g, b)}"
