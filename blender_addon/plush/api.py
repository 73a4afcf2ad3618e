"""Growing a plush and following the camera: the scripting API (`plush`, `knit_plush`,
`update_plush_view`, `noise_image`) that the operators and the frame handler call."""

import time
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import bpy
import knitwear
import numpy as np
from bpy.app.handlers import persistent
from mathutils import Matrix

from .. import frame_handlers, mesh_build, sampling
from .core_inputs import complete, core_settings, sample, settings_from, view_of, world_to_local
from .mesh import new_plush_mesh, plush_material, set_mask


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
        sampled, samples = sample(source, context, kwargs, depsgraph)
    local = to_local if to_local is not None else world_to_local(sampled.matrix)
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
        tuple(sorted(settings_from(obj).items())),
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
    settings = complete(settings)
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
        complete(settings_from(obj)),
        world_to_local(obj.matrix_world),
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
    view = view_of(camera, world_to_local(matrix), depsgraph)
    view_key = tuple(sorted(view.items()))
    if not force and view_key == entry.last_view:
        return False
    new = entry.field.view(**view, threads=scene.render.threads)
    mesh = obj.data
    set_mask(mesh, new.mask)
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


def plush_objects(scene: bpy.types.Scene) -> list[bpy.types.Object]:
    """The plush objects of ``scene`` that follow the camera."""
    return [
        obj
        for obj in scene.objects
        if obj.type == "MESH"
        and obj.knitwear_plush.is_plush
        and obj.knitwear_plush.follow_camera
    ]


on_frame_change = frame_handlers.per_object(
    plush_objects,
    lambda obj, depsgraph: update_plush_view(obj, depsgraph=depsgraph),
    "did not follow the camera",
)


@persistent
def on_load(*_args: object) -> None:
    _fields.clear()
