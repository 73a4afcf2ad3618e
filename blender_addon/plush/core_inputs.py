"""From plush settings to the core's `knitwear.plush` keywords: size, colours, noise, press
map and the view, and the source sampled for them. Converts and checks; creates nothing."""

import math
import re
from collections.abc import Mapping
from typing import Any

import bpy
import knitwear
import numpy as np
from mathutils import Matrix, Vector

from .. import sampling, shared_inputs
from .properties import MAX_COLORS, PLUSH_SETTINGS

#: Grid samples per stitch the NURBS source is tessellated with. Piles only need the
#: surface's position and normal at their roots (interpolated bilinearly between samples),
#: so one sample per stitch is plenty and keeps tessellation cheap at 384 x 240.
SAMPLES_PER_STITCH = 1


complete = PLUSH_SETTINGS.complete


def settings_from(obj: bpy.types.Object) -> dict[str, Any]:
    return PLUSH_SETTINGS.read(obj.knitwear_plush)


def _noise_scales(text: str) -> list[int]:
    parts = [p for p in re.split(r"[\s,;]+", text.strip()) if p]
    try:
        scales = [int(p) for p in parts]
    except ValueError:
        scales = []
    if not scales or min(scales) < 1:
        raise knitwear.ParameterError(
            f"noise scales must be positive whole numbers such as '1 2 4 8', not '{text}'"
        )
    return scales


def press_weights(image: bpy.types.Image) -> np.ndarray:
    """An image as the core's press map: (height, width) float32 luminance in 0..1, row 0 at
    v = 0 (Blender's bottom row)."""
    rgba = sampling.image_pixels(image)
    luminance = rgba[..., :3] @ np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)
    return np.ascontiguousarray(np.clip(luminance, 0.0, 1.0), dtype=np.float32)


def _colors(settings: Mapping[str, Any]) -> dict[str, Any]:
    mode = settings["color_mode"]
    if mode == "SINGLE":
        return {"colors": shared_inputs.palette(settings, 1)[0]}
    if mode == "STRIPES":
        return {"colors": shared_inputs.stripes(settings, MAX_COLORS)}
    if mode == "IMAGE":
        image = shared_inputs.image_named(settings["color_image_name"], "colour")
        return {"color_image": sampling.image_pixels(image)}
    raise knitwear.ParameterError(f"unknown color_mode {mode!r}; expected SINGLE, STRIPES, IMAGE")


def core_settings(settings: Mapping[str, Any], scene: bpy.types.Scene) -> dict[str, Any]:
    """`knitwear.plush` keywords for ``settings`` (all but the surface and the view)."""
    out: dict[str, Any] = {
        **shared_inputs.size(settings, scene),
        **_colors(settings),
        "piles_per_stitch": int(settings["piles_per_stitch"]),
        "pile_length": settings["pile_length"] or None,
        "pile_radius": settings["pile_radius"] or None,
        "slices": int(settings["slices"]),
        "lean": (settings["lean_angle"], settings["lean_direction"]),
        "theta_max": settings["theta_max"],
        "noise_scales": _noise_scales(settings["noise_scales"]),
        "seed": int(settings["seed"]),
        "threads": scene.render.threads,
    }
    if settings["press_image_name"]:
        press = shared_inputs.image_named(settings["press_image_name"], "press")
        out["press"] = press_weights(press)
        out["press_strength"] = settings["press_strength"]
    return out


def min_samples(counts: tuple[int, int]) -> tuple[int, int]:
    wales, courses = counts
    # Capped so an absurd count reaches the core's own checks instead of a huge grid.
    return (
        int(min(wales, 1e6) * SAMPLES_PER_STITCH) + 1,
        int(min(courses, 1e6) * SAMPLES_PER_STITCH) + 1,
    )


def sample(
    source: bpy.types.Object,
    context: bpy.types.Context,
    size: Mapping[str, Any],
    depsgraph: bpy.types.Depsgraph | None = None,
) -> tuple[sampling.Sampled, tuple[int, int] | None]:
    """The source sampled densely enough for ``size``; and the grid samples asked for."""
    if source.type == "MESH":
        return sampling.sample_object(source, context, depsgraph=depsgraph), None
    if "gauge" in size:
        probe = sampling.sample_object(source, context, depsgraph=depsgraph)
        if probe.grid_shape is None:
            return probe, None
        extent_u, extent_v = probe.surface.extent
        counts = (
            math.ceil(extent_u * size["gauge"][0] / shared_inputs.GAUGE_LENGTH),
            math.ceil(extent_v * size["gauge"][1] / shared_inputs.GAUGE_LENGTH),
        )
    else:
        counts = (size["wales"], size["courses"])
    samples = min_samples(counts)
    return sampling.sample_object(source, context, min_samples=samples, depsgraph=depsgraph), (
        samples
    )


# --- the view ------------------------------------------------------------------------------


def view_of(
    camera: bpy.types.Object | None,
    to_local: Matrix,
    depsgraph: bpy.types.Depsgraph | None = None,
) -> dict[str, tuple[float, float, float]]:
    """The core's ``eye`` (perspective) or ``view_dir`` (orthographic) for ``camera`` in the
    space ``to_local`` maps world coordinates into; {} (along each normal) with no camera."""
    if camera is None:
        return {}
    if depsgraph is not None:
        camera = camera.evaluated_get(depsgraph)
    world = camera.matrix_world
    if camera.type == "CAMERA" and camera.data.type == "ORTHO":
        direction = world.to_3x3() @ Vector((0.0, 0.0, -1.0))
        local = (to_local.to_3x3() @ direction).normalized()
        return {"view_dir": tuple(local)}
    return {"eye": tuple(to_local @ world.translation)}


def world_to_local(obj_matrix: Matrix) -> Matrix:
    return obj_matrix.inverted_safe()
