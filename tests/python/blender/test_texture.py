"""Knitwear texture: the source gets an image of its stitches as a material, the image is
the core's, a render shows the yarn colours the right way round, and errors change nothing."""

import importlib
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import bpy
import numpy as np
import pytest
from blender_scenes import (
    ADDON_MODULE,
    SMALL,
    SOURCES,
    data_counts,
    mesh_without_uvs,
    nurbs_patch,
    snapshot,
    uv_mesh,
)
from PIL import Image

RED = (0.6, 0.02, 0.02)
BLUE = (0.02, 0.05, 0.6)
STRIPES = {
    **SMALL,
    "courses": 12,
    "wales": 12,
    "color_mode": "STRIPES",
    "color_count": 2,
    "stripe_height": 6,
    "color_1": RED,
    "color_2": BLUE,
    "color_variation": 0.0,
}


@pytest.fixture(scope="module")
def texture(addon: ModuleType) -> ModuleType:
    return importlib.import_module(f"{ADDON_MODULE}.texture")


def _pixels(image: bpy.types.Image) -> np.ndarray:
    w, h = image.size
    out = np.empty(w * h * 4, dtype=np.float32)
    image.pixels.foreach_get(out)
    return out.reshape(h, w, 4)


def _core_texture(
    api: ModuleType,
    core: ModuleType,
    source: bpy.types.Object,
    width: int,
    height: int,
    settings: dict,
) -> np.ndarray:
    """The core's texture for ``source``, in the UV map's order (u and v swapped where
    the courses run along V)."""
    inputs = api.core_inputs.core_inputs(source, bpy.context, api.core_inputs.complete(settings))
    if inputs.sampled.courses_along == "V":
        img = core.knit_texture(
            inputs.sampled.surface, inputs.pattern, width=height, height=width, **inputs.kwargs
        )
        return img.transpose(1, 0, 2)
    return core.knit_texture(
        inputs.sampled.surface, inputs.pattern, width=width, height=height, **inputs.kwargs
    )


@pytest.mark.parametrize("kind", ["nurbs_patch", "uv_mesh"])
def test_the_source_wears_the_cores_texture(
    texture: ModuleType, api: ModuleType, core: ModuleType, kind: str
) -> None:
    source = SOURCES[kind]()
    material = texture.texture_object(source, width=96, height=64, **STRIPES)
    name = f"{source.name} Knit Texture"
    assert material.name == name
    assert source.data.materials[0] == material
    image = bpy.data.images[name]
    assert tuple(image.size) == (96, 64) and image.is_float
    nodes = [n for n in material.node_tree.nodes if n.type == "TEX_IMAGE"]
    assert len(nodes) == 1 and nodes[0].image == image
    expected = _core_texture(api, core, source, 96, 64, STRIPES)
    np.testing.assert_array_equal(_pixels(image), expected)
    # Both yarn colours are in the image, and gaps between the yarns.
    covered = expected[..., 3] > 0.5
    assert 0.3 < covered.mean() < 0.98
    reds = covered & (expected[..., 0] > expected[..., 2])
    assert 0.2 < reds.sum() / covered.sum() < 0.8

    # Again: the image and material are reused, not duplicated.
    texture.texture_object(source, width=96, height=64, **STRIPES)
    assert len([m for m in bpy.data.materials if m.name.startswith(name)]) == 1
    assert len([i for i in bpy.data.images if i.name.startswith(name)]) == 1


def test_the_operator_gives_what_the_function_gives(
    texture: ModuleType, api: ModuleType, core: ModuleType
) -> None:
    source = nurbs_patch()
    result = bpy.ops.object.knitwear_texture(texture_width=64, texture_height=64, **STRIPES)
    assert result == {"FINISHED"}
    image = bpy.data.images[f"{source.name} Knit Texture"]
    np.testing.assert_array_equal(_pixels(image), _core_texture(api, core, source, 64, 64, STRIPES))


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
    scene.render.resolution_x, scene.render.resolution_y = 160, 160
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = True
    scene.display.shading.light = "FLAT"
    scene.display.shading.color_type = "TEXTURE"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    return np.asarray(Image.open(path).convert("RGBA"), dtype=np.float32) / 255.0


def _red_share(pixels: np.ndarray) -> np.ndarray:
    """How much the share of red among the yarn pixels differs between the two halves of
    the image split across rows (entry 0) and across columns (entry 1)."""
    covered = pixels[..., 3] > 0.5
    yarn = covered & (pixels[..., :3].max(axis=-1) > 0.08)
    red = yarn & (pixels[..., 0] > pixels[..., 2])
    n = pixels.shape[0] // 2

    def share(sl: tuple[slice, slice]) -> float:
        return float(red[sl].sum() / max(yarn[sl].sum(), 1))

    rows = abs(share((slice(0, n), slice(None))) - share((slice(n, None), slice(None))))
    cols = abs(share((slice(None), slice(0, n))) - share((slice(None), slice(n, None))))
    return np.array([rows, cols])


def test_a_render_shows_the_stripes_along_the_course_direction(
    texture: ModuleType, api: ModuleType, core: ModuleType, tmp_path: Path
) -> None:
    source = nurbs_patch()
    texture.texture_object(source, width=512, height=512, **STRIPES)
    along_u = _render(tmp_path / "texture_u.png")
    # The patch fills most of the frame, in the yarn colours.
    covered = along_u[..., 3] > 0.5
    assert covered.mean() > 0.3
    split_u = _red_share(along_u)
    along_v = STRIPES | {"direction": "V"}
    texture.texture_object(source, width=512, height=512, **along_v)
    # The reused image holds the new pixels.
    image = bpy.data.images[f"{source.name} Knit Texture"]
    np.testing.assert_array_equal(
        _pixels(image), _core_texture(api, core, source, 512, 512, along_v)
    )
    split_v = _red_share(_render(tmp_path / "texture_v.png"))
    # Two stripes of six courses: one half of the patch red, the other blue, split across
    # the courses; turning the courses turns the split.
    assert split_u.max() > 0.8 and split_u.min() < 0.2, split_u
    assert split_v.max() > 0.8 and split_v.min() < 0.2, split_v
    assert np.argmax(split_u) != np.argmax(split_v)


@pytest.mark.parametrize(
    ("make", "settings", "message"),
    [
        (mesh_without_uvs, {}, "UV"),
        (uv_mesh, {"courses": 10**6, "wales": 10**6}, "budget"),
        (nurbs_patch, {"pattern": "CUSTOM", "pattern_chart": "kq"}, "pattern"),
        # Issue 18: Blender cannot pack a float image of 2 GiB or more (it crashed).
        (uv_mesh, {"texture_width": 16384, "texture_height": 16384}, "cannot pack"),
        (uv_mesh, {"texture_width": 16384, "texture_height": 8192}, "at most 130,023,424"),
    ],
)
def test_errors_leave_the_scene_unchanged(
    texture: ModuleType,
    make: Callable[[], bpy.types.Object],
    settings: dict,
    message: str,
) -> None:
    source = make()
    before = (data_counts(), snapshot(source))
    with pytest.raises(RuntimeError, match=message):
        bpy.ops.object.knitwear_texture(**(SMALL | settings))
    assert (data_counts(), snapshot(source)) == before
    assert len(source.data.materials) == 0
