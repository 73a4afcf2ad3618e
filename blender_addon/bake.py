"""Baking a knit's animation into a point cache that plain Blender plays back.

A farm machine may not have the extension. Baking steps through the frame range, lets the knit
follow its source on each frame, and writes the positions to a PC2 file (Blender's Mesh Cache
modifier reads it natively); it then gives the knit a Mesh Cache modifier, keys the object's
transform where the source moved, and switches Follow Source off. The .blend then renders the
animation anywhere, extension or not.

On each frame the bake also measures how close the yarn comes to other yarn (the core's
`Knit.clearance`, in yarn diameters): a body that bends squashes the rows with the skin, and
where the minimum falls under `api.MIN_CLEARANCE` loops pass visibly through each other. The
bake says in which frames (`Baked.summary`), so an animator knows where to look.

PC2 layout (little-endian): b"POINTCACHE2\\0", int32 version 1, int32 points, float32 start
frame, float32 sample rate (1 = one sample per frame), int32 samples; then samples x points x 3
float32 positions in the object's space.
"""

import errno
import os
import struct
from dataclasses import dataclass, field
from pathlib import Path
from typing import BinaryIO

import bpy
import knitwear
import numpy as np

from . import api, follow, frame_handlers, mesh_build

PC2_MAGIC = b"POINTCACHE2\0"
CACHE_MODIFIER = "Knitwear Baked Animation"


_HEADER = struct.Struct("<iiffi")  # version, points, start frame, sample rate, samples


@dataclass(frozen=True)
class FrameClearance:
    """The yarn's clearance in one baked frame, in yarn diameters (1: neighbouring yarns
    touch)."""

    frame: int
    min: float
    #: The 1st percentile.
    p01: float


@dataclass(frozen=True)
class Baked:
    """What `bake_animation` wrote and measured. A path-like object: scripts written when
    `bake_animation` returned the cache's `Path` can open it or pass it on as before."""

    #: The cache file.
    path: Path
    #: Each frame's clearance, in frame order; empty when not checked.
    clearance: list[FrameClearance] = field(default_factory=list)

    def __fspath__(self) -> str:
        return os.fspath(self.path)

    def passing_through(self) -> list[FrameClearance]:
        """The frames where yarn passes visibly through yarn (a minimum under
        `api.MIN_CLEARANCE`)."""
        return [c for c in self.clearance if c.min < api.MIN_CLEARANCE]

    def summary(self) -> str | None:
        """A warning naming the frames where yarn passes through yarn and the worst of them,
        or None."""
        bad = self.passing_through()
        if not bad:
            return None
        worst = min(bad, key=lambda c: (c.min, c.frame))
        down_to = (
            f"clearance down to {worst.min:.2f} yarn diameters at frame {worst.frame} (loops "
            f"overlap visibly under {api.MIN_CLEARANCE})"
        )
        if len(bad) == len(self.clearance):
            # Not the animation's doing, most likely: the knit collides in its own pose.
            return (
                f"yarn passes through yarn in every baked frame: {down_to}; where it does so "
                "in every pose, look at where its rows crowd (a sphere's poles) or at a yarn "
                "thick for its stitch, before the animation"
            )
        best = max(c.min for c in self.clearance if c not in bad)
        return (
            f"yarn passes through yarn in frame{'s' if len(bad) > 1 else ''} "
            f"{_frame_ranges([c.frame for c in bad])}: {down_to}, against {best:.2f} at best "
            "in the others; the surface squashes or folds the rows there"
        )


def _deformed(positions: np.ndarray, rest: np.ndarray) -> bool:
    """Whether the knit's own positions moved by more than a rigid motion's rounding (the
    source resampled in its turned object space): 1e-5 of the knit's size."""
    if positions.size == 0:
        return False
    size = float(np.ptp(rest, axis=0).max())
    return bool(np.abs(positions - rest).max() > 1e-5 * size)


def _frame_ranges(frames: list[int]) -> str:
    """``[1, 2, 3, 7]`` as ``"1-3, 7"``."""
    runs: list[list[int]] = []
    for f in frames:
        if runs and f == runs[-1][1] + 1:
            runs[-1][1] = f
        else:
            runs.append([f, f])
    return ", ".join(f"{a}-{b}" if b > a else f"{a}" for a, b in runs)


def write_pc2_header(handle: BinaryIO, points: int, start: int, samples: int) -> None:
    handle.write(PC2_MAGIC + _HEADER.pack(1, points, float(start), 1.0, samples))


def read_pc2(path: "str | os.PathLike[str]") -> tuple[int, np.ndarray]:
    """(start frame, positions (samples, points, 3) float32) of a PC2 file."""
    path = Path(path)
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
    check_clearance: bool = True,
) -> Baked:
    """Bake knit ``obj``'s animation for frames ``frame_start..=frame_end``; return the cache
    file and, with ``check_clearance``, each frame's clearance (at 11k stitches about 0.4 s a
    frame, against 0.24 s to follow and write it). Raises `knitwear.KnitError` (nothing is
    changed then) if the knit cannot follow or the file cannot be written (a folder, a
    read-only place: the error names the path)."""
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
    deforms = False
    clearance: list[FrameClearance] = []
    partial: Path | None = None
    try:
        partial = _partial_path(path)
        # Other knits need not follow each baked frame: the frame they show is put back.
        with partial.open("wb") as handle, frame_handlers.paused():
            write_pc2_header(handle, n, frame_start, frame_end - frame_start + 1)
            for frame in range(frame_start, frame_end + 1):
                scene.frame_set(frame)
                # The cache holds no normals.
                followed = follow.follow(obj, context=context, normals=False)
                if check_clearance:
                    least, p01 = followed.knit.clearance(followed.surface)
                    clearance.append(FrameClearance(frame, least, p01))
                positions = mesh_build.read_positions(mesh)
                deforms = deforms or _deformed(positions, rest)
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
    # with the ones Blender computes from them, not with those of the frame it stood at. A
    # culled knit keeps the whole knit's own where it only moves rigidly (the object's keys
    # turn them); where its source deforms they would stay in the rest pose, so it shades
    # with Blender's too (measured on a strip an armature tilts 45 degrees: within 0.99 SSIM
    # of the whole knit's bake, whose own are 0.87 from the live knit's). Nor does the cache
    # carry fibre directions: the rest pose's would point the highlight wrong as the yarn
    # turns, so a baked knit's is round (the material's anisotropy needs the attribute),
    # culled or not.
    culled = obj.get(api.SEEN_PROPERTY) is not None
    mesh_build.write_normals(mesh, rest_normals if culled and not deforms else None)
    mesh_build.write_tangents(mesh, None)
    scene.frame_set(frame_before)
    return Baked(path, clearance)


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

    check_clearance: bpy.props.BoolProperty(
        name="Check Clearance",
        description="Measure on every frame how close the yarn comes to other yarn, and warn "
        "in which frames it passes through (the bake takes two to three times as long)",
        default=True,
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
            baked = bake_animation(
                context.active_object,
                frame_start=scene.frame_start,
                frame_end=scene.frame_end,
                filepath=self.filepath,
                context=context,
                check_clearance=self.check_clearance,
            )
        except knitwear.KnitError as err:
            self.report({"ERROR"}, str(err))
            return {"CANCELLED"}
        done = f"Baked frames {scene.frame_start}-{scene.frame_end} to {baked.path}"
        warning = baked.summary()
        if warning is None:
            self.report({"INFO"}, done)
        else:
            self.report({"WARNING"}, f"{done}; {warning}")
        return {"FINISHED"}
