"""NumPy buffers -> Blender mesh, at close to memory speed.

The fast route writes the whole topology as attributes, with the edges the core already
computed (`KnitResult.edges`, `KnitResult.corner_edges`), so that `Mesh.update()` has no edges
to hash: about 0.03-0.06 s per million triangles against 0.4-0.8 s for the classic
`vertices/loops/polygons.foreach_set` route (see docs/design.md section 9.1). The attribute names it
uses (".corner_vert", ".edge_verts", ".corner_edge") are internal to Blender, so the classic
route remains as a fallback when they are missing or refuse the data.

Every array goes to `foreach_set` as a C-contiguous float32/int32 buffer: anything else makes
Blender convert element by element.
"""

import bpy
import numpy as np

from . import blender_compat

#: Name of the point-domain colour attribute holding the yarn colour (the material reads it).
COLOR_ATTRIBUTE = "Col"


def _f32(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.float32).ravel()


def _i32(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.int32).ravel()


#: Name prefix of the cached triangle templates (dot-prefixed: hidden in the UI). They have
#: no users, so they are never saved into the .blend.
TEMPLATE_PREFIX = ".knitwear triangles "
#: Templates kept at once: the latest knit's face count and one before it (a redo that changes
#: the ring segments or the stitch count, then changes them back).
MAX_TEMPLATES = 2
#: Custom property on a knit mesh: the core's topology key (hex) of the buffers it holds.
TOPOLOGY_PROPERTY = "knitwear_topology"


def _triangle_template(nf: int) -> bpy.types.Mesh:
    """A mesh of ``nf`` triangles with no vertices, its face offsets set.

    Setting face offsets from Python goes through RNA element by element (about 0.1 s per
    million faces, measured), the one slow step of building a mesh. A copy of a mesh shares
    its arrays until written (about 0.1 ms), so the offsets are paid once per face count and
    a redo, an update or a re-knit of the same size gets them for free.
    """
    name = f"{TEMPLATE_PREFIX}{nf}"
    template = bpy.data.meshes.get(name)
    if template is not None:
        if len(template.polygons) == nf and len(template.loops) == 3 * nf:
            return template
        bpy.data.meshes.remove(template)
    stale = [m for m in bpy.data.meshes if m.name.startswith(TEMPLATE_PREFIX) and m.users == 0]
    for old in stale[: max(0, len(stale) - (MAX_TEMPLATES - 1))]:
        bpy.data.meshes.remove(old)
    template = bpy.data.meshes.new(name)
    template.loops.add(3 * nf)
    template.polygons.add(nf)
    template.polygons.foreach_set("loop_start", np.arange(0, 3 * nf, 3, dtype=np.int32))
    return template


def ready_template(nf: int) -> None:
    """Make the triangle template for ``nf`` faces now, if it is not cached (see
    `_triangle_template`): a knit's steps call it while the core builds, so that the first
    mesh of a face count does not wait for it afterwards."""
    _triangle_template(nf)


def _fill_fast(name: str, result: object) -> bpy.types.Mesh:
    """A new mesh from a template copy, all topology written as attributes with the edges
    the core computed, so that `Mesh.update()` hashes nothing."""
    mesh = _triangle_template(len(result.triangles)).copy()
    try:
        mesh.name = name
        mesh.vertices.add(len(result.vertices))
        mesh.edges.add(len(result.edges))
        attributes = mesh.attributes
        attributes["position"].data.foreach_set("vector", _f32(result.vertices))
        attributes[".corner_vert"].data.foreach_set("value", _i32(result.triangles))
        attributes[".edge_verts"].data.foreach_set("value", _i32(result.edges))
        attributes[".corner_edge"].data.foreach_set("value", _i32(result.corner_edges))
        mesh.update()
    except BaseException:
        bpy.data.meshes.remove(mesh)
        raise
    return mesh


def _fill_classic(name: str, result: object) -> bpy.types.Mesh:
    mesh = bpy.data.meshes.new(name)
    try:
        nf = len(result.triangles)
        mesh.vertices.add(len(result.vertices))
        mesh.loops.add(3 * nf)
        mesh.polygons.add(nf)
        mesh.vertices.foreach_set("co", _f32(result.vertices))
        mesh.loops.foreach_set("vertex_index", _i32(result.triangles))
        mesh.polygons.foreach_set("loop_start", np.arange(0, 3 * nf, 3, dtype=np.int32))
        mesh.update(calc_edges=True)
    except BaseException:
        bpy.data.meshes.remove(mesh)
        raise
    return mesh


def _set_colors(mesh: bpy.types.Mesh, colors: np.ndarray) -> None:
    attribute = mesh.color_attributes.get(COLOR_ATTRIBUTE)
    if attribute is None or attribute.data_type != "FLOAT_COLOR" or attribute.domain != "POINT":
        if attribute is not None:
            mesh.color_attributes.remove(attribute)
        # FLOAT_COLOR fills at memory speed; BYTE_COLOR would convert per element (40x slower).
        attribute = mesh.color_attributes.new(COLOR_ATTRIBUTE, "FLOAT_COLOR", "POINT")
    attribute.data.foreach_set("color", _f32(colors))
    # Active for painting and the viewport, default for rendering (Workbench "Attribute",
    # and the Color Attribute node when it names no attribute).
    mesh.color_attributes.active_color = attribute
    mesh.attributes.default_color_name = attribute.name


#: Blender's free custom normals: a float vector per vertex that shading uses instead of the
#: normals the mesh's own triangles give.
NORMAL_ATTRIBUTE = "custom_normal"


def _read_vectors(mesh: bpy.types.Mesh, name: str) -> np.ndarray | None:
    """``mesh``'s point-domain float vector attribute ``name``, (V, 3) float32, or None."""
    attribute = mesh.attributes.get(name)
    if attribute is None or attribute.data_type != "FLOAT_VECTOR" or attribute.domain != "POINT":
        return None
    vectors = np.empty((len(mesh.vertices), 3), dtype=np.float32)
    attribute.data.foreach_get("vector", vectors.ravel())
    return vectors


def _write_vectors(mesh: bpy.types.Mesh, name: str, vectors: np.ndarray | None) -> None:
    """Set ``mesh``'s point-domain float vector attribute ``name`` to ``vectors`` (made if
    missing or of another kind), or remove it (``None``)."""
    attribute = mesh.attributes.get(name)
    if vectors is None:
        if attribute is not None:
            mesh.attributes.remove(attribute)
        return
    if attribute is None or attribute.data_type != "FLOAT_VECTOR" or attribute.domain != "POINT":
        if attribute is not None:
            mesh.attributes.remove(attribute)
        attribute = mesh.attributes.new(name, "FLOAT_VECTOR", "POINT")
    attribute.data.foreach_set("vector", _f32(vectors))


def read_normals(mesh: bpy.types.Mesh) -> np.ndarray | None:
    """``mesh``'s free custom normals, (V, 3) float32, or None where it has none."""
    return _read_vectors(mesh, NORMAL_ATTRIBUTE)


def shading_normals(result: object) -> np.ndarray | None:
    """The normals to shade ``result``'s mesh with: a knit's own (the swept tube's, so that
    its fibre triangles shade as soft yarn, not as facets) where Blender shades with them
    (4.5 and later); None for a plush, and on 4.2, which computes its own from the
    triangles."""
    if not blender_compat.FREE_CUSTOM_NORMALS:
        return None
    return getattr(result, "normals", None)


def write_normals(mesh: bpy.types.Mesh, normals: np.ndarray | None) -> None:
    """Give ``mesh`` the knit's own vertex normals as free custom normals (see
    `shading_normals`), or none (``None``: Blender computes them from the triangles)."""
    _write_vectors(mesh, NORMAL_ATTRIBUTE, normals)


#: The fibres' directions at each vertex (`KnitResult.tangents`): a float vector per vertex
#: that the yarn material reads as the tangent of its anisotropic highlight.
TANGENT_ATTRIBUTE = "yarn_tangent"


def read_tangents(mesh: bpy.types.Mesh) -> np.ndarray | None:
    """``mesh``'s fibre directions, (V, 3) float32, or None where it has none."""
    return _read_vectors(mesh, TANGENT_ATTRIBUTE)


def write_tangents(mesh: bpy.types.Mesh, tangents: np.ndarray | None) -> None:
    """Give ``mesh`` the knit's fibre directions (`TANGENT_ATTRIBUTE`), or none (``None``:
    the yarn material's highlight is then round, not drawn along the fibres)."""
    _write_vectors(mesh, TANGENT_ATTRIBUTE, tangents)


def _topology_key(result: object) -> str:
    return format(int(result.stats["topology_key"]), "016x")


def _same_topology(mesh: bpy.types.Mesh, result: object) -> bool:
    return (
        mesh.get(TOPOLOGY_PROPERTY) == _topology_key(result)
        and len(mesh.vertices) == len(result.vertices)
        and len(mesh.polygons) == len(result.triangles)
        and len(mesh.edges) == len(result.edges)
    )


def _build(name: str, result: object) -> bpy.types.Mesh:
    try:
        mesh = _fill_fast(name, result)
    except (KeyError, RuntimeError, TypeError, ValueError):
        # An internal attribute name changed or refused the data: the public API is slower
        # but stable.
        mesh = _fill_classic(name, result)
    try:
        _set_colors(mesh, result.colors)
        mesh.shade_smooth()
        write_normals(mesh, shading_normals(result))
        write_tangents(mesh, getattr(result, "tangents", None))
        mesh[TOPOLOGY_PROPERTY] = _topology_key(result)
    except BaseException:
        bpy.data.meshes.remove(mesh)
        raise
    return mesh


def read_positions(mesh: bpy.types.Mesh) -> np.ndarray:
    """``mesh``'s vertex positions, (V, 3) float32."""
    positions = np.empty((len(mesh.vertices), 3), dtype=np.float32)
    # A mesh without vertices has no "position" attribute at all (an empty knit: every
    # stitch left to the texture, or out of the camera's view).
    if len(positions):
        mesh.attributes["position"].data.foreach_get("vector", positions.ravel())
    return positions


def write_positions(mesh: bpy.types.Mesh, positions: np.ndarray) -> None:
    """Rewrite ``mesh``'s vertex positions (same count) in one `foreach_set`: the per-frame
    path of a knit that follows its source (about 1 ms per million vertices). Nothing to do
    for an empty mesh, which has no position attribute."""
    if len(mesh.vertices) == 0:
        return
    mesh.attributes["position"].data.foreach_set("vector", _f32(positions))
    mesh.update()


def fill_mesh(mesh: bpy.types.Mesh, result: object) -> bpy.types.Mesh:
    """Make ``mesh`` hold a `knitwear.KnitResult`; return the mesh that now does.

    Where the result has the topology ``mesh`` already holds (a new seed, colour, fluffiness or
    a deformed source: the core's topology key says so), only positions and colours are
    written, in place. Otherwise a new mesh is built and takes ``mesh``'s place everywhere
    (`ID.user_remap`), with its name and materials; ``mesh`` is removed. Either way every
    object that used ``mesh`` shows the result.
    """
    if _same_topology(mesh, result):
        _set_colors(mesh, result.colors)
        write_normals(mesh, shading_normals(result))
        write_tangents(mesh, getattr(result, "tangents", None))
        write_positions(mesh, result.vertices)
        return mesh
    name = mesh.name
    new = _build(name + ".new", result)
    for slot_material in mesh.materials:
        new.materials.append(slot_material)
    mesh.user_remap(new)
    bpy.data.meshes.remove(mesh)
    new.name = name
    return new


def new_mesh(name: str, result: object) -> bpy.types.Mesh:
    """A new mesh datablock holding a `knitwear.KnitResult`."""
    return _build(name, result)
