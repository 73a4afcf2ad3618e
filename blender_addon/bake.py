"""Baking a knit's animation into a point cache that plain Blender plays back.

A farm machine may not have the extension. Baking steps through the frame range, lets the knit
follow its source on each frame, and writes the positions to a PC2 file (Blender's Mesh Cache
modifier reads it natively); it then gives the knit a Mesh Cache modifier, keys the object's
transform where the source moved, and switches Follow Source off. The .blend then renders the
animation anywhere, extension or not.

PC2 layout (little-endian): b"POINTCACHE2\\0", int32 version 1, int32 points, float32 start
frame, float32 sample rate (1 = one sample per frame), int32 samples; then samples x points x 3
float32 positions in the object's space.
"""

import errno
import os
import struct
from pathlib import Path
from typing import BinaryIO

import bpy
import knitwear
import numpy as np

from . import api, follow, mesh_build

PC2_MAGIC = b"POINTCACHE2\0"
CACHE_MODIFIER = "Knitwear Baked Animation"


_HEADER = struct.Struct("<iiffi")  # version, points, start frame, sample rate, samples


def write_pc2_header(handle: BinaryIO, points: int, start: int, samples: int) -> None:
    handle.write(PC2_MAGIC + _HEADER.pack(1, points, float(start), 1.0, samples))


def read_pc2(path: Path) -> tuple[int, np.ndarray]:
    """(start frame, positions (samples, points, 3) float32) of a PC2 file."""
    data = path.read_bytes()
    if data[:12] != PC2_MAGIC:
        raise knitwear.ParameterError(f"{path} is not a PC2 point cache")
    _version, points, start, _rate, samples = _HEADER.unpack_from(data, len(PC2_MAGIC))
    offset = len(PC2_MAGIC) + _HEADER.size
    positions = np.frombuffer(data, dtype="<f4", offset=offset, count=samples * points * 3)
    return int(start), positions.reshape(samples, points, 3)


def _cache_path(obj: bpy.types.Object, filepath: str) -> tuple[str, Path]:
    """The path as stored in the modifier (may be blend-relative) and as a real file path."""
    stored = filepath or f"//{bpy.path.clean_name(obj.name)}.pc2"
    if stored.startswith("//") and not bpy.data.filepath:
        raise knitwear.ParameterError(
            "save the .blend first (the cache goes next to it), or give an absolute file path"
        )
    return stored, Path(bpy.path.abspath(stored))


def _partial_path(path: Path) -> Path:
    """The file beside ``path`` a bake writes and then moves over it, so that a failed bake
    leaves an earlier cache (and its modifier) as they were. Raises `OSError` where ``path``
    cannot be a file."""
    if path.is_dir():
        raise IsADirectoryError(errno.EISDIR, "it is a folder: give a file path", str(path))
    path.parent.mkdir(parents=True, exist_ok=True)
    return path.with_name(f".{path.name}.{os.getpid()}.partial")


def _write_error(path: Path, err: OSError) -> knitwear.KnitError:
    where = f" ('{err.filename}')" if err.filename and str(err.filename) != str(path) else ""
    return knitwear.ParameterError(
        f"cannot write the point cache '{path}': {err.strerror or err}{where}"
    )


def bake_animation(
    obj: bpy.types.Object,
    *,
    frame_start: int,
    frame_end: int,
    filepath: str = "",
    context: bpy.types.Context | None = None,
) -> Path:
    """Bake knit ``obj``'s animation for frames ``frame_start..=frame_end``; return the cache
    file. Raises `knitwear.KnitError` (nothing is changed then) if the knit cannot follow or
    the file cannot be written (a folder, a read-only place: the error names the path)."""
    context = context or bpy.context
    if not obj.knitwear.is_knit:
        raise knitwear.ParameterError(f"'{obj.name}' is not a knit: knit a surface first")
    if frame_end < frame_start:
        raise knitwear.ParameterError(f"empty frame range {frame_start}..{frame_end}")
    stored, path = _cache_path(obj, filepath)
    scene = context.scene
    mesh = obj.data
    n = len(mesh.vertices)
    frame_before = scene.frame_current
    # The knit's own positions (what it shows outside the baked range) stay as they were.
    rest = mesh_build.read_positions(mesh)
    rest_normals = mesh_build.read_normals(mesh)
    rest_tangents = mesh_build.read_tangents(mesh)
    matrix_before = obj.matrix_world.copy()
    following = obj.knitwear.follow_source
    # The handler would follow too on each frame_set: the bake follows once, itself.
    obj.knitwear.follow_source = False
    matrices = []
    partial: Path | None = None
    try:
        partial = _partial_path(path)
        with partial.open("wb") as handle:
            write_pc2_header(handle, n, frame_start, frame_end - frame_start + 1)
            for frame in range(frame_start, frame_end + 1):
                scene.frame_set(frame)
                follow.follow(obj, context=context, normals=False)  # the cache holds none
                positions = mesh_build.read_positions(mesh)
                handle.write(positions.astype("<f4", copy=False).tobytes())
                matrices.append(obj.matrix_world.copy())
        partial.replace(path)
    except BaseException as err:
        # Every way out but success leaves the scene, the knit and any earlier cache as they
        # were, and no partial file behind.
        if partial is not None:
            partial.unlink(missing_ok=True)
        scene.frame_set(frame_before)
        mesh_build.write_positions(mesh, rest)
        mesh_build.write_normals(mesh, rest_normals)
        mesh_build.write_tangents(mesh, rest_tangents)
        obj.matrix_world = matrix_before
        obj.knitwear.follow_source = following
        if isinstance(err, OSError):
            raise _write_error(path, err) from err
        raise

    previous = obj.modifiers.get(CACHE_MODIFIER)
    if previous is not None:
        obj.modifiers.remove(previous)
    modifier = obj.modifiers.new(CACHE_MODIFIER, "MESH_CACHE")
    modifier.cache_format = "PC2"
    modifier.filepath = stored
    modifier.frame_start = frame_start
    obj.modifiers.move(obj.modifiers.find(modifier.name), 0)  # before anything else
    if any(m != matrices[0] for m in matrices):
        for frame, matrix in zip(range(frame_start, frame_end + 1), matrices, strict=True):
            obj.matrix_world = matrix
            for path_name in ("location", "rotation_euler", "scale"):
                obj.keyframe_insert(path_name, frame=frame)
    mesh_build.write_positions(mesh, rest)
    # The cache moves the vertices and carries no normals: a knit that culls nothing shades
    # with the ones Blender computes from them, not with those of the frame it stood at.
    # (A culled knit keeps its own, which only the extension can move.) Nor does it carry
    # fibre directions: the rest pose's would point the highlight wrong as the yarn turns, so
    # a baked knit's is round (the material's anisotropy needs the attribute), culled or not.
    culled = obj.get(api.SEEN_PROPERTY) is not None
    mesh_build.write_normals(mesh, rest_normals if culled else None)
    mesh_build.write_tangents(mesh, None)
    scene.frame_set(frame_before)
    return path


class OBJECT_OT_knitwear_bake(bpy.types.Operator):
    """Bake the knit's animation into a point cache (Mesh Cache modifier) so the file renders
    on machines without the Knitwear extension"""

    bl_idname = "object.knitwear_bake"
    bl_label = "Bake Knit Animation"
    bl_options = {"REGISTER", "UNDO"}

    filepath: bpy.props.StringProperty(
        name="Cache File",
        description="Where the PC2 point cache goes (empty: next to the .blend, named after the "
        "knit)",
        subtype="FILE_PATH",
        default="",
    )

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        if obj is None or not obj.knitwear.is_knit:
            cls.poll_message_set("The active object is not a knit")
            return False
        return True

    def execute(self, context: bpy.types.Context) -> set[str]:
        scene = context.scene
        try:
            path = bake_animation(
                context.active_object,
                frame_start=scene.frame_start,
                frame_end=scene.frame_end,
                filepath=self.filepath,
                context=context,
            )
        except knitwear.KnitError as err:
            self.report({"ERROR"}, str(err))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Baked frames {scene.frame_start}-{scene.frame_end} to {path}")
        return {"FINISHED"}
