"""Knits that follow their animated sources, frame after frame.

Bind once, follow always: a knit object remembers the counts, yarn radius, stitch size and
sampling density it was knitted with (`api.Bound`), so its source in any later pose binds to a
`knitwear.Knit` that rebuilds exactly its topology. On every frame change the source is sampled
as the depsgraph evaluates it (armature, shape keys, modifiers), the core computes the new
vertex positions in parallel into a buffer kept per knit, and one `foreach_set` writes them:
vertex count, triangles, edges, colours and every random choice stay as they were, so nothing
flickers, and frame N rendered alone on a farm machine equals frame N reached in a sequence
(the positions are a function of the stored settings and the source at that frame only).

The frame handler never lets an error escape into a render: a knit that cannot follow (its
source was deleted, or changed its UV layout) is reported on the console and left in place.
"""

from dataclasses import dataclass
from typing import Any

import bpy
import knitwear
import numpy as np
from bpy.app.handlers import persistent

from . import api, blender_compat, frame_handlers, mesh_build


@dataclass
class _Follower:
    """A knit object's binding and the positions buffer its frames are computed into."""

    knit: "knitwear.Knit"
    #: What the binding was made from: a change rebinds.
    key: tuple[Any, ...]
    positions: np.ndarray
    normals: np.ndarray
    tangents: np.ndarray


@dataclass(frozen=True)
class Followed:
    """Where `follow` moved a knit: its binding, and its source's surface in that pose."""

    knit: "knitwear.Knit"
    surface: "knitwear.GridSurface | knitwear.MeshSurface"


#: Bindings by knit object (`ID.session_uid`), rebuilt on demand and dropped on file load.
_followers: dict[int, _Follower] = {}


def _key(obj: bpy.types.Object) -> tuple[Any, ...]:
    stored = obj.knitwear
    return (
        tuple(sorted(api.settings_from(obj).items())),
        api.bound_of(obj),
        stored.source.name if stored.source else None,
        obj.data.get(mesh_build.TOPOLOGY_PROPERTY),
        len(obj.data.vertices),
    )


def _follower(obj: bpy.types.Object, sampled: Any, scene: bpy.types.Scene) -> _Follower:
    key = _key(obj)
    follower = _followers.get(obj.session_uid)
    if follower is not None and follower.key == key:
        return follower
    knit = api.bind(obj, sampled, scene)
    if (
        format(knit.topology_key, "016x") != obj.data.get(mesh_build.TOPOLOGY_PROPERTY)
        or knit.vertex_count != len(obj.data.vertices)
    ):
        raise knitwear.SurfaceError(
            f"'{obj.name}' no longer matches its source's layout (its mesh was edited, or the "
            "source's UV map changed): use Update Knit"
        )
    shape = (knit.vertex_count, 3)
    follower = _Follower(
        knit,
        key,
        np.empty(shape, np.float32),
        np.empty(shape, np.float32),
        np.empty(shape, np.float32),
    )
    _followers[obj.session_uid] = follower
    return follower


def follow(
    obj: bpy.types.Object,
    *,
    context: bpy.types.Context | None = None,
    depsgraph: bpy.types.Depsgraph | None = None,
    normals: bool = True,
) -> Followed:
    """Move knit object ``obj``'s yarn to its source's pose in ``depsgraph`` (default: the
    context's): positions, and with ``normals`` the smooth normals (and, in a scene that
    renders with Cycles, the fibre directions) that go with them, into the same mesh. Returns
    the binding and the surface it followed to. Raises `knitwear.KnitError` when the knit
    cannot follow (then nothing is changed)."""
    context = context or bpy.context
    if not obj.knitwear.is_knit:
        raise knitwear.ParameterError(f"'{obj.name}' is not a knit: knit a surface first")
    depsgraph = depsgraph or context.evaluated_depsgraph_get()
    sampled = api.sample_source(obj, context, depsgraph)
    follower = _follower(obj, sampled, context.scene)
    culled = follower.knit.seen_triangles is not None
    # Culled hidden yarn shades with the whole knit's normals, which move with it. Any other
    # knit gets its normals too where Blender shades with them: computed by the core with the
    # positions, in the same pass, they spare Blender its own recompute on every draw.
    # The fibre directions turn with the yarn too, where the knit carries them and the scene
    # renders with Cycles: only its anisotropic highlight reads them (EEVEE and Workbench
    # do not), and they cost a third more per frame (10k stitches: about 35 ms).
    tangents = (
        normals
        and depsgraph.scene.render.engine == "CYCLES"
        and mesh_build.TANGENT_ATTRIBUTE in obj.data.attributes
    )
    normals = normals and (culled or blender_compat.FREE_CUSTOM_NORMALS)
    follower.knit.positions(
        sampled.surface,
        out=follower.positions,
        normals_out=follower.normals if normals else None,
        tangents_out=follower.tangents if tangents else None,
    )
    if normals:
        mesh_build.write_normals(obj.data, follower.normals)
    if tangents:
        mesh_build.write_tangents(obj.data, follower.tangents)
    mesh_build.write_positions(obj.data, follower.positions)
    if obj.matrix_world != sampled.matrix:
        obj.matrix_world = sampled.matrix
    return Followed(follower.knit, sampled.surface)


def followers(scene: bpy.types.Scene) -> list[bpy.types.Object]:
    """The knit objects of ``scene`` that follow their sources."""
    return [
        obj
        for obj in scene.objects
        if obj.type == "MESH" and obj.knitwear.is_knit and obj.knitwear.follow_source
    ]


_on_frame_change = frame_handlers.per_object(
    followers,
    lambda obj, depsgraph: follow(obj, depsgraph=depsgraph),
    "did not follow its source",
)


@persistent
def _on_load(*_args: object) -> None:
    _followers.clear()


_HANDLERS = (
    (bpy.app.handlers.frame_change_post, _on_frame_change),
    (bpy.app.handlers.load_post, _on_load),
)


def register() -> None:
    for handlers, handler in _HANDLERS:
        if handler not in handlers:
            handlers.append(handler)


def unregister() -> None:
    for handlers, handler in reversed(_HANDLERS):
        if handler in handlers:
            handlers.remove(handler)
    _followers.clear()
