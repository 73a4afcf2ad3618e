"""Scripting API: knit an object without the UI.

Everything the Knit operator and the Update operator do goes through here, so a script gets
exactly what a click gets::

    import bpy
    from bl_ext.user_default.knitwear import api

    knit = api.knit_object(bpy.data.objects["Sweater"], pattern="rib_2x2",
                           color_mode="STRIPES", color_count=2, stripe_height=4)
    api.update_knit(knit, gauge_stitches=24)

Settings are the keyword arguments of `knit_object` (see `properties.KnitSettingsMixin`
for names, units and defaults). Every failure a user can cause raises a `knitwear.KnitError`
subclass with a message fit for a report, and leaves the blend file as it was.

A knit and an update are also available as steps (`knit_steps`, `update_steps`): generators
that yield the jobs only the core runs (each a `CoreJob`: no `bpy`, the GIL released
inside: the knit's preparation, then the wait for its build, which runs on a thread of its own
while the steps make the mesh's triangle template), are sent each result back and return the
outcome. `run_steps` runs the jobs inline (what `knit` and `update` do); the operators run
them on a worker thread (`core_thread`) so the interface stays live and Esc stops them.
"""

import threading
import time
from collections.abc import Callable, Generator, Mapping
from dataclasses import dataclass
from typing import Any, TypeVar

import bpy
import knitwear
import numpy as np

from . import (
    animation,
    core_inputs,
    frame_handlers,
    material,
    mesh_build,
    new_data,
    sampling,
    source_link,
    texture,
)
from .properties import KNIT_SETTINGS

#: Called with the fraction done (0..1) between the steps of a knit.
Progress = core_inputs.Progress

#: Below this many diameters of clearance on a flat patch loops overlap visibly (docs/design.md
#: section 7): the user is warned. With every course interlocked the tuned loops of the
#: knit/purl presets keep 0.6-0.97 at the default yarn, but cables and lace still fall
#: below it (their loop shapes are the open work of "Knitted, not stacked"), and the
#: warning says so rather than hiding it.
MIN_CLEARANCE = 0.5

#: The share of stitches more than 15% off the gauge (their width or height against the mean,
#: where the UV map stretches more or less than on average) above which a knit's report
#: warns: a knitter sees the gauge change there.
UNEVEN_SHARE = 0.05

#: Custom property of a knit object: its stitch levels (one byte per stitch, row-major) when
#: it was knitted with auto detail, pinned so every frame rebuilds the same topology. Stored
#: packed (`pack_pinned`); read it with `bound_of`.
LEVELS_PROPERTY = "knitwear_stitch_levels"

#: Custom property of a knit object knitted with Cull Hidden Yarn: the triangles the camera
#: saw (one bit per triangle before culling), pinned as the levels are.
SEEN_PROPERTY = "knitwear_seen_triangles"

#: An animated camera is sampled at most at this many frames of the scene's frame range.
MAX_CAMERA_FRAMES = 25

#: Names of the core's detail levels, finest first.
LEVEL_NAMES = ("full", "mid", "far", "texture", "culled")


@dataclass(frozen=True)
class KnitOutcome:
    """What one knit produced, for reports and benchmarks."""

    object: bpy.types.Object
    stitches: int
    triangles: int
    #: Stitches of the grid not built: in empty UV space between islands, or lost.
    skipped_stitches: int
    #: Of them, stitches of fabric lost where a UV island ends part-way through a stitch.
    lost_stitches: int
    #: Stitches whose normal offsets were clamped where the surface curves more tightly than
    #: the yarn stands off it (a thin tube, a sharp crease).
    clamped_stitches: int
    #: The smallest distance between yarns the loop shapes reach on a flat patch, in yarn
    #: diameters: below `MIN_CLEARANCE` the yarn is too thick for its stitch and loops overlap.
    flat_clearance: float
    #: Seconds from start to finished mesh; of them, sampling the source (and its camera
    #: views), inside the core (the hidden-yarn pass included), and the hidden-yarn pass.
    seconds: float
    sampling_seconds: float
    core_seconds: float
    hidden_pass_seconds: float
    #: Seconds spent building the Blender mesh from the core's arrays.
    mesh_seconds: float
    #: Stitches at each detail level (`LEVEL_NAMES`); all "full" without auto detail.
    levels: dict[str, int]
    #: Triangles the knit would have with every stitch at full quality.
    triangles_full_detail: int
    #: Triangles culled as hidden behind other yarn (Cull Hidden Yarn), of those its levels
    #: make.
    triangles_hidden: int
    #: With Cull Hidden Yarn (on, auto detail, a still source), whether its pass ran: False
    #: where the knit has fewer full-detail triangles than Cull From (it is then built whole,
    #: which is quicker); None where it was not asked for.
    hidden_pass: bool | None
    #: Whether auto detail applied (Detail is Auto and the scene has a camera).
    auto_detail: bool
    #: The material of the knitwear texture the source now wears, where stitches were left
    #: to it; None otherwise.
    texture_material: str | None
    #: How far the stitches' sizes spread round the gauge where the UV map stretches
    #: (`stats["stitch_spread"]`: "width" and "height" as 5th and 95th percentiles over the
    #: mean, and the share of "stretched" stitches); None where it was not measured.
    stitch_spread: dict[str, Any] | None = None
    #: Whether the fabric closes round along u and along v (`stats["in_the_round"]`): a
    #: closed NURBS surface, or a mesh whose UV seam closes it, is knitted in the round.
    in_the_round: tuple[bool, bool] = (False, False)

    @property
    def uneven(self) -> bool:
        """Whether the UV map stretches enough stitches visibly off the gauge to warn."""
        spread = self.stitch_spread
        return spread is not None and spread["stretched"] > UNEVEN_SHARE


def settings_from(obj: bpy.types.Object) -> dict[str, Any]:
    """The knit settings stored on ``obj`` (a knit object), as `knit_object` keywords."""
    return KNIT_SETTINGS.read(obj.knitwear)


@dataclass(frozen=True)
class Bound:
    """What a knit pins at bind time so that any later pose rebuilds the same topology."""

    counts: tuple[int, int]
    yarn_radius: float
    stitch_size: tuple[float, float]
    #: Grid samples the NURBS source was tessellated with, or (0, 0) for a mesh.
    samples: tuple[int, int]
    #: Each stitch's detail level (one byte per stitch, row-major) with auto detail, else
    #: None.
    levels: bytes | None = None
    #: The triangles seen (one bit per triangle before culling) with Cull Hidden Yarn, else
    #: None.
    seen: bytes | None = None


def pack_pinned(data: bytes) -> np.ndarray:
    """Pinned bytes as the ID property array `bound_of` reads back: int32 ``[byte count,
    the bytes zero-padded to whole little-endian words...]``.

    Not a bytes property: Blender 5.0.1 cuts a bytes ID property at its first zero byte when
    an existing one is assigned again (an Update Knit), and an array has an explicit length
    that no version truncates. It is also assigned from a buffer, at memory speed.
    """
    padded = data + bytes(-len(data) % 4)
    words = np.frombuffer(padded, dtype="<i4")
    return np.concatenate([np.array([len(data)], dtype=np.int32), words.astype(np.int32)])


def unpack_pinned(value: Any) -> bytes | None:
    """The bytes `pack_pinned` stored (or a bytes property of a file saved before it)."""
    if value is None:
        return None
    if isinstance(value, bytes):
        return value  # a bytes property: a file saved before `pack_pinned`
    words = np.asarray(value, dtype=np.int32)
    if words.size == 0 or not 0 <= int(words[0]) <= 4 * (words.size - 1):
        raise knitwear.SurfaceError(
            "the knit's pinned detail data is damaged: use Update Knit to pin it again"
        )
    return words[1:].astype("<i4").tobytes()[: int(words[0])]


def _set_pinned(obj: bpy.types.Object, key: str, data: bytes | None) -> None:
    # Removed first: assigning over an existing property keeps parts of the old one (its type,
    # and in 5.0.1 a bytes value's length up to its first zero byte).
    obj.pop(key, None)
    if data is not None:
        obj[key] = pack_pinned(data)


def _camera_frames(scene: bpy.types.Scene, source_animates: bool) -> list[int]:
    """The frames to model the knit for: the current one, and where the camera or the
    source moves, up to `MAX_CAMERA_FRAMES` spread over the scene's frame range."""
    frames = [scene.frame_current]
    start, end = scene.frame_start, scene.frame_end
    if end > start and (source_animates or animation.animates(scene.camera)):
        count = min(MAX_CAMERA_FRAMES, end - start + 1)
        frames += [int(round(f)) for f in np.linspace(start, end, count)]
    return sorted(set(frames))


def _camera_view(
    scene: bpy.types.Scene,
    source: bpy.types.Object,
    depsgraph: bpy.types.Depsgraph,
    origin: tuple[float, float, float],
) -> tuple[np.ndarray, np.ndarray]:
    """The scene camera's clip-from-object matrix and eye in the knit's object space (the
    source's location and rotation moved to ``origin``, as `sampling` gives the knit), in
    the current frame."""
    cam = scene.camera.evaluated_get(depsgraph)
    r = scene.render
    x = max(1, r.resolution_x * r.resolution_percentage // 100)
    y = max(1, r.resolution_y * r.resolution_percentage // 100)
    proj = cam.calc_matrix_camera(
        depsgraph, x=x, y=y, scale_x=r.pixel_aspect_x, scale_y=r.pixel_aspect_y
    )
    world_from_object = sampling.knit_matrix(
        source.evaluated_get(depsgraph).matrix_world, origin
    )
    clip = proj @ cam.matrix_world.inverted() @ world_from_object
    object_from_world = world_from_object.inverted()
    if cam.data.type == "ORTHO":
        # The camera looks down its -Z: +Z points back towards it.
        towards = (object_from_world.to_3x3() @ cam.matrix_world.col[2].xyz).normalized()
        eye = (*towards, 0.0)
    else:
        eye = (*(object_from_world @ cam.matrix_world.translation), 1.0)
    return np.array(clip, dtype=np.float64), np.array(eye, dtype=np.float64)


def _is_closed(source: bpy.types.Object, depsgraph: bpy.types.Depsgraph) -> bool:
    """Whether ``source`` as evaluated is a closed surface: every edge on the border of
    only one face has (next to) no length (the poles of a sphere)."""
    evaluated = source.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        if mesh is None or len(mesh.polygons) == 0:
            return False
        ne = len(mesh.edges)
        loop_edges = np.empty(len(mesh.loops), dtype=np.int32)
        mesh.loops.foreach_get("edge_index", loop_edges)
        border = np.flatnonzero(np.bincount(loop_edges, minlength=ne) == 1)
        if border.size == 0:
            return True
        edges = np.empty((ne, 2), dtype=np.int32)
        mesh.edges.foreach_get("vertices", edges.ravel())
        pos = np.empty((len(mesh.vertices), 3), dtype=np.float32)
        mesh.attributes["position"].data.foreach_get("vector", pos.ravel())
        size = float(np.linalg.norm(pos.max(axis=0) - pos.min(axis=0)))
        a, b = pos[edges[border, 0]], pos[edges[border, 1]]
        return float(np.linalg.norm(a - b, axis=1).max()) <= 1e-6 * max(size, 1e-30)
    finally:
        evaluated.to_mesh_clear()


def detail_settings(
    source: bpy.types.Object,
    context: bpy.types.Context,
    settings: Mapping[str, Any],
    origin: tuple[float, float, float] = (0.0, 0.0, 0.0),
    pose: Callable[[bpy.types.Depsgraph], sampling.Sampled] | None = None,
) -> dict[str, Any]:
    """The core's camera-driven detail keywords for ``settings``: empty unless Detail is
    Auto and the scene has a (perspective or orthographic) camera. An animated camera or
    source is followed over the scene's frame range (the frame is restored after).
    ``origin`` is the sampled source's (`sampling.Sampled.origin`). ``pose`` samples the
    source as a depsgraph evaluates it, as the knit samples it: where the source animates,
    each frame's view then sees the source in that frame's pose, so a part that moves into
    the frame, or up to the camera, is built for the frame that sees it best."""
    scene = context.scene
    camera = scene.camera
    if settings["detail_mode"] != "AUTO" or camera is None or camera.type != "CAMERA":
        return {}
    if camera.data.type not in {"PERSP", "ORTHO"}:
        return {}  # a panoramic projection has no single clip matrix
    # Armatures, hooks, physics...: whatever the depsgraph animates it with counts.
    source_animates = animation.animates(source, context)
    frame, subframe = scene.frame_current, scene.frame_subframe
    frames = _camera_frames(scene, source_animates)
    posed = pose is not None and source_animates and len(frames) > 1
    views = []
    poses = []
    with frame_handlers.paused():
        try:
            for f in frames:
                if f != scene.frame_current or len(frames) > 1:
                    scene.frame_set(f)
                depsgraph = context.evaluated_depsgraph_get()
                if posed:
                    assert pose is not None
                    sampled = pose(depsgraph)
                    poses.append(sampled.surface)
                    views.append(_camera_view(scene, source, depsgraph, sampled.origin))
                else:
                    views.append(_camera_view(scene, source, depsgraph, origin))
        finally:
            if (scene.frame_current, scene.frame_subframe) != (frame, subframe):
                scene.frame_set(frame, subframe=subframe)
    r = scene.render
    resolution = (
        max(1, r.resolution_x * r.resolution_percentage // 100),
        max(1, r.resolution_y * r.resolution_percentage // 100),
    )
    camera_views = knitwear.Camera(
        np.stack([v[0] for v in views]),
        np.stack([v[1] for v in views]),
        resolution,
        poses=poses if posed else None,
    )
    cull_back = bool(settings["cull_back_faces"]) and _is_closed(
        source, context.evaluated_depsgraph_get()
    )
    # Each frame's view finds the yarn it sees on the source in that frame's pose (the core
    # builds the knit in each pose to look), so what an animated source shows later was
    # built. Without the poses the pass would see the pose now only: then nothing is culled.
    cull_hidden = bool(settings["cull_hidden"]) and (posed or not source_animates)
    return {
        "camera": camera_views,
        "detail_px": (
            float(settings["detail_full_px"]),
            float(settings["detail_mid_px"]),
            float(settings["detail_texture_px"]),
        ),
        "frustum_margin": float(settings["frustum_margin"]),
        "cull_back_faces": cull_back,
        "cull_hidden": cull_hidden,
        "hidden_supersampling": int(settings["cull_hidden_samples"]),
        "cull_hidden_min_triangles": int(settings["cull_hidden_min_triangles"]),
    }


#: A step of a knit that only the core runs: no `bpy` (whatever thread runs it), the GIL
#: released while the core works, stopped by `knitwear.cancel` with `knitwear.CancelledError`.
CoreJob = Callable[[], Any]
T = TypeVar("T")


def run_steps(steps: Generator[CoreJob, Any, T]) -> T:
    """Drive ``steps`` (`knit_steps`, `update_steps`) to their outcome on this thread, each
    core job inline. An exception from a job is thrown back into the steps, as
    `core_thread.StepsOnThread` does."""
    value: Any = None
    error: BaseException | None = None
    while True:
        try:
            job = steps.throw(error) if error is not None else steps.send(value)
        except StopIteration as done:
            return done.value
        try:
            value, error = job(), None
        except BaseException as e:  # noqa: BLE001 - handed back to the steps, as a thread would
            value, error = None, e


def _core_steps(
    source: bpy.types.Object,
    context: bpy.types.Context,
    settings: Mapping[str, Any],
    progress: Progress | None,
) -> Generator[CoreJob, Any, tuple[sampling.Sampled, Any, Bound, tuple[float, float]]]:
    """Everything that can fail, before any datablock is created: sampling here, then the
    core's knit as `CoreJob`s. Returns the seconds of both: (sampling, core)."""
    try:
        return (yield from _core_steps_sized(source, context, settings, progress))
    except knitwear.BudgetError as err:
        raise _at_real_size(err, source, context, settings) from err


def _at_real_size(
    err: knitwear.BudgetError,
    source: bpy.types.Object,
    context: bpy.types.Context,
    settings: Mapping[str, Any],
) -> knitwear.BudgetError:
    """A refusal for size that says why a knit is so large: the first knit of Blender's 2 m
    default cube is 2.7 million stitches, because knitting happens at a real gauge."""
    if settings["size_mode"] != "GAUGE":
        return err
    metres = [d * context.scene.unit_settings.scale_length for d in source.dimensions]
    size = " x ".join(f"{m:.3g}" for m in metres)
    return knitwear.BudgetError(
        f"{err}. Knitwear knits at a real gauge ({settings['gauge_stitches']:g} stitches per "
        f"10 cm) and '{source.name}' measures {size} m: scale it to the size of the real "
        "garment piece, or set Size to Counts"
    )


def _core_steps_sized(
    source: bpy.types.Object,
    context: bpy.types.Context,
    settings: Mapping[str, Any],
    progress: Progress | None,
) -> Generator[CoreJob, Any, tuple[sampling.Sampled, Any, Bound, tuple[float, float]]]:
    t_sampling = time.perf_counter()
    inputs = core_inputs.core_inputs(source, context, settings, progress)
    sampled, pattern, kwargs, min_samples = (
        inputs.sampled,
        inputs.pattern,
        inputs.kwargs,
        inputs.min_samples,
    )
    def pose(depsgraph: bpy.types.Depsgraph) -> sampling.Sampled:
        return sampling.sample_object(
            source,
            context,
            direction=settings["direction"],
            min_samples=min_samples,
            depsgraph=depsgraph,
        )

    detail = detail_settings(source, context, settings, sampled.origin, pose)
    sampling_seconds = time.perf_counter() - t_sampling

    def prepare() -> tuple[Any, float]:
        t0 = time.perf_counter()
        knit = knitwear.Knit(sampled.surface, pattern, **kwargs, **detail)
        return knit, time.perf_counter() - t0

    knit, prepare_seconds = yield prepare
    # The core builds on a thread of its own (it holds no GIL) while this one, which alone may
    # touch bpy, makes the mesh's triangle template: the first knit of a face count no longer
    # waits for it after the core (about 0.1 s per million triangles).
    build = _BuildThread(knit, sampled.surface)
    mesh_build.ready_template(knit.triangle_count)
    result, build_seconds = yield build.result
    core_seconds = prepare_seconds + build_seconds
    levels = knit.stitch_levels
    bound = Bound(
        knit.counts,
        knit.yarn_radius,
        knit.stitch_size,
        min_samples or (0, 0),
        None if levels is None else levels.tobytes(),
        knit.seen_triangles,
    )
    if progress:
        progress(0.8)
    return sampled, result, bound, (sampling_seconds, core_seconds)


class _BuildThread:
    """``knit.build(surface)`` started on a thread now; `result` (a `CoreJob`) waits for it
    and returns (the result, its seconds) or raises what the build raised."""

    def __init__(self, knit: Any, surface: Any) -> None:
        self._outcome: tuple[Any, float] | None = None
        self._error: BaseException | None = None
        self._thread = threading.Thread(target=self._run, args=(knit, surface), daemon=True)
        self._thread.start()

    def _run(self, knit: Any, surface: Any) -> None:
        t0 = time.perf_counter()
        try:
            self._outcome = (knit.build(surface), time.perf_counter() - t0)
        except BaseException as e:  # noqa: BLE001 - raised again by `result`
            self._error = e

    def result(self) -> tuple[Any, float]:
        self._thread.join()
        if self._error is not None:
            raise self._error
        assert self._outcome is not None
        return self._outcome


def _store(
    obj: bpy.types.Object, source: bpy.types.Object, settings: Mapping[str, Any], bound: Bound
) -> None:
    stored = obj.knitwear
    for name, value in settings.items():
        setattr(stored, name, value)
    stored.source = source
    stored.bound_counts = bound.counts
    stored.bound_yarn_radius = bound.yarn_radius
    stored.bound_stitch_size = bound.stitch_size
    stored.bound_samples = bound.samples
    _set_pinned(obj, LEVELS_PROPERTY, bound.levels)
    _set_pinned(obj, SEEN_PROPERTY, bound.seen)
    stored.is_knit = True


def _texture_where_needed(
    source: bpy.types.Object,
    context: bpy.types.Context,
    settings: Mapping[str, Any],
    result: Any,
) -> str | None:
    """Give ``source`` the knitwear texture when auto detail left stitches to it (about 8
    pixels per stitch, 256 to 4096 a side); return the material's name, or None."""
    if result.stats["levels"]["texture"] == 0:
        return None
    courses, wales = result.stats["courses"], result.stats["wales"]
    side = [int(min(4096, max(256, 8 * n))) for n in (wales, courses)]
    material = texture.texture_object(
        source, context=context, width=side[0], height=side[1], **settings
    )
    return material.name


def _outcome(
    obj: bpy.types.Object,
    result: Any,
    t_start: float,
    seconds: tuple[float, float, float],
    bound: Bound,
    texture_material: str | None,
) -> KnitOutcome:
    stats = result.stats
    skipped = int(stats.get("stitches_skipped", 0))
    stitches = int(stats.get("stitches", 0))
    return KnitOutcome(
        object=obj,
        stitches=stitches,
        triangles=len(result.triangles),
        skipped_stitches=skipped,
        lost_stitches=int(stats.get("stitches_lost", 0)),
        clamped_stitches=int(stats.get("stitches_clamped", 0)),
        flat_clearance=float(stats.get("flat_clearance", 0.0)),
        seconds=time.perf_counter() - t_start,
        sampling_seconds=seconds[0],
        core_seconds=seconds[1],
        hidden_pass_seconds=float(stats["hidden_pass_seconds"]),
        mesh_seconds=seconds[2],
        levels={name: int(stats["levels"][name]) for name in LEVEL_NAMES},
        triangles_full_detail=int(stats["triangles_full_detail"]),
        triangles_hidden=int(stats["triangles_hidden"]),
        hidden_pass=stats["hidden_pass"],
        auto_detail=bound.levels is not None,
        texture_material=texture_material,
        stitch_spread=stats.get("stitch_spread"),
        in_the_round=tuple(stats["in_the_round"]),
    )


def knit(
    source: bpy.types.Object,
    *,
    context: bpy.types.Context | None = None,
    progress: Progress | None = None,
    **settings: Any,
) -> KnitOutcome:
    """Knit ``source`` into a new object; return it with timings and counts.

    The new object, "<source>.knit", goes into the source's first collection with the source's
    location and rotation (its scale and shear are baked into the mesh, and a surface far
    from its origin moves the knit's origin to its centre: see `sampling`), carries the
    "Knitwear Yarn" material and remembers ``source`` and the settings for `update_knit`.
    """
    return run_steps(knit_steps(source, context=context, progress=progress, **settings))


def knit_steps(
    source: bpy.types.Object,
    *,
    context: bpy.types.Context | None = None,
    progress: Progress | None = None,
    **settings: Any,
) -> Generator[CoreJob, Any, KnitOutcome]:
    """`knit` as steps (see the module docstring): nothing is created before the core job
    has returned, so steps closed or failing there leave the scene as it was."""
    t_start = time.perf_counter()
    context = context or bpy.context
    settings = core_inputs.complete(settings)
    source = core_inputs.check_source(source, "the object")
    sampled, result, bound, (sampling_s, core_s) = yield from _core_steps(
        source, context, settings, progress
    )

    # Whatever fails from here on (the texture, last, leaves nothing of its own behind)
    # takes the knit's datablocks with it.
    with new_data.removed_on_failure():
        t_mesh = time.perf_counter()
        name = f"{source.name}.knit"
        mesh = mesh_build.new_mesh(name, result)
        mesh_s = time.perf_counter() - t_mesh
        material.assign(mesh)
        obj = bpy.data.objects.new(name, mesh)
        obj.matrix_world = sampled.matrix
        collection = source.users_collection[0] if source.users_collection else None
        (collection or context.scene.collection).objects.link(obj)
        _store(obj, source, settings, bound)
        source_link.link_source(obj)
        textured = _texture_where_needed(source, context, settings, result)
    # The knit follows its source from a frame handler that writes mesh data, which Blender
    # asks to do with the interface locked during renders.
    context.scene.render.use_lock_interface = True
    if progress:
        progress(1.0)
    return _outcome(obj, result, t_start, (sampling_s, core_s, mesh_s), bound, textured)


def knit_object(
    source: bpy.types.Object, *, context: bpy.types.Context | None = None, **settings: Any
) -> bpy.types.Object:
    """Knit ``source`` (a NURBS surface, or a mesh with a UV map) and return the knit object.

    ``settings`` are the knit settings by name (unnamed ones take their defaults), e.g.
    ``pattern="seed", gauge_stitches=22, color_mode="STRIPES"``. Raises `knitwear.KnitError`
    (for instance `knitwear.SurfaceError` for a mesh without UV map, `knitwear.BudgetError` for
    a stitch count that would not fit in memory); nothing is created then.
    """
    return knit(source, context=context, **settings).object


def knit_result(
    source: bpy.types.Object, *, context: bpy.types.Context | None = None, **settings: Any
) -> Any:
    """The core's `knitwear.KnitResult` for ``source`` and ``settings``, building nothing in
    Blender: for scripts that want the raw arrays (yarn centrelines per course, colours...).
    The arrays are in the space of the knit object `knit_object` would create."""
    context = context or bpy.context
    source = core_inputs.check_source(source, "the object")
    return run_steps(_core_steps(source, context, core_inputs.complete(settings), None))[1]


def bound_of(obj: bpy.types.Object) -> Bound:
    """The values knit object ``obj`` pinned when it was knitted or last updated."""
    stored = obj.knitwear
    return Bound(
        tuple(stored.bound_counts),
        stored.bound_yarn_radius,
        tuple(stored.bound_stitch_size),
        tuple(stored.bound_samples),
        unpack_pinned(obj.get(LEVELS_PROPERTY)),
        unpack_pinned(obj.get(SEEN_PROPERTY)),
    )


def bind(
    obj: bpy.types.Object,
    sampled: sampling.Sampled,
    scene: bpy.types.Scene,
) -> "knitwear.Knit":
    """A `knitwear.Knit` for knit object ``obj`` that rebuilds exactly its mesh from its
    source in any pose: the stored settings with counts, yarn radius and stitch size pinned
    to the values stored at knit time (see `follow`)."""
    settings = core_inputs.complete(settings_from(obj))
    bound = bound_of(obj)
    kwargs = core_inputs.core_settings(settings, scene)
    for key in ("gauge", "courses", "wales"):
        kwargs.pop(key, None)
    kwargs["courses"], kwargs["wales"] = bound.counts
    kwargs["yarn_radius"] = bound.yarn_radius
    kwargs["stitch_size"] = bound.stitch_size
    if bound.levels is not None:
        # The levels auto detail chose at knit time, whatever the camera does now.
        kwargs["stitch_levels"] = np.frombuffer(bound.levels, dtype=np.uint8)
    if bound.seen is not None:
        # And the yarn it saw.
        kwargs["seen_triangles"] = bound.seen
    return knitwear.Knit(sampled.surface, core_inputs.pattern_of(settings), **kwargs)


def sample_source(
    obj: bpy.types.Object, context: bpy.types.Context, depsgraph: bpy.types.Depsgraph
) -> sampling.Sampled:
    """Knit object ``obj``'s source as ``depsgraph`` evaluates it now, sampled as it was at
    knit time (same direction, same grid density)."""
    source = core_inputs.check_source(obj.knitwear.source, f"'{obj.name}'")
    samples = bound_of(obj).samples
    return sampling.sample_object(
        source,
        context,
        direction=obj.knitwear.direction,
        min_samples=samples if samples != (0, 0) else None,
        depsgraph=depsgraph,
    )


def update(
    obj: bpy.types.Object,
    *,
    context: bpy.types.Context | None = None,
    progress: Progress | None = None,
    **settings: Any,
) -> KnitOutcome:
    """Rebuild knit object ``obj`` in place from its source; ``settings`` override the stored
    ones (and are stored). Where only positions or colours change (a new seed, colours,
    fluffiness, a moved source) the mesh datablock is rewritten in place; otherwise a new one
    takes its place for every user, with its name and materials. The object follows its
    source's current location and rotation."""
    return run_steps(update_steps(obj, context=context, progress=progress, **settings))


def update_steps(
    obj: bpy.types.Object,
    *,
    context: bpy.types.Context | None = None,
    progress: Progress | None = None,
    **settings: Any,
) -> Generator[CoreJob, Any, KnitOutcome]:
    """`update` as steps (see the module docstring): ``obj`` is untouched until the core job
    has returned."""
    t_start = time.perf_counter()
    context = context or bpy.context
    if not obj.knitwear.is_knit:
        raise knitwear.ParameterError(f"'{obj.name}' is not a knit: knit a surface first")
    merged = core_inputs.complete(settings_from(obj) | dict(settings))
    source = core_inputs.check_source(obj.knitwear.source, f"'{obj.name}'")
    sampled, result, bound, (sampling_s, core_s) = yield from _core_steps(
        source, context, merged, progress
    )

    # What fails from here on puts the knit back as it was: its mesh (from a copy), matrix
    # and stored settings, and removes what the update created.
    before = (settings_from(obj), bound_of(obj), obj.matrix_world.copy(), obj.data.copy())
    with new_data.removed_on_failure():
        try:
            t_mesh = time.perf_counter()
            mesh = mesh_build.fill_mesh(obj.data, result)
            mesh_s = time.perf_counter() - t_mesh
            material.assign(mesh)
            obj.matrix_world = sampled.matrix
            _store(obj, source, merged, bound)
            source_link.link_source(obj)
            textured = _texture_where_needed(source, context, merged, result)
        except BaseException:
            _put_back(obj, source, *before)
            raise
    bpy.data.meshes.remove(before[3])
    if progress:
        progress(1.0)
    return _outcome(obj, result, t_start, (sampling_s, core_s, mesh_s), bound, textured)


def _put_back(
    obj: bpy.types.Object,
    source: bpy.types.Object,
    settings: Mapping[str, Any],
    bound: Bound,
    matrix: Any,
    mesh: bpy.types.Mesh,
) -> None:
    """Knit ``obj`` as it was before a failed update: ``mesh`` (a copy of its mesh then)
    takes the place of the one it has now, with its name."""
    live = obj.data
    name = live.name
    live.user_remap(mesh)
    bpy.data.meshes.remove(live)
    mesh.name = name
    obj.matrix_world = matrix
    _store(obj, source, settings, bound)


def update_knit(
    obj: bpy.types.Object, *, context: bpy.types.Context | None = None, **settings: Any
) -> bpy.types.Object:
    """Rebuild ``obj`` from its stored source and settings (``settings`` override and are
    stored). Raises `knitwear.KnitError` and leaves ``obj`` unchanged on failure."""
    return update(obj, context=context, **settings).object

