"""Sources to knit and ways to compare Blender data before and after, for the add-on tests."""

from typing import Any

import bpy
import numpy as np
from mathutils import Vector

#: The add-on's module name once installed into the "user_default" extension repository.
ADDON_MODULE = "bl_ext.user_default.knitwear"

#: Small knits keep the suite fast: a few hundred stitches, coarse yarn.
SMALL: dict[str, Any] = {
    "size_mode": "COUNTS",
    "courses": 8,
    "wales": 10,
    "ring_segments": 4,
    "samples_per_loop": 8,
}

DATA_KINDS = ("objects", "meshes", "curves", "materials", "images", "shape_keys", "collections")


def nurbs_patch() -> bpy.types.Object:
    """Blender's NURBS Surface Patch: 4x4 points, a gently domed 1 m square."""
    bpy.ops.surface.primitive_nurbs_surface_surface_add()
    return bpy.context.active_object


def nurbs_sphere() -> bpy.types.Object:
    """Blender's NURBS Surface Sphere: closed in v, poles at the ends of u."""
    bpy.ops.surface.primitive_nurbs_surface_sphere_add(radius=0.5, location=(2.0, 0.0, 0.0))
    return bpy.context.active_object


def uv_mesh() -> bpy.types.Object:
    """A UV sphere, which comes with a UV map."""
    bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8, radius=0.5)
    return bpy.context.active_object


def mesh_without_uvs() -> bpy.types.Object:
    bpy.ops.mesh.primitive_plane_add(size=1.0)
    obj = bpy.context.active_object
    while obj.data.uv_layers:
        obj.data.uv_layers.remove(obj.data.uv_layers[0])
    obj.data.update()  # tag it, so the depsgraph re-evaluates it
    return obj


SOURCES = {"nurbs_patch": nurbs_patch, "nurbs_sphere": nurbs_sphere, "uv_mesh": uv_mesh}


def data_counts() -> dict[str, int]:
    """Datablocks a user sees, by kind. Dot-prefixed names are Blender's hidden data (the
    add-on's cached triangle templates: unused, never saved)."""
    return {
        kind: sum(not d.name.startswith(".") for d in getattr(bpy.data, kind))
        for kind in DATA_KINDS
    }


def _array(collection: bpy.types.bpy_prop_collection, attr: str, width: int) -> np.ndarray:
    out = np.empty(len(collection) * width, dtype=np.float32)
    collection.foreach_get(attr, out)
    return out


def snapshot(obj: bpy.types.Object) -> dict[str, Any]:
    """Everything about a source object that knitting must not change."""
    state: dict[str, Any] = {
        "name": obj.name,
        "data": obj.data.name,
        "users": obj.data.users,
        "matrix": [tuple(row) for row in obj.matrix_world],
        "modifiers": [(m.name, m.type, m.show_viewport) for m in obj.modifiers],
        "hidden": (obj.hide_get(), obj.hide_viewport, obj.hide_render),
        "collections": [c.name for c in obj.users_collection],
    }
    if obj.type == "SURFACE":
        state["splines"] = [
            (
                s.point_count_u,
                s.point_count_v,
                s.resolution_u,
                s.resolution_v,
                s.use_cyclic_u,
                s.use_cyclic_v,
                s.order_u,
                s.order_v,
                _array(s.points, "co", 4).tobytes(),
            )
            for s in obj.data.splines
        ]
        state["curve_resolution"] = (obj.data.resolution_u, obj.data.resolution_v)
    else:
        mesh = obj.data
        state["positions"] = _array(mesh.vertices, "co", 3).tobytes()
        state["counts"] = (len(mesh.vertices), len(mesh.edges), len(mesh.polygons))
        state["uv_maps"] = [
            (uv.name, _array(uv.uv, "vector", 2).tobytes()) for uv in mesh.uv_layers
        ]
    return state


def positions(mesh: bpy.types.Mesh) -> np.ndarray:
    return _array(mesh.vertices, "co", 3).reshape(-1, 3)


def corner_verts(mesh: bpy.types.Mesh) -> np.ndarray:
    out = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.loops.foreach_get("vertex_index", out)
    return out


def colors(mesh: bpy.types.Mesh, name: str = "Col") -> np.ndarray:
    attribute = mesh.color_attributes[name]
    return _array(attribute.data, "color", 4).reshape(-1, 4)


# Camera-driven detail: a strip receding from a low camera.

#: A 10 x 60 cm strip at about the default gauge: 20 wales x 160 courses.
STRIP = {"size_mode": "COUNTS", "courses": 160, "wales": 20}


def strip() -> bpy.types.Object:
    """A UV-mapped plane scaled to a 10 x 60 cm strip along y, centred on the origin."""
    bpy.ops.mesh.primitive_plane_add(size=1.0)
    obj = bpy.context.active_object
    obj.scale = (0.1, 0.6, 1.0)
    bpy.context.view_layer.update()
    return obj


def camera(location: tuple, target: tuple) -> bpy.types.Object:
    """The scene camera (a 20 mm lens) at ``location`` looking at ``target``, rendering
    1920 x 1080."""
    data = bpy.data.cameras.new("Camera")
    data.lens = 20.0
    cam = bpy.data.objects.new("Camera", data)
    bpy.context.scene.collection.objects.link(cam)
    aim(cam, location, target)
    scene = bpy.context.scene
    scene.camera = cam
    scene.render.resolution_x, scene.render.resolution_y = 1920, 1080
    scene.render.resolution_percentage = 100
    return cam


def aim(cam: bpy.types.Object, location: tuple, target: tuple) -> None:
    cam.location = location
    cam.rotation_euler = (Vector(target) - Vector(location)).to_track_quat("-Z", "Y").to_euler()
    bpy.context.view_layer.update()


def receding_camera() -> bpy.types.Object:
    """Low over the strip's near end, looking along it."""
    return camera((0.0, -0.38, 0.06), (0.0, -0.05, 0.0))
