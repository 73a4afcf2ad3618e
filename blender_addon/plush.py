"""Plush: warp-knitted pile over a NURBS surface or a UV-mapped mesh (README "Plush").

The core (`knitwear.plush`) does all the geometry: pile roots on the stitch grid, fractal-noise
directions, press-map bending and, per pile, horizontal or vertical slices for the view. This
module only moves buffers: the source is read with `sampling.sample_object`, the slices become
a mesh through `mesh_build` (the fast template route, with the core's edges), and the view is
the scene camera's, expressed in the plush object's space (the source's object space with its
scale baked in, see `sampling`).

Follow the camera. A plush's `knitwear.PlushField` (roots, frames, directions, colours) is kept
per object in a module-level cache; on every frame change and on `update_plush_view(obj)` the
camera's eye (perspective) or direction (orthographic) goes to `PlushField.view`, and only the
vertex positions and the "plush_mask" attribute are written: the slices keep their topology,
UVs and colours. After a file load (or on a farm machine) the field is grown again from the
stored settings, which is deterministic: same source, settings and seed, same field.

Scripting::

    from bl_ext.user_default.knitwear import plush
    obj = plush.knit_plush(bpy.data.objects["Cushion"], size_mode="COUNTS", courses=200,
                           wales=160, pile_length=0.01, seed=3, press_image_name="Palm")
    plush.update_plush_view(obj)   # after moving the camera by hand
"""

import math
import re
import time
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import bpy
import knitwear
import numpy as np
from bpy.app.handlers import persistent
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    FloatVectorProperty,
    IntProperty,
    IntVectorProperty,
    PointerProperty,
    StringProperty,
)
from mathutils import Matrix, Vector

from . import frame_handlers, mesh_build, sampling
from .settings_schema import SettingsSchema

MATERIAL_NAME = "Knitwear Plush"
#: Point-domain float attribute: the core's per-vertex mask (0 round / horizontal slice,
#: 1 rectangular / vertical slice); the material mixes its alpha shapes by it.
MASK_ATTRIBUTE = "plush_mask"
UV_MAP = "UVMap"
#: The core reads a gauge as piles per this many scene units (10 cm in metres).
_GAUGE_LENGTH = 0.1
#: Grid samples per stitch the NURBS source is tessellated with. Piles only need the
#: surface's position and normal at their roots (interpolated bilinearly between samples),
#: so one sample per stitch is plenty and keeps tessellation cheap at 384 x 240.
SAMPLES_PER_STITCH = 1

SIZE_MODE_ITEMS = [
    ("GAUGE", "Gauge", "Pile density from a gauge: wales and courses per 10 cm"),
    ("COUNTS", "Counts", "A fixed number of courses and wales over the whole surface"),
]
COLOR_MODE_ITEMS = [
    ("SINGLE", "Single", "One pile colour"),
    ("STRIPES", "Stripes", "Stripes of courses cycling through the colours"),
    ("IMAGE", "Image", "Each pile takes the colour of an image at its (u,v)"),
]
MAX_COLORS = 4
_DEFAULT_COLORS = (
    (0.30, 0.012, 0.03),  # deep red velvet
    (0.60, 0.50, 0.35),  # camel
    (0.02, 0.05, 0.25),  # navy
    (0.05, 0.20, 0.06),  # bottle green
)


def _color_prop(index: int) -> FloatVectorProperty:
    return FloatVectorProperty(
        name=f"Colour {index + 1}",
        description="Pile colour (linear RGB); the tip is lighter and the root darker",
        subtype="COLOR",
        size=3,
        min=0.0,
        max=1.0,
        default=_DEFAULT_COLORS[index],
    )


class PlushSettingsMixin:
    """Every plush setting, declared once: stored on the object and edited in the redo panel."""

    size_mode: EnumProperty(name="Size", items=SIZE_MODE_ITEMS, default="GAUGE")
    gauge_wales: FloatProperty(
        name="Wales / 10 cm",
        description="Stitches along a course per 10 cm (the paper's fabric: about 48)",
        default=48.0,
        min=0.1,
        soft_max=200.0,
    )
    gauge_courses: FloatProperty(
        name="Courses / 10 cm",
        description="Courses (rows) per 10 cm along a wale",
        default=64.0,
        min=0.1,
        soft_max=200.0,
    )
    courses: IntProperty(
        name="Courses", description="Courses over the whole surface (along v)",
        default=96, min=1, max=1_000_000, soft_max=2000,
    )
    wales: IntProperty(
        name="Wales", description="Wales over the whole surface (along u)",
        default=64, min=1, max=1_000_000, soft_max=2000,
    )
    piles_per_stitch: IntProperty(
        name="Piles per Stitch",
        description="Piles grown from each stitch, on a near-square sub-grid (4: 2x2)",
        default=1, min=1, max=64,
    )
    pile_length: FloatProperty(
        name="Pile Length",
        description="Length of a pile; 0 = automatic (2.5 stitch widths)",
        default=0.0, min=0.0, soft_max=0.1, subtype="DISTANCE", unit="LENGTH", precision=4,
    )
    pile_radius: FloatProperty(
        name="Pile Radius",
        description="Half width of a slice; 0 = automatic (0.6 pile spacings)",
        default=0.0, min=0.0, soft_max=0.05, subtype="DISTANCE", unit="LENGTH", precision=4,
    )
    slices: IntProperty(
        name="Slices", description="Quads per pile", default=8, min=1, max=64,
    )
    lean_angle: FloatProperty(
        name="Lean",
        description="Angle of the pile's nominal direction from the surface normal",
        default=math.radians(30.0), min=0.0, max=math.radians(89.0), subtype="ANGLE",
    )
    lean_direction: FloatProperty(
        name="Lean Direction",
        description="Azimuth of the lean in the fabric plane, from the course (u) towards the "
        "wale (v)",
        default=math.radians(-90.0), min=-2 * math.pi, max=2 * math.pi, subtype="ANGLE",
    )
    theta_max: FloatProperty(
        name="Noise Angle",
        description="Largest deviation of a pile from the nominal direction (theta_max, below "
        "45 degrees)",
        default=math.radians(20.0), min=0.0, max=math.radians(44.9), subtype="ANGLE",
    )
    noise_scales: StringProperty(
        name="Noise Scales",
        description="Sampling coefficients k of the fractal noise, e.g. '1 2 4 8' (larger k: "
        "coarser features, more weight)",
        default="1 2 4 8",
    )
    seed: IntProperty(
        name="Seed", description="Random seed of the noise: same seed, same plush",
        default=0, min=0,
    )
    color_mode: EnumProperty(name="Colour", items=COLOR_MODE_ITEMS, default="SINGLE")
    color_1: _color_prop(0)
    color_2: _color_prop(1)
    color_3: _color_prop(2)
    color_4: _color_prop(3)
    color_count: IntProperty(
        name="Colours", description="How many colours the stripes cycle through",
        default=2, min=1, max=MAX_COLORS,
    )
    stripe_height: IntProperty(
        name="Stripe Height", description="Courses per stripe", default=8, min=1,
    )
    color_image_name: StringProperty(
        name="Image", description="Image giving each pile its colour at the pile's (u,v)",
    )
    press_image_name: StringProperty(
        name="Press Map",
        description="Image whose brightness (0..1) over (u,v) says where the fabric was "
        "pressed: the pile bends towards the fabric there",
    )
    press_strength: FloatProperty(
        name="Press Strength", description="How far a fully pressed pile bends (0..1)",
        default=0.9, min=0.0, max=1.0, subtype="FACTOR",
    )


#: The plush settings as the scripting API sees them.
PLUSH_SETTINGS = SettingsSchema("plush", PlushSettingsMixin)
#: Settings by name, in declaration order.
SETTING_NAMES: tuple[str, ...] = PLUSH_SETTINGS.names


def _poll_source(_self: bpy.types.PropertyGroup, obj: bpy.types.Object) -> bool:
    return obj.type in {"SURFACE", "MESH"}


class PlushSettings(PlushSettingsMixin, bpy.types.PropertyGroup):
    """A plush object's settings (``Object.knitwear_plush``), kept to re-grow it."""

    is_plush: BoolProperty(name="Is Plush", default=False)
    source: PointerProperty(
        name="Source", type=bpy.types.Object, poll=_poll_source,
        description="The surface this plush grows on",
    )
    follow_camera: BoolProperty(
        name="Follow Camera",
        description="Choose horizontal or vertical slices for the scene camera on every frame "
        "change (and in renders)",
        default=True,
    )
    #: Pinned when grown: the stitch counts and the grid density, so a re-grown field after a
    #: file load has exactly this topology.
    bound_counts: IntVectorProperty(size=2, default=(0, 0), options={"HIDDEN"})
    bound_samples: IntVectorProperty(size=2, default=(0, 0), options={"HIDDEN"})


# --- settings -> core keywords -------------------------------------------------------------


_complete = PLUSH_SETTINGS.complete


def _settings_from(obj: bpy.types.Object) -> dict[str, Any]:
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


def _image(name: str, what: str) -> bpy.types.Image:
    image = bpy.data.images.get(name)
    if image is None:
        raise knitwear.ParameterError(f"{what} image '{name}' not found")
    return image


def press_weights(image: bpy.types.Image) -> np.ndarray:
    """An image as the core's press map: (height, width) float32 luminance in 0..1, row 0 at
    v = 0 (Blender's bottom row)."""
    rgba = sampling.image_pixels(image)
    luminance = rgba[..., :3] @ np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)
    return np.ascontiguousarray(np.clip(luminance, 0.0, 1.0), dtype=np.float32)


def _colors(settings: Mapping[str, Any]) -> dict[str, Any]:
    palette = [tuple(settings[f"color_{i + 1}"]) for i in range(MAX_COLORS)]
    mode = settings["color_mode"]
    if mode == "SINGLE":
        return {"colors": palette[0]}
    if mode == "STRIPES":
        count = int(settings["color_count"])
        if not 1 <= count <= MAX_COLORS:
            raise knitwear.ParameterError(f"color_count must be 1 to {MAX_COLORS}, not {count}")
        return {
            "colors": knitwear.ColorPattern.stripes(
                palette[:count], rows_each=int(settings["stripe_height"])
            )
        }
    if mode == "IMAGE":
        name = settings["color_image_name"]
        if not name:
            raise knitwear.ParameterError("no colour image chosen for the Image colour mode")
        return {"color_image": sampling.image_pixels(_image(name, "colour"))}
    raise knitwear.ParameterError(f"unknown color_mode {mode!r}; expected SINGLE, STRIPES, IMAGE")


def _size(settings: Mapping[str, Any], scene: bpy.types.Scene) -> dict[str, Any]:
    if settings["size_mode"] == "COUNTS":
        return {"courses": int(settings["courses"]), "wales": int(settings["wales"])}
    if settings["size_mode"] == "GAUGE":
        # Per 10 cm -> per 0.1 scene units (one unit is scale_length metres).
        scale = scene.unit_settings.scale_length
        return {"gauge": (settings["gauge_wales"] * scale, settings["gauge_courses"] * scale)}
    raise knitwear.ParameterError(
        f"unknown size_mode {settings['size_mode']!r}; expected GAUGE or COUNTS"
    )


def core_settings(settings: Mapping[str, Any], scene: bpy.types.Scene) -> dict[str, Any]:
    """`knitwear.plush` keywords for ``settings`` (all but the surface and the view)."""
    out: dict[str, Any] = {
        **_size(settings, scene),
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
        out["press"] = press_weights(_image(settings["press_image_name"], "press"))
        out["press_strength"] = settings["press_strength"]
    return out


def _min_samples(counts: tuple[int, int]) -> tuple[int, int]:
    wales, courses = counts
    # Capped so an absurd count reaches the core's own checks instead of a huge grid.
    return (
        int(min(wales, 1e6) * SAMPLES_PER_STITCH) + 1,
        int(min(courses, 1e6) * SAMPLES_PER_STITCH) + 1,
    )


def _sample(
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
            math.ceil(extent_u * size["gauge"][0] / _GAUGE_LENGTH),
            math.ceil(extent_v * size["gauge"][1] / _GAUGE_LENGTH),
        )
    else:
        counts = (size["wales"], size["courses"])
    samples = _min_samples(counts)
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


def _to_local(obj_matrix: Matrix) -> Matrix:
    return obj_matrix.inverted_safe()


# --- mesh and material ---------------------------------------------------------------------


def _set_uvs(mesh: bpy.types.Mesh, uvs: np.ndarray, triangles: np.ndarray) -> None:
    layer = mesh.uv_layers.get(UV_MAP) or mesh.uv_layers.new(name=UV_MAP)
    corner_uvs = np.ascontiguousarray(uvs[triangles.ravel()], dtype=np.float32)
    layer.uv.foreach_set("vector", corner_uvs.ravel())
    layer.active = True
    layer.active_render = True


def _set_mask(mesh: bpy.types.Mesh, mask: np.ndarray) -> None:
    attribute = mesh.attributes.get(MASK_ATTRIBUTE)
    if attribute is None or attribute.data_type != "FLOAT" or attribute.domain != "POINT":
        if attribute is not None:
            mesh.attributes.remove(attribute)
        attribute = mesh.attributes.new(MASK_ATTRIBUTE, "FLOAT", "POINT")
    attribute.data.foreach_set("value", np.ascontiguousarray(mask, dtype=np.float32))


def _fill_extras(mesh: bpy.types.Mesh, result: Any) -> None:
    _set_uvs(mesh, result.uvs, result.triangles)
    _set_mask(mesh, result.mask)
    mesh.update()


def new_plush_mesh(name: str, result: Any) -> bpy.types.Mesh:
    """A new mesh holding a `knitwear.PlushResult`: positions, triangles and edges through
    the fast route, the "Col" colours, the "UVMap" UVs (per corner) and "plush_mask"."""
    mesh = mesh_build.new_mesh(name, result)
    try:
        _fill_extras(mesh, result)
    except BaseException:
        bpy.data.meshes.remove(mesh)
        raise
    return mesh


def _build_material(material: bpy.types.Material) -> None:
    if material.node_tree is None:
        material.use_nodes = True  # Blender 4.x; 5.0 always has a tree
    tree = material.node_tree
    nodes, links = tree.nodes, tree.links
    nodes.clear()

    output = nodes.new("ShaderNodeOutputMaterial")
    output.location = (500, 0)
    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.location = (200, 0)
    color = nodes.new("ShaderNodeVertexColor")
    color.location = (-100, 200)
    color.layer_name = mesh_build.COLOR_ATTRIBUTE
    # Velvet: a rough dielectric whose fibre tips catch grazing light.
    inputs = bsdf.inputs
    inputs["Roughness"].default_value = 0.9
    inputs["Sheen Weight"].default_value = 1.0
    inputs["Sheen Roughness"].default_value = 0.3
    inputs["Specular IOR Level"].default_value = 0.2
    links.new(color.outputs["Color"], inputs["Base Color"])
    links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])

    # Alpha from the slice's UV: a round disc for horizontal slices (1 - smoothstep of the
    # distance from the centre, radius 0.5), a rectangle soft at its long sides for vertical
    # ones (u runs across the slice's width), mixed by the core's per-vertex mask.
    uv = nodes.new("ShaderNodeUVMap")
    uv.location = (-900, -200)
    uv.uv_map = UV_MAP
    distance = nodes.new("ShaderNodeVectorMath")
    distance.location = (-650, -150)
    distance.operation = "DISTANCE"
    distance.inputs[1].default_value = (0.5, 0.5, 0.0)
    links.new(uv.outputs["UV"], distance.inputs[0])
    disc = nodes.new("ShaderNodeMapRange")
    disc.location = (-400, -150)
    disc.interpolation_type = "SMOOTHSTEP"
    disc.inputs["From Min"].default_value = 0.3
    disc.inputs["From Max"].default_value = 0.5
    disc.inputs["To Min"].default_value = 1.0
    disc.inputs["To Max"].default_value = 0.0
    links.new(distance.outputs["Value"], disc.inputs["Value"])

    split = nodes.new("ShaderNodeSeparateXYZ")
    split.location = (-650, -400)
    links.new(uv.outputs["UV"], split.inputs[0])
    edges = []
    for i, (lo, hi) in enumerate(((0.0, 0.2), (1.0, 0.8))):
        ramp = nodes.new("ShaderNodeMapRange")
        ramp.location = (-400, -350 - 200 * i)
        ramp.interpolation_type = "SMOOTHSTEP"
        ramp.inputs["From Min"].default_value = lo
        ramp.inputs["From Max"].default_value = hi
        links.new(split.outputs["X"], ramp.inputs["Value"])
        edges.append(ramp)
    rect = nodes.new("ShaderNodeMath")
    rect.location = (-150, -400)
    rect.operation = "MINIMUM"
    links.new(edges[0].outputs["Result"], rect.inputs[0])
    links.new(edges[1].outputs["Result"], rect.inputs[1])

    mask = nodes.new("ShaderNodeAttribute")
    mask.location = (-400, 100)
    mask.attribute_type = "GEOMETRY"
    mask.attribute_name = MASK_ATTRIBUTE
    mix = nodes.new("ShaderNodeMix")
    mix.location = (0, -200)
    mix.data_type = "FLOAT"
    links.new(mask.outputs["Fac"], mix.inputs["Factor"])
    links.new(disc.outputs["Result"], mix.inputs[2])  # A (float)
    links.new(rect.outputs["Value"], mix.inputs[3])  # B (float)
    links.new(mix.outputs[0], inputs["Alpha"])

    # EEVEE (4.2+) shows alpha with dithered (order-independent) transparency; Cycles always
    # does. Workbench ignores node alpha and draws whole quads.
    if hasattr(material, "surface_render_method"):
        material.surface_render_method = "DITHERED"
    else:
        material.blend_method = "HASHED"
    material.use_backface_culling = False
    material.diffuse_color = (0.3, 0.02, 0.03, 1.0)
    material.roughness = 0.9


def plush_material() -> bpy.types.Material:
    """The shared plush material, created on first use and never overwritten afterwards."""
    material = bpy.data.materials.get(MATERIAL_NAME)
    if material is None:
        material = bpy.data.materials.new(MATERIAL_NAME)
        _build_material(material)
    return material


# --- growing a plush -----------------------------------------------------------------------


@dataclass(frozen=True)
class PlushOutcome:
    """What one plush produced, for reports, tests and benchmarks."""

    object: bpy.types.Object
    result: Any
    piles: int
    triangles: int
    horizontal: int
    vertical: int
    #: Seconds from start to finished object; inside `knitwear.plush`; building the mesh.
    seconds: float
    core_seconds: float
    mesh_seconds: float


@dataclass
class _Entry:
    """A plush object's field, what it was grown from, and the last view written."""

    field: Any
    key: tuple[Any, ...]
    last_view: tuple[Any, ...] | None = None


#: Fields by plush object (`ID.session_uid`), re-grown on demand, dropped on file load.
_fields: dict[int, _Entry] = {}


def _check_source(source: bpy.types.Object | None, what: str) -> bpy.types.Object:
    if source is None:
        raise knitwear.SurfaceError(f"{what} has no source surface (was it deleted?)")
    if source.type not in {"SURFACE", "MESH"}:
        raise knitwear.SurfaceError(
            f"'{source.name}' is a {source.type.lower()}: plush grows on NURBS surfaces and "
            "meshes with a UV map"
        )
    if source.knitwear_plush.is_plush or source.knitwear.is_knit:
        raise knitwear.SurfaceError(
            f"'{source.name}' is itself a plush or a knit: use its source instead"
        )
    return source


def _grow(
    source: bpy.types.Object,
    context: bpy.types.Context,
    settings: Mapping[str, Any],
    to_local: Matrix | None,
    camera: bpy.types.Object | None,
    counts: tuple[int, int] | None = None,
    samples: tuple[int, int] | None = None,
    depsgraph: bpy.types.Depsgraph | None = None,
) -> tuple[sampling.Sampled, Any, tuple[int, int] | None, float]:
    """Sample the source and run the core; nothing in ``bpy.data`` changes. ``counts`` and
    ``samples`` pin the stitch grid and tessellation of an existing plush."""
    kwargs = core_settings(settings, context.scene)
    if counts is not None:
        kwargs.pop("gauge", None)
        kwargs["wales"], kwargs["courses"] = counts
    if samples is not None and source.type == "SURFACE":
        sampled = sampling.sample_object(source, context, min_samples=samples,
                                         depsgraph=depsgraph)
    else:
        sampled, samples = _sample(source, context, kwargs, depsgraph)
    local = to_local if to_local is not None else _to_local(sampled.matrix)
    kwargs.update(view_of(camera, local, depsgraph))
    t0 = time.perf_counter()
    result = knitwear.plush(sampled.surface, **kwargs)
    return sampled, result, samples, time.perf_counter() - t0


def _store(
    obj: bpy.types.Object,
    source: bpy.types.Object,
    settings: Mapping[str, Any],
    result: Any,
    samples: tuple[int, int] | None,
) -> None:
    stored = obj.knitwear_plush
    for name, value in settings.items():
        setattr(stored, name, value)
    stored.source = source
    stats = result.stats
    stored.bound_counts = (int(stats["wales"]), int(stats["courses"]))
    stored.bound_samples = samples or (0, 0)
    stored.is_plush = True


def _key(obj: bpy.types.Object) -> tuple[Any, ...]:
    stored = obj.knitwear_plush
    return (
        tuple(sorted(_settings_from(obj).items())),
        tuple(stored.bound_counts),
        tuple(stored.bound_samples),
        stored.source.name if stored.source else None,
        obj.data.get(mesh_build.TOPOLOGY_PROPERTY),
        len(obj.data.vertices),
    )


def plush(
    source: bpy.types.Object,
    *,
    context: bpy.types.Context | None = None,
    camera: bpy.types.Object | None = None,
    **settings: Any,
) -> PlushOutcome:
    """Grow plush over ``source`` as a new object "<source>.plush"; return it with counts and
    timings. The slices are chosen for ``camera`` (default: the scene's camera; none: along
    each normal). Raises `knitwear.KnitError`, with nothing created, for anything a user can
    get wrong."""
    t_start = time.perf_counter()
    context = context or bpy.context
    settings = _complete(settings)
    source = _check_source(source, "the object")
    camera = camera or context.scene.camera
    sampled, result, samples, core_s = _grow(source, context, settings, None, camera)

    t_mesh = time.perf_counter()
    name = f"{source.name}.plush"
    mesh = new_plush_mesh(name, result)
    mesh_s = time.perf_counter() - t_mesh
    mesh.materials.append(plush_material())
    obj = bpy.data.objects.new(name, mesh)
    obj.matrix_world = sampled.matrix
    collection = source.users_collection[0] if source.users_collection else None
    (collection or context.scene.collection).objects.link(obj)
    _store(obj, source, settings, result, samples)
    _fields[obj.session_uid] = _Entry(result.field, _key(obj))
    # The frame handler writes mesh data, which renders want done with the interface locked.
    context.scene.render.use_lock_interface = True
    stats = result.stats
    return PlushOutcome(
        object=obj,
        result=result,
        piles=int(stats["piles"]),
        triangles=len(result.triangles),
        horizontal=int(stats["horizontal"]),
        vertical=int(stats["vertical"]),
        seconds=time.perf_counter() - t_start,
        core_seconds=core_s,
        mesh_seconds=mesh_s,
    )


def knit_plush(
    source: bpy.types.Object,
    *,
    context: bpy.types.Context | None = None,
    camera: bpy.types.Object | None = None,
    **settings: Any,
) -> bpy.types.Object:
    """Grow plush over ``source`` (a NURBS surface or a mesh with a UV map) and return the
    new object. ``settings`` are `PlushSettingsMixin`'s by name (e.g. ``size_mode="COUNTS",
    courses=384, wales=240, pile_length=0.004, seed=2, press_image_name="Palm"``)."""
    return plush(source, context=context, camera=camera, **settings).object


def _field(
    obj: bpy.types.Object,
    context: bpy.types.Context,
    depsgraph: bpy.types.Depsgraph | None = None,
) -> _Entry:
    """``obj``'s cached field, or one grown again from its stored settings (same counts,
    tessellation and seed: the same field, so the same topology)."""
    key = _key(obj)
    entry = _fields.get(obj.session_uid)
    if entry is not None and entry.key == key:
        return entry
    stored = obj.knitwear_plush
    source = _check_source(stored.source, f"'{obj.name}'")
    samples = tuple(stored.bound_samples)
    _sampled, result, _samples, _s = _grow(
        source,
        context,
        _complete(_settings_from(obj)),
        _to_local(obj.matrix_world),
        None,
        counts=tuple(stored.bound_counts),
        samples=samples if samples != (0, 0) else None,
        depsgraph=depsgraph,
    )
    field = result.field
    if (
        format(int(result.stats["topology_key"]), "016x")
        != obj.data.get(mesh_build.TOPOLOGY_PROPERTY)
        or len(result.vertices) != len(obj.data.vertices)
    ):
        raise knitwear.SurfaceError(
            f"'{obj.name}' no longer matches its source (its mesh was edited, or the source's "
            "size or UV map changed): grow the plush again"
        )
    entry = _Entry(field, key)
    _fields[obj.session_uid] = entry
    return entry


def update_plush_view(
    obj: bpy.types.Object,
    *,
    context: bpy.types.Context | None = None,
    camera: bpy.types.Object | None = None,
    depsgraph: bpy.types.Depsgraph | None = None,
    force: bool = False,
) -> bool:
    """Choose ``obj``'s slices for ``camera`` (default: the scene's) and write the new
    positions and mask in place (topology, UVs and colours stay). Returns whether anything
    was written (not when the view is the one last written, unless ``force``). Raises
    `knitwear.KnitError` when the plush cannot be re-grown (its source was deleted...)."""
    context = context or bpy.context
    if not obj.knitwear_plush.is_plush:
        raise knitwear.ParameterError(f"'{obj.name}' is not a plush")
    scene = context.scene
    camera = camera or scene.camera
    entry = _field(obj, context, depsgraph)
    matrix = obj.evaluated_get(depsgraph).matrix_world if depsgraph else obj.matrix_world
    view = view_of(camera, _to_local(matrix), depsgraph)
    view_key = tuple(sorted(view.items()))
    if not force and view_key == entry.last_view:
        return False
    new = entry.field.view(**view, threads=scene.render.threads)
    mesh = obj.data
    _set_mask(mesh, new.mask)
    mesh_build.write_positions(mesh, new.vertices)  # one foreach_set + update()
    entry.last_view = view_key
    return True


def noise_image(
    obj: bpy.types.Object, *, context: bpy.types.Context | None = None
) -> bpy.types.Image:
    """The plush's fractal-noise pile directions as the paper's image ((v + 1) / 2 as RGB, in
    the noise frame: blue is along the nominal direction), in an image datablock named
    "<object> Pile Noise" (made or overwritten), for the Image Editor."""
    context = context or bpy.context
    if not obj.knitwear_plush.is_plush:
        raise knitwear.ParameterError(f"'{obj.name}' is not a plush")
    rgb = _field(obj, context, None).field.noise_rgb
    height, width = rgb.shape[:2]
    name = f"{obj.name} Pile Noise"
    image = bpy.data.images.get(name)
    if image is None or tuple(image.size) != (width, height):
        if image is not None:
            bpy.data.images.remove(image)
        image = bpy.data.images.new(name, width, height, float_buffer=True)
    # The noise encodes directions, not colours: no colour management.
    image.colorspace_settings.is_data = True
    rgba = np.ones((height, width, 4), np.float32)
    rgba[..., :3] = rgb
    image.pixels.foreach_set(rgba.ravel())
    image.update()
    return image


class OBJECT_OT_knitwear_plush_noise(bpy.types.Operator):
    """Make an image of this plush's fractal-noise pile directions (open it in the Image
    Editor)"""

    bl_idname = "object.knitwear_plush_noise"
    bl_label = "Show Pile Noise"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        return obj is not None and obj.knitwear_plush.is_plush

    def execute(self, context: bpy.types.Context) -> set[str]:
        try:
            image = noise_image(context.active_object, context=context)
        except knitwear.KnitError as err:
            self.report({"ERROR"}, str(err))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Pile noise in image '{image.name}' ({image.size[0]}x"
                    f"{image.size[1]})")
        return {"FINISHED"}


def plush_objects(scene: bpy.types.Scene) -> list[bpy.types.Object]:
    """The plush objects of ``scene`` that follow the camera."""
    return [
        obj
        for obj in scene.objects
        if obj.type == "MESH"
        and obj.knitwear_plush.is_plush
        and obj.knitwear_plush.follow_camera
    ]


_on_frame_change = frame_handlers.per_object(
    plush_objects,
    lambda obj, depsgraph: update_plush_view(obj, depsgraph=depsgraph),
    "did not follow the camera",
)


@persistent
def _on_load(*_args: object) -> None:
    _fields.clear()


# --- operators, panel, menu ----------------------------------------------------------------


def _draw_settings(layout: bpy.types.UILayout, settings: bpy.types.AnyType, prefix: str) -> None:
    layout.use_property_split = True
    layout.use_property_decorate = False
    header, body = layout.panel(f"{prefix}_size")
    header.label(text="Size")
    if body is not None:
        body.row().prop(settings, "size_mode", expand=True)
        col = body.column(align=True)
        if settings.size_mode == "GAUGE":
            col.prop(settings, "gauge_wales")
            col.prop(settings, "gauge_courses")
        else:
            col.prop(settings, "courses")
            col.prop(settings, "wales")
        body.prop(settings, "piles_per_stitch")
    header, body = layout.panel(f"{prefix}_pile")
    header.label(text="Pile")
    if body is not None:
        for name in ("pile_length", "pile_radius", "slices", "lean_angle", "lean_direction",
                     "theta_max", "noise_scales", "seed"):
            body.prop(settings, name)
    header, body = layout.panel(f"{prefix}_colour")
    header.label(text="Colour")
    if body is not None:
        body.prop(settings, "color_mode")
        shown = 1
        if settings.color_mode == "STRIPES":
            body.prop(settings, "color_count")
            body.prop(settings, "stripe_height")
            shown = settings.color_count
        elif settings.color_mode == "IMAGE":
            body.prop_search(settings, "color_image_name", bpy.data, "images")
            shown = 0
        col = body.column(align=True)
        for i in range(shown):
            col.prop(settings, f"color_{i + 1}")
    header, body = layout.panel(f"{prefix}_press", default_closed=True)
    header.label(text="Press")
    if body is not None:
        body.prop_search(settings, "press_image_name", bpy.data, "images")
        body.prop(settings, "press_strength")


def _summary(outcome: PlushOutcome) -> str:
    return (
        f"Plush: {outcome.piles:,} piles, {outcome.triangles:,} triangles "
        f"({outcome.horizontal:,} horizontal, {outcome.vertical:,} vertical) "
        f"in {outcome.seconds:.2f} s"
    )


class OBJECT_OT_knitwear_plush(PlushSettingsMixin, bpy.types.Operator):
    """Grow warp-knit plush (pile) over the active NURBS surface or UV-mapped mesh, as a new
    object whose slices follow the scene camera"""

    bl_idname = "object.knitwear_plush"
    bl_label = "Plush this surface"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        if obj is None or obj.type not in {"SURFACE", "MESH"}:
            cls.poll_message_set("Select a NURBS surface or a mesh with a UV map")
            return False
        if context.mode != "OBJECT":
            cls.poll_message_set("Switch to Object Mode to grow plush")
            return False
        if obj.knitwear_plush.is_plush or obj.knitwear.is_knit:
            cls.poll_message_set("The active object is already a plush or a knit")
            return False
        return True

    def execute(self, context: bpy.types.Context) -> set[str]:
        settings = {name: getattr(self, name) for name in SETTING_NAMES}
        try:
            outcome = plush(context.active_object, context=context, **settings)
        except knitwear.KnitError as err:
            self.report({"ERROR"}, str(err))
            return {"CANCELLED"}
        for other in context.selected_objects:
            other.select_set(False)
        try:
            outcome.object.select_set(True)
            context.view_layer.objects.active = outcome.object
        except RuntimeError:
            pass  # the source's collection is excluded from this view layer
        self.report({"INFO"}, _summary(outcome))
        return {"FINISHED"}

    def draw(self, _context: bpy.types.Context) -> None:
        _draw_settings(self.layout, self, "knitwear_plush_redo")


class OBJECT_OT_knitwear_plush_view(bpy.types.Operator):
    """Choose the active plush's slices for the scene camera now"""

    bl_idname = "object.knitwear_plush_view"
    bl_label = "Update Plush View"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        if obj is None or obj.type != "MESH" or not obj.knitwear_plush.is_plush:
            cls.poll_message_set("The active object is not a plush")
            return False
        return True

    def execute(self, context: bpy.types.Context) -> set[str]:
        try:
            update_plush_view(context.active_object, context=context, force=True)
        except knitwear.KnitError as err:
            self.report({"ERROR"}, str(err))
            return {"CANCELLED"}
        return {"FINISHED"}


class VIEW3D_PT_knitwear_plush(bpy.types.Panel):
    """A plush's source, camera following and the settings it was grown with."""

    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Knitwear"
    bl_label = "Plush"

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        return obj is not None and obj.type in {"SURFACE", "MESH"}

    def draw(self, context: bpy.types.Context) -> None:
        layout = self.layout
        stored = context.active_object.knitwear_plush
        if not stored.is_plush:
            layout.operator(OBJECT_OT_knitwear_plush.bl_idname, icon="OUTLINER_OB_CURVES")
            return
        layout.use_property_split = True
        layout.use_property_decorate = False
        layout.prop(stored, "source")
        layout.prop(stored, "follow_camera")
        layout.operator(OBJECT_OT_knitwear_plush_view.bl_idname, icon="VIEW_CAMERA")
        layout.operator(OBJECT_OT_knitwear_plush_noise.bl_idname, icon="IMAGE_DATA")
        box = layout.column()
        box.label(text="Grown with (undo and redo the operator to change):")
        box.enabled = False
        _draw_settings(box, stored, "knitwear_plush_panel")


def draw_object_menu(self: bpy.types.Menu, _context: bpy.types.Context) -> None:
    """Object menu entries (which also makes them searchable with F3)."""
    self.layout.operator(OBJECT_OT_knitwear_plush.bl_idname, icon="OUTLINER_OB_CURVES")


_CLASSES: tuple[type, ...] = (
    PlushSettings,
    OBJECT_OT_knitwear_plush,
    OBJECT_OT_knitwear_plush_view,
    OBJECT_OT_knitwear_plush_noise,
    VIEW3D_PT_knitwear_plush,
)
_HANDLERS = (
    (bpy.app.handlers.frame_change_post, _on_frame_change),
    (bpy.app.handlers.load_post, _on_load),
)


def register() -> None:
    for cls in _CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Object.knitwear_plush = PointerProperty(type=PlushSettings)
    bpy.types.VIEW3D_MT_object.append(draw_object_menu)
    for handlers, handler in _HANDLERS:
        if handler not in handlers:
            handlers.append(handler)


def unregister() -> None:
    for handlers, handler in reversed(_HANDLERS):
        if handler in handlers:
            handlers.remove(handler)
    bpy.types.VIEW3D_MT_object.remove(draw_object_menu)
    del bpy.types.Object.knitwear_plush
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
    _fields.clear()
