"""Blender object -> core surface: reading buffers only, no geometry algorithms.

A SURFACE object becomes a `knitwear.GridSurface`: Blender tessellates the NURBS patch (with
its modifiers, through the depsgraph) on a grid we make dense enough for the stitch size, and
we reshape that grid. A MESH object (or a surface whose modifiers changed its topology)
becomes a `knitwear.MeshSurface` over its active render UV map. Everything is read with
`foreach_get` into preallocated NumPy arrays.

Frames. The core works in the space of the returned `Sampled.matrix`: the source's object
space with the whole linear part of its world transform (scale, and the shear a rotated child
of a non-uniformly scaled parent gets) baked into the coordinates, so that gauge, yarn radius
and the round yarn cross-section are all measured in world-sized scene units. The knit object
takes `Sampled.matrix` (location and rotation) and so lands exactly on the source. A zero
scale is a flat surface (normals come from the cofactor matrix, which stays finite), and a
surface far from its origin is sampled about its own centre (`FAR_FROM_ORIGIN`).

Directions. The core lays courses along its u and wales along its v. ``direction`` picks which
of the surface's own directions is the core's u; "AUTO" knits in the round (courses around the
closed direction) on a surface closed in exactly one direction, else along U.
"""

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

import bpy
import knitwear
import numpy as np
from mathutils import Matrix, Quaternion, Vector

#: Grid samples per stitch along each direction. The core interpolates the grid bilinearly;
#: for a surface whose curvature radius is at least a stitch wide, four samples per stitch keep
#: the chord error (h^2 / 8R) below a tenth of a typical yarn radius.
SAMPLES_PER_STITCH = 4
#: Blender's limit on a spline's resolution.
MAX_RESOLUTION = 1024
#: Cap on the evaluated grid (vertices). Tessellation costs about 0.25 s per million samples;
#: 4M samples is 2000 per side, full density for 500 x 500 stitches; beyond that the samples
#: per stitch drop gracefully (the grid is still far finer than Blender's default).
MAX_GRID_SAMPLES = 4_000_000


@dataclass(frozen=True)
class Sampled:
    """A source surface ready for `knitwear.knit`."""

    surface: "knitwear.GridSurface | knitwear.MeshSurface"
    #: Where the knit object goes: the source's location and rotation (scale and shear are
    #: baked into the coordinates), moved to `origin`.
    matrix: Matrix
    #: "U" or "V": which of the source's directions the courses run along.
    courses_along: str
    #: Grid samples (u, v) in the core's frame, or None for a mesh surface.
    grid_shape: tuple[int, int] | None
    #: The point of the source's (scaled, unrotated) frame the coordinates are relative to:
    #: the origin, or the surface's centre where it lies far from the origin (see
    #: `knit_matrix`).
    origin: tuple[float, float, float] = (0.0, 0.0, 0.0)


def _float_array(n: int, width: int) -> np.ndarray:
    return np.empty((n, width), dtype=np.float32)


def _read_positions_normals(mesh: bpy.types.Mesh) -> tuple[np.ndarray, np.ndarray]:
    n = len(mesh.vertices)
    positions = _float_array(n, 3)
    normals = _float_array(n, 3)
    mesh.attributes["position"].data.foreach_get("vector", positions.ravel())
    mesh.vertex_normals.foreach_get("vector", normals.ravel())
    return positions, normals


#: A surface whose centre lies more than this many times its size from its object's origin
#: is knitted about its own centre: float32 coordinates far from their origin keep too few
#: bits for the yarn (10 km out, 1 mm steps).
FAR_FROM_ORIGIN = 16.0


def _flat_rotation(m3: Matrix) -> Quaternion | None:
    """The rotation of a linear map with exactly one axis scaled to zero, whose own
    decomposition is undefined (it normalises a zero column): the other two axes and their
    cross product. None where no axis, or more than one, is zero."""
    lengths = [m3.col[i].length for i in range(3)]
    zero = [i for i in range(3) if lengths[i] <= 1e-12 * max(lengths)]
    if len(zero) != 1:
        return None
    k = zero[0]
    axes = [m3.col[i].normalized() for i in range(3)]
    axes[k] = axes[(k + 1) % 3].cross(axes[(k + 2) % 3]).normalized()
    return Matrix((axes[0], axes[1], axes[2])).transposed().to_quaternion()


def knit_frame(matrix_world: Matrix) -> tuple[Matrix, np.ndarray]:
    """The frame a knit of an object with ``matrix_world`` lives in, and the linear map into
    it: (the object's location and rotation, the 3x3 float64 ``L`` taking the object's
    coordinates into that frame).

    ``L`` is the rotation's inverse times the whole linear part of ``matrix_world``, so that
    ``frame @ (L @ p) == matrix_world @ p`` for any transform, a shear from a non-uniformly
    scaled parent included (a scale-only decomposition would misplace it). Without shear
    ``L`` is exactly the object's scale on the diagonal, and the identity for a scale within
    1e-6 of 1: a rotation alone must not perturb the coordinates by its rounding, or a knit
    whose source turns would jitter from frame to frame.
    """
    loc, rot, scale = matrix_world.decompose()
    m3 = matrix_world.to_3x3()
    flat = _flat_rotation(m3)
    if flat is not None:
        rot = flat
        scale = Vector([m3.col[i].length for i in range(3)])
    rotation = np.array(rot.to_matrix(), dtype=np.float64)
    linear = rotation.T @ np.array(m3, dtype=np.float64)
    off_diagonal = linear - np.diag(np.diag(linear))
    if np.abs(off_diagonal).max() <= 1e-6 * max(float(np.abs(linear).max()), 1e-30):
        s = np.array(scale, dtype=np.float64)
        s[np.abs(s - 1.0) <= 1e-6] = 1.0
        linear = np.diag(s)
    return Matrix.LocRotScale(loc, rot, None), linear


def knit_matrix(matrix_world: Matrix, origin: tuple[float, float, float]) -> Matrix:
    """The knit object's matrix for a source with ``matrix_world`` sampled about ``origin``
    (`Sampled.origin`, in the knit frame)."""
    frame, _linear = knit_frame(matrix_world)
    return frame @ Matrix.Translation(origin)


def _normal_matrix(linear: np.ndarray) -> np.ndarray:
    """The matrix normals transform with under ``linear``: its cofactor matrix (the inverse
    transpose times the determinant), made orientation-preserving, U diag(s1 s2, s0 s2,
    s0 s1) V^T from the SVD. Unlike the inverse it stays finite where an axis is scaled to
    zero: a flattened object's normals keep pointing out of its plane instead of 0/0."""
    if not (linear - np.diag(np.diag(linear))).any():
        s = np.abs(np.diag(linear))
        # A mirrored axis flips its own component only (and a zero one none).
        sign = np.where(np.diag(linear) < 0, -1.0, 1.0)
        return np.diag(sign * np.array([s[1] * s[2], s[0] * s[2], s[0] * s[1]]))
    u, s, vt = np.linalg.svd(linear)
    return (u * np.array([s[1] * s[2], s[0] * s[2], s[0] * s[1]])) @ vt


def _to_knit_frame(
    obj: bpy.types.Object, positions: np.ndarray, normals: np.ndarray
) -> tuple[np.ndarray, np.ndarray, Matrix, tuple[float, float, float]]:
    """``obj``'s coordinates and normals in its knit's frame (float32, ready for the core),
    the knit object's matrix and the origin the coordinates are relative to.

    The object's scale and any shear are applied to the arrays (see `knit_frame`), so gauge
    and yarn radius are measured in world-sized scene units. Positions are computed in
    float64 and, for a surface far from its object's origin (`FAR_FROM_ORIGIN`), taken
    about the centre of its bounding box, which the knit object's matrix moves back.
    """
    frame, linear = knit_frame(obj.matrix_world)
    s = np.linalg.svd(linear, compute_uv=False)
    if s[1] <= 1e-12 * max(float(s[0]), 1e-30):
        raise knitwear.SurfaceError(
            f"'{obj.name}' is scaled to zero along two axes (scale "
            f"{tuple(round(x, 6) for x in obj.matrix_world.to_scale())}): it has no area to "
            "knit on"
        )
    identity = not (linear - np.eye(3)).any()
    world = positions if identity else positions.astype(np.float64) @ linear.T
    origin = (0.0, 0.0, 0.0)
    if len(world):
        low, high = world.min(axis=0).astype(np.float64), world.max(axis=0).astype(np.float64)
        centre = 0.5 * (low + high)
        if np.abs(centre).max() > FAR_FROM_ORIGIN * max(float((high - low).max()), 1e-30):
            # Snapped to float32 (what Blender's matrices hold) so that an object without
            # rotation lands exactly where its data was.
            snapped = centre.astype(np.float32).astype(np.float64)
            world = world.astype(np.float64) - snapped
            origin = (float(snapped[0]), float(snapped[1]), float(snapped[2]))
    if not identity:
        normals = normals.astype(np.float64) @ _normal_matrix(linear).T
        length = np.linalg.norm(normals, axis=1, keepdims=True)
        # A face seen edge-on after a zero scale has no normal: zero, as at a pole, which
        # the core fills in from its neighbours.
        normals = np.divide(normals, length, out=np.zeros_like(normals), where=length > 0)
    matrix = frame @ Matrix.Translation(origin)
    return (
        np.ascontiguousarray(world, dtype=np.float32),
        np.ascontiguousarray(normals, dtype=np.float32),
        matrix,
        origin,
    )


def _check_not_empty(obj: bpy.types.Object, mesh: bpy.types.Mesh | None) -> bpy.types.Mesh:
    if mesh is None or len(mesh.polygons) == 0:
        raise knitwear.SurfaceError(f"'{obj.name}' has no faces to knit on")
    return mesh


def _no_uv_map(obj: bpy.types.Object) -> knitwear.SurfaceError:
    return knitwear.SurfaceError(
        f"'{obj.name}' has no UV map: knitwear lays stitches out over the UV map. "
        "Unwrap it first (Edit Mode > UV > Unwrap), or knit a NURBS surface"
    )


def _check_has_uv_map(obj: bpy.types.Object) -> None:
    """Refuse a mesh whose own data has no UV map. Its evaluated copy may still have the one
    a script removed without tagging the mesh (`uv_layers.remove` does not), and would be
    knitted over a map the user no longer sees. Only a Geometry Nodes modifier can make a
    UV map out of nothing: with one, the evaluated mesh decides."""
    if len(obj.data.uv_layers) == 0 and not any(m.type == "NODES" for m in obj.modifiers):
        raise _no_uv_map(obj)


def _mesh_surface(
    obj: bpy.types.Object, mesh: bpy.types.Mesh, courses_along: str
) -> Sampled:
    _check_not_empty(obj, mesh)
    uv_layer = next((layer for layer in mesh.uv_layers if layer.active_render), None)
    if uv_layer is None:
        uv_layer = mesh.uv_layers.active
    if uv_layer is None:
        raise _no_uv_map(obj)
    positions, normals = _read_positions_normals(mesh)
    mesh.calc_loop_triangles()
    nt = len(mesh.loop_triangles)
    triangles = np.empty((nt, 3), dtype=np.int32)
    tri_loops = np.empty(nt * 3, dtype=np.int32)
    mesh.loop_triangles.foreach_get("vertices", triangles.ravel())
    mesh.loop_triangles.foreach_get("loops", tri_loops)
    corner_uvs = _float_array(len(mesh.loops), 2)
    uv_layer.uv.foreach_get("vector", corner_uvs.ravel())
    uvs = corner_uvs[tri_loops].reshape(nt, 3, 2)  # the core takes (T, 3, 2)
    if courses_along == "V":
        uvs = np.ascontiguousarray(uvs[..., ::-1])
    positions, normals, matrix, origin = _to_knit_frame(obj, positions, normals)
    surface = knitwear.MeshSurface(positions, normals, triangles, uvs)
    return Sampled(surface, matrix, courses_along, None, origin)


def _surface_spline(obj: bpy.types.Object) -> bpy.types.Spline:
    splines = obj.data.splines
    if len(splines) != 1:
        raise knitwear.SurfaceError(
            f"'{obj.name}' has {len(splines)} surface patches; knitwear knits one patch at a "
            "time: separate them (Edit Mode > Separate) and knit each"
        )
    return splines[0]


def _resolve_direction(direction: str, cyclic_u: bool, cyclic_v: bool) -> str:
    if direction != "AUTO":
        return direction
    # Knitting in the round: the courses go round the closed direction.
    return "V" if cyclic_v and not cyclic_u else "U"


def _grid_resolution(
    spline: bpy.types.Spline, min_samples: tuple[int, int] | None
) -> tuple[int, int]:
    """Spline resolution (u, v) giving at least ``min_samples`` grid samples, capped."""
    res = [spline.resolution_u, spline.resolution_v]
    if min_samples is None:
        return res[0], res[1]
    points = (spline.point_count_u, spline.point_count_v)
    want = [max(r, -(-m // p)) for r, m, p in zip(res, min_samples, points, strict=True)]
    total = want[0] * points[0] * want[1] * points[1]
    if total > MAX_GRID_SAMPLES:
        shrink = (MAX_GRID_SAMPLES / total) ** 0.5
        want = [max(r, int(w * shrink)) for r, w in zip(res, want, strict=True)]
    return min(want[0], MAX_RESOLUTION), min(want[1], MAX_RESOLUTION)


@contextmanager
def _dense_copy(
    obj: bpy.types.Object, context: bpy.types.Context, resolution: tuple[int, int]
) -> Iterator[bpy.types.Object]:
    """A temporary copy of a surface object and its data at a higher resolution.

    The source is never touched (no undo step, no depsgraph tag on it). The copy is linked to
    the scene's master collection, which no view layer can exclude, so the depsgraph
    evaluates it with its modifiers; copy and data are removed however the block exits.
    """
    data = obj.data.copy()
    tmp = obj.copy()
    tmp.data = data
    tmp.hide_viewport = False
    for spline in data.splines:
        spline.resolution_u, spline.resolution_v = resolution
    context.scene.collection.objects.link(tmp)
    try:
        yield tmp
    finally:
        bpy.data.objects.remove(tmp)
        bpy.data.curves.remove(data)


def _grid_from_mesh(
    obj: bpy.types.Object,
    mesh: bpy.types.Mesh,
    spline: bpy.types.Spline,
    resolution: tuple[int, int],
    courses_along: str,
) -> Sampled | None:
    """The evaluated surface as a grid, or None when modifiers changed its topology."""
    nu = resolution[0] * spline.point_count_u
    nv = resolution[1] * spline.point_count_v
    if len(mesh.vertices) != nu * nv:
        return None
    positions, normals = _read_positions_normals(mesh)
    positions, normals, matrix, origin = _to_knit_frame(obj, positions, normals)
    # Blender tessellates u-major: vertex (iu, iv) is iu * nv + iv, and the closed direction
    # does not repeat its seam. The core wants positions[i, j] = s(u_j, v_i) with j along the
    # courses, i.e. rows along the wales.
    grid_p = positions.reshape(nu, nv, 3)
    grid_n = normals.reshape(nu, nv, 3)
    cyclic_u, cyclic_v = spline.use_cyclic_u, spline.use_cyclic_v
    if courses_along == "U":
        grid_p, grid_n = grid_p.transpose(1, 0, 2), grid_n.transpose(1, 0, 2)
    else:
        cyclic_u, cyclic_v = cyclic_v, cyclic_u
    grid_p = np.ascontiguousarray(grid_p)
    grid_n = np.ascontiguousarray(grid_n)
    surface = knitwear.GridSurface(grid_p, grid_n, cyclic_u=cyclic_u, cyclic_v=cyclic_v)
    rows, cols = grid_p.shape[:2]
    return Sampled(surface, matrix, courses_along, (cols, rows), origin)


def sample_object(
    obj: bpy.types.Object,
    context: bpy.types.Context,
    *,
    direction: str = "AUTO",
    min_samples: tuple[int, int] | None = None,
    depsgraph: bpy.types.Depsgraph | None = None,
) -> Sampled:
    """Sample ``obj`` as evaluated in ``context``'s view layer (modifiers, shape keys...), or
    in ``depsgraph`` where given (a frame-change handler's, which may be a render's).

    ``min_samples`` asks for at least that many grid samples along the courses and along the
    wales (NURBS surfaces only; a mesh is used as it is). ``direction`` is "AUTO", "U" or "V"
    (see the module docstring). Raises `knitwear.SurfaceError` for anything that cannot be
    knitted. Leaves ``bpy.data`` as it found it.
    """
    if obj.type == "MESH":
        _check_has_uv_map(obj)
        courses_along = _resolve_direction(direction, False, False)
        evaluated = obj.evaluated_get(depsgraph or context.evaluated_depsgraph_get())
        mesh = evaluated.to_mesh()
        try:
            # The evaluated object carries this frame's transform, also in a render's depsgraph.
            return _mesh_surface(evaluated, mesh, courses_along)
        finally:
            evaluated.to_mesh_clear()
    if obj.type != "SURFACE":
        raise knitwear.SurfaceError(
            f"'{obj.name}' is a {obj.type.lower()}: knitwear knits NURBS surfaces and meshes "
            "with a UV map"
        )
    spline = _surface_spline(obj)
    courses_along = _resolve_direction(direction, spline.use_cyclic_u, spline.use_cyclic_v)
    if min_samples is not None and courses_along == "V":
        min_samples = (min_samples[1], min_samples[0])
    resolution = _grid_resolution(spline, min_samples)
    with _dense_copy(obj, context, resolution) as tmp:
        evaluated = tmp.evaluated_get(context.evaluated_depsgraph_get())
        mesh = _check_not_empty(obj, evaluated.to_mesh())
        try:
            sampled = _grid_from_mesh(obj, mesh, tmp.data.splines[0], resolution, courses_along)
            if sampled is None:
                # A modifier changed the topology (subdivision, solidify...): the grid is gone
                # but the evaluated mesh keeps the surface's UV map, so knit over that.
                sampled = _mesh_surface(obj, mesh, courses_along)
        finally:
            evaluated.to_mesh_clear()
    return sampled


def image_pixels(image: bpy.types.Image) -> np.ndarray:
    """An image's pixels as linear RGBA float32, shape (height, width, 4), bottom row first.

    Byte images in the sRGB colour space are linearised (the core mixes colours linearly);
    float images are already scene-linear.
    """
    # Reading the size loads the image (file, packed or generated); no pixels means the file
    # is missing.
    width, height = image.size
    channels = image.channels
    if width * height * channels == 0:
        raise knitwear.ParameterError(f"image '{image.name}' has no pixels (missing file?)")
    flat = np.empty(width * height * channels, dtype=np.float32)
    image.pixels.foreach_get(flat)
    pixels = flat.reshape(height, width, channels)
    rgba = np.ones((height, width, 4), dtype=np.float32)
    if channels >= 3:
        rgba[..., :3] = pixels[..., :3]
    else:
        rgba[..., :3] = pixels[..., :1]
    if channels in (2, 4):
        rgba[..., 3] = pixels[..., -1]
    if not image.is_float and image.colorspace_settings.name == "sRGB":
        rgb = rgba[..., :3]
        rgba[..., :3] = np.where(
            rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4
        )
    return rgba

