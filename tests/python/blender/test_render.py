"""A Workbench render shows the knit in its yarn colours."""

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
