"""Renders show the knit in its yarn colours, and Cycles draws its highlight along the fibres."""

from pathlib import Path
from types import ModuleType

import bpy
import numpy as np
from blender_scenes import SMALL, nurbs_patch
from PIL import Image

RED = (0.6, 0.02, 0.02)
BLUE = (0.02, 0.05, 0.6)


def _srgb(linear: tuple[float, float, float]) -> np.ndarray:
    c = np.asarray(linear)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)


def _render(path: Path) -> np.ndarray:
    scene = bpy.context.scene
    camera_data = bpy.data.cameras.new("Camera")
    camera_data.type = "ORTHO"
    camera_data.ortho_scale = 1.1
    camera = bpy.data.objects.new("Camera", camera_data)
    camera.location = (0.0, 0.0, 4.0)  # looking straight down at the patch
    scene.collection.objects.link(camera)
    scene.camera = camera

    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.resolution_x, scene.render.resolution_y = 120, 120
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = True
    scene.display.render_aa = "OFF"
    scene.display.shading.light = "FLAT"  # the attribute colour itself, unshaded
    scene.display.shading.color_type = "VERTEX"  # shown as "Attribute" in the UI
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    return np.asarray(Image.open(path).convert("RGBA"), dtype=np.float32) / 255.0


def test_workbench_render_shows_both_yarn_colours(api: ModuleType, tmp_path: Path) -> None:
    source = nurbs_patch()
    source.hide_render = True
    api.knit_object(
        source,
        **(SMALL | {"courses": 12, "wales": 12}),
        color_mode="STRIPES",
        color_count=2,
        stripe_height=2,
        color_1=RED,
        color_2=BLUE,
        color_variation=0.0,
    )
    pixels = _render(tmp_path / "knit.png")
    rgb, alpha = pixels[..., :3], pixels[..., 3]
    covered = alpha > 0.5
    assert covered.mean() > 0.3, f"the knit covers only {covered.mean():.0%} of the frame"
    for colour in (RED, BLUE):
        near = np.linalg.norm(rgb - _srgb(colour), axis=-1) < 0.12
        share = np.mean(near & covered)
        assert share > 0.05, f"yarn colour {colour} covers only {share:.1%} of the frame"


def test_cycles_renders_the_knit_in_its_yarn_colour(api: ModuleType, tmp_path: Path) -> None:
    source = nurbs_patch()
    source.hide_render = True
    api.knit_object(source, **SMALL, color_1=RED, color_variation=0.0)
    scene = bpy.context.scene
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = 1.1
    camera.location = (0.0, 0.0, 4.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    world = bpy.data.worlds.new("White")
    world.color = (1.0, 1.0, 1.0)  # uniform light from every side: the base colour shows
    scene.world = world
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 4
    scene.cycles.use_denoising = False
    scene.render.resolution_x = scene.render.resolution_y = 48
    scene.render.film_transparent = True
    scene.view_settings.view_transform = "Standard"
    scene.render.filepath = str(tmp_path / "cycles.png")
    bpy.ops.render.render(write_still=True)
    pixels = np.asarray(Image.open(tmp_path / "cycles.png").convert("RGBA"), np.float32) / 255
    covered = pixels[..., 3] > 0.5
    assert covered.mean() > 0.3, f"the knit covers only {covered.mean():.0%} of the frame"
    rgb = pixels[covered][:, :3]
    # The yarn material shows its vertex colour: red dominates wherever the knit is.
    r, g, b = np.median(rgb, axis=0)
    assert r > 0.08 and r > 3 * max(g, b), f"median colour {(r, g, b)}"


def _cycles_render(path: Path) -> np.ndarray:
    """A 64 x 64 Cycles render (4 samples, the seed fixed: the same scene renders the same
    pixels) of the patch from above under a low sun, where the yarn's highlight shows."""
    scene = bpy.context.scene
    if scene.camera is None:
        camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
        camera.data.type = "ORTHO"
        camera.data.ortho_scale = 0.6
        camera.location = (0.0, 0.0, 4.0)
        scene.collection.objects.link(camera)
        scene.camera = camera
        sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
        sun.rotation_euler = (1.0, 0.2, 0.4)
        sun.data.energy = 4.0
        scene.collection.objects.link(sun)
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 4
    scene.cycles.seed = 1
    scene.cycles.use_denoising = False
    scene.render.resolution_x = scene.render.resolution_y = 64
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    return np.asarray(Image.open(path).convert("RGB"), np.float32)


def test_cycles_draws_the_yarns_highlight_along_its_fibres(
    api: ModuleType, tmp_path: Path
) -> None:
    """The yarn material takes the knit's fibre directions (`yarn_tangent`) as the tangent
    of its anisotropic highlight: turning them a quarter turn round each normal changes the
    render, and without them the highlight is round (the material reads a zero vector)."""
    source = nurbs_patch()
    source.hide_render = True
    knit = api.knit_object(source, **SMALL, color_1=RED, color_variation=0.0)
    knit.knitwear.follow_source = False  # a render's frame change would rewrite them
    mesh = knit.data
    bsdf = next(n for n in mesh.materials[0].node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    assert bsdf.inputs["Tangent"].is_linked and bsdf.inputs["Anisotropic"].is_linked
    along = _cycles_render(tmp_path / "along.png")
    np.testing.assert_array_equal(_cycles_render(tmp_path / "again.png"), along)
    tangents = np.empty((len(mesh.vertices), 3), np.float32)
    normals = np.empty_like(tangents)
    mesh.attributes["yarn_tangent"].data.foreach_get("vector", tangents.ravel())
    mesh.attributes["custom_normal"].data.foreach_get("vector", normals.ravel())
    mesh.attributes["yarn_tangent"].data.foreach_set("vector", np.cross(normals, tangents).ravel())
    across = _cycles_render(tmp_path / "across.png")
    mesh.attributes.remove(mesh.attributes["yarn_tangent"])
    round_ = _cycles_render(tmp_path / "round.png")
    for name, other in (("turned", across), ("round", round_)):
        changed = np.abs(other - along).max(axis=-1) > 2
        # (Measured: 25% of pixels turned, 12% round; 0 if the material ignored them.)
        assert changed.mean() > 0.05, f"{name}: {changed.mean():.1%} of pixels changed"
