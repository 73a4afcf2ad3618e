"""Blender object -> core surface: reading buffers only, no geometry algorithms.

A SURFACE object becomes a `knitwear.GridSurface`: Blender tessellates the NURBS patch (with
its modifiers, through the depsgraph) on a grid we make dense enough for the stitch size, and
we reshape that grid. A MESH object (or a surface whose modifiers changed its topology)
becomes a `knitwear.MeshSurface` over its active render UV map. Everything is read with
`foreach_get` into preallocated NumPy arrays.

Frames. The core works in the space of the returned `Sampled.matrix`: the source's object
space with the object's scale baked into the coordinates, so that gauge, yarn radius and the
round yarn cross-section are all measured in world-sized scene units even on a scaled (or
non-uniformly scaled) object. The knit object takes `Sampled.matrix` (location and rotation)
and so lands exactly on the source.

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
from mathutils import Matrix

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
    #: Where the knit object goes (the source's location and rotation; scale is baked).
    matrix: Matrix
    #: "U" or "V": which of the source's directions the courses run along.
    courses_along: str
    #: Grid samples (u, v) in the core's frame, or None for a mesh surface.
    grid_shape: tuple[int, int] | None


def _float_array(n: int, width: int) -> np.ndarray:
    return np.empty((n, width), dtype=np.float32)


def _read_positions_normals(mesh: bpy.types.Mesh) -> tuple[np.ndarray, np.ndarray]:
    n = len(mesh.vertices)
    positions = _float_array(n, 3)
    normals = _float_array(n, 3)
    mesh.attributes["position"].data.foreach_get("vector", positions.ravel())
    mesh.vertex_normals.foreach_get("vector", normals.ravel())
    return positions, normals


def _bake_scale(
    obj: bpy.types.Object, positions: np.ndarray, normals: np.ndarray
) -> Matrix:
    """Apply the object's scale to the arrays in place; return the knit object's matrix."""
    loc, rot, scale = obj.matrix_world.decompose()
    s = np.array(scale, dtype=np.float32)
    if not np.allclose(s, 1.0, rtol=0.0, atol=1e-6):
        positions *= s
        # Normals transform with the inverse transpose; renormalised so the core gets unit
        # normals (a zero scale axis leaves nothing sensible: the core rejects a flat surface).
        with np.errstate(divide="ignore", invalid="ignore"):
            normals /= s
            normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    return Matrix.LocRotScale(loc, rot, None)


def _check_not_empty(obj: bpy.types.Object, mesh: bpy.types.Mesh | None) -> bpy.types.Mesh:
    if mesh is None or len(mesh.polygons) == 0:
        raise knitwear.SurfaceError(f"'{obj.name}' has no faces to knit on")
    return mesh


def _mesh_surface(
    obj: bpy.types.Object, mesh: bpy.types.Mesh, courses_along: str
) -> Sampled:
    _check_not_empty(obj, mesh)
    uv_layer = next((layer for layer in mesh.uv_layers if layer.active_render), None)
    if uv_layer is None:
        uv_layer = mesh.uv_layers.active
    if uv_layer is None:
        raise knitwear.SurfaceError(
            f"'{obj.name}' has no UV map: knitwear lays stitches out over the UV map. "
            "Unwrap it first (Edit Mode > UV > Unwrap), or knit a NURBS surface"
        )
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
    matrix = _bake_scale(obj, positions, normals)
    surface = knitwear.MeshSurface(positions, normals, triangles, uvs)
    return Sampled(surface, matrix, courses_along, None)


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
    matrix = _bake_scale(obj, positions, normals)
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
    return Sampled(surface, matrix, courses_along, (cols, rows))


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

