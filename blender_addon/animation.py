"""Whether an object moves or deforms over the scene's frame range.

Auto detail models a knit for one camera frame only where neither the camera nor its source
animates; for a source that animates it samples the source's pose at each camera frame it
follows, so that what the source shows later (to the levels and to the hidden-yarn pass) was
built. "Animates" is anything the depsgraph makes of it frame by frame, not only keys on the
object itself: keys and drivers on it, its data or its shape keys; a parent; an armature,
lattice, hook, curve or any other object a modifier or constraint reads (recursively);
time-driven modifiers (wave, physics, caches).
What no such rule can see (a Geometry Nodes tree reading the scene time) is caught by
evaluating the object at a few frames of the range and comparing.
"""

import bpy
import numpy as np

from . import blender_compat, frame_handlers

#: Modifiers that change the geometry with time by themselves.
TIME_MODIFIERS = frozenset(
    {
        "CLOTH",
        "DYNAMIC_PAINT",
        "EXPLODE",
        "FLUID",
        "MESH_CACHE",
        "MESH_SEQUENCE_CACHE",
        "OCEAN",
        "PARTICLE_SYSTEM",
        "SOFT_BODY",
        "WAVE",
    }
)

#: Frames of the range evaluated where the rules see nothing but a modifier might animate.
PROBE_FRAMES = 5


def _keyed(idb: bpy.types.ID | None) -> bool:
    anim = getattr(idb, "animation_data", None)
    return anim is not None and (anim.action is not None or len(anim.drivers) > 0)


def _referenced_objects(item: bpy.types.bpy_struct) -> list[bpy.types.Object]:
    """Objects a modifier or constraint points at (its target, armature, lattice...)."""
    found = []
    for prop in item.bl_rna.properties:
        if prop.type == "POINTER" and prop.identifier not in {"rna_type", "id_data"}:
            value = getattr(item, prop.identifier, None)
            if isinstance(value, bpy.types.Object):
                found.append(value)
    # The Armature constraint keeps its bones' armatures in a list of targets.
    for target in getattr(item, "targets", ()):
        if isinstance(getattr(target, "target", None), bpy.types.Object):
            found.append(target.target)
    # A Geometry Nodes modifier keeps its inputs (an Object socket among them) apart.
    if isinstance(item, bpy.types.NodesModifier):
        values = blender_compat.node_input_values(item)
        found += [value for value in values if isinstance(value, bpy.types.Object)]
    return found


def _driven(obj: bpy.types.Object, visiting: set[int]) -> bool:
    """Whether a rule says ``obj`` moves or deforms with time (see the module docstring)."""
    if obj.session_uid in visiting:
        return False  # a dependency circle: each object is judged once
    visiting.add(obj.session_uid)
    data = obj.data
    if _keyed(obj) or _keyed(data) or _keyed(getattr(data, "shape_keys", None)):
        return True
    if obj.parent is not None and _driven(obj.parent, visiting):
        return True
    for modifier in getattr(obj, "modifiers", ()):
        if not (modifier.show_viewport or modifier.show_render):
            continue
        if modifier.type in TIME_MODIFIERS:
            return True
        if any(_driven(other, visiting) for other in _referenced_objects(modifier)):
            return True
    for constraint in obj.constraints:
        if constraint.enabled and any(
            _driven(other, visiting) for other in _referenced_objects(constraint)
        ):
            return True
    return False


def _pose(obj: bpy.types.Object, depsgraph: bpy.types.Depsgraph) -> np.ndarray:
    """``obj``'s evaluated world matrix and vertex positions, flattened."""
    evaluated = obj.evaluated_get(depsgraph)
    matrix = np.array(evaluated.matrix_world, dtype=np.float32).ravel()
    mesh = evaluated.to_mesh()
    try:
        if mesh is None or len(mesh.vertices) == 0:
            return matrix
        positions = np.empty(3 * len(mesh.vertices), dtype=np.float32)
        mesh.attributes["position"].data.foreach_get("vector", positions)
        return np.concatenate([matrix, positions])
    finally:
        evaluated.to_mesh_clear()


def _changes_over_range(obj: bpy.types.Object, context: bpy.types.Context) -> bool:
    """Whether ``obj`` as evaluated differs anywhere among a few frames of the scene's
    range (the current frame is restored)."""
    scene = context.scene
    start, end = scene.frame_start, scene.frame_end
    if end <= start:
        return False
    frame, subframe = scene.frame_current, scene.frame_subframe
    frames = sorted({int(round(f)) for f in np.linspace(start, end, PROBE_FRAMES)} - {frame})
    with frame_handlers.paused():
        try:
            now = _pose(obj, context.evaluated_depsgraph_get())
            for f in frames:
                scene.frame_set(f)
                other = _pose(obj, context.evaluated_depsgraph_get())
                if other.shape != now.shape or not np.array_equal(other, now):
                    return True
        finally:
            if (scene.frame_current, scene.frame_subframe) != (frame, subframe):
                scene.frame_set(frame, subframe=subframe)
    return False


def animates(obj: bpy.types.Object | None, context: bpy.types.Context | None = None) -> bool:
    """Whether ``obj`` moves or deforms over time (see the module docstring). With
    ``context``, an object with modifiers or constraints the rules find still is also
    evaluated over the scene's frame range; without, only the rules apply."""
    if obj is None:
        return False
    if _driven(obj, set()):
        return True
    could_hide_time = len(getattr(obj, "modifiers", ())) > 0 or len(obj.constraints) > 0
    return context is not None and could_hide_time and _changes_over_range(obj, context)
