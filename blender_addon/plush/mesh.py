"""A plush's Blender mesh and material: the slices through the fast template route, their
per-corner UVs, the slice mask attribute, and the velvet material that shapes each slice by
alpha."""

from typing import Any

import bpy
import numpy as np

from .. import mesh_build

MATERIAL_NAME = "Knitwear Plush"
#: Point-domain float attribute: the core's per-vertex mask (0 round / horizontal slice,
#: 1 rectangular / vertical slice); the material mixes its alpha shapes by it.
MASK_ATTRIBUTE = "plush_mask"
UV_MAP = "UVMap"


def _set_uvs(mesh: bpy.types.Mesh, uvs: np.ndarray, triangles: np.ndarray) -> None:
    layer = mesh.uv_layers.get(UV_MAP) or mesh.uv_layers.new(name=UV_MAP)
    corner_uvs = np.ascontiguousarray(uvs[triangles.ravel()], dtype=np.float32)
    layer.uv.foreach_set("vector", corner_uvs.ravel())
    layer.active = True
    layer.active_render = True


def set_mask(mesh: bpy.types.Mesh, mask: np.ndarray) -> None:
    attribute = mesh.attributes.get(MASK_ATTRIBUTE)
    if attribute is None or attribute.data_type != "FLOAT" or attribute.domain != "POINT":
        if attribute is not None:
            mesh.attributes.remove(attribute)
        attribute = mesh.attributes.new(MASK_ATTRIBUTE, "FLOAT", "POINT")
    attribute.data.foreach_set("value", np.ascontiguousarray(mask, dtype=np.float32))


def _fill_extras(mesh: bpy.types.Mesh, result: Any) -> None:
    _set_uvs(mesh, result.uvs, result.triangles)
    set_mask(mesh, result.mask)
    mesh.update()


def new_plush_mesh(name: str, result: Any) -> bpy.types.Mesh:
    """A new mesh holding a `knitwear.PlushResult`: positions, triangles and edges through
    the fast route, the "Col" colours, the "UVMap" UVs (per corner) and "plush_mask"."""
    mesh = mesh_build.new_mesh(name, result)
    try:
        _fill_extras(mesh, result)
    except BaseException:
        bpy.data.meshes.remove(mesh)
        raise
    return mesh


def _build_material(material: bpy.types.Material) -> None:
    if material.node_tree is None:
        material.use_nodes = True  # Blender 4.x; 5.0 always has a tree
    tree = material.node_tree
    nodes, links = tree.nodes, tree.links
    nodes.clear()

    output = nodes.new("ShaderNodeOutputMaterial")
    output.location = (500, 0)
    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.location = (200, 0)
    color = nodes.new("ShaderNodeVertexColor")
    color.location = (-100, 200)
    color.layer_name = mesh_build.COLOR_ATTRIBUTE
    # Velvet: a rough dielectric whose fibre tips catch grazing light.
    inputs = bsdf.inputs
    inputs["Roughness"].default_value = 0.9
    inputs["Sheen Weight"].default_value = 1.0
    inputs["Sheen Roughness"].default_value = 0.3
    inputs["Specular IOR Level"].default_value = 0.2
    links.new(color.outputs["Color"], inputs["Base Color"])
    links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])

    # Alpha from the slice's UV: a round disc for horizontal slices (1 - smoothstep of the
    # distance from the centre, radius 0.5), a rectangle soft at its long sides for vertical
    # ones (u runs across the slice's width), mixed by the core's per-vertex mask.
    uv = nodes.new("ShaderNodeUVMap")
    uv.location = (-900, -200)
    uv.uv_map = UV_MAP
    distance = nodes.new("ShaderNodeVectorMath")
    distance.location = (-650, -150)
    distance.operation = "DISTANCE"
    distance.inputs[1].default_value = (0.5, 0.5, 0.0)
    links.new(uv.outputs["UV"], distance.inputs[0])
    disc = nodes.new("ShaderNodeMapRange")
    disc.location = (-400, -150)
    disc.interpolation_type = "SMOOTHSTEP"
    disc.inputs["From Min"].default_value = 0.3
    disc.inputs["From Max"].default_value = 0.5
    disc.inputs["To Min"].default_value = 1.0
    disc.inputs["To Max"].default_value = 0.0
    links.new(distance.outputs["Value"], disc.inputs["Value"])

    split = nodes.new("ShaderNodeSeparateXYZ")
    split.location = (-650, -400)
    links.new(uv.outputs["UV"], split.inputs[0])
    edges = []
    for i, (lo, hi) in enumerate(((0.0, 0.2), (1.0, 0.8))):
        ramp = nodes.new("ShaderNodeMapRange")
        ramp.location = (-400, -350 - 200 * i)
        ramp.interpolation_type = "SMOOTHSTEP"
        ramp.inputs["From Min"].default_value = lo
        ramp.inputs["From Max"].default_value = hi
        links.new(split.outputs["X"], ramp.inputs["Value"])
        edges.append(ramp)
    rect = nodes.new("ShaderNodeMath")
    rect.location = (-150, -400)
    rect.operation = "MINIMUM"
    links.new(edges[0].outputs["Result"], rect.inputs[0])
    links.new(edges[1].outputs["Result"], rect.inputs[1])

    mask = nodes.new("ShaderNodeAttribute")
    mask.location = (-400, 100)
    mask.attribute_type = "GEOMETRY"
    mask.attribute_name = MASK_ATTRIBUTE
    mix = nodes.new("ShaderNodeMix")
    mix.location = (0, -200)
    mix.data_type = "FLOAT"
    links.new(mask.outputs["Fac"], mix.inputs["Factor"])
    links.new(disc.outputs["Result"], mix.inputs[2])  # A (float)
    links.new(rect.outputs["Value"], mix.inputs[3])  # B (float)
    links.new(mix.outputs[0], inputs["Alpha"])

    # EEVEE (4.2+) shows alpha with dithered (order-independent) transparency; Cycles always
    # does. Workbench ignores node alpha and draws whole quads.
    if hasattr(material, "surface_render_method"):
        material.surface_render_method = "DITHERED"
    else:
        material.blend_method = "HASHED"
    material.use_backface_culling = False
    material.diffuse_color = (0.3, 0.02, 0.03, 1.0)
    material.roughness = 0.9


def plush_material() -> bpy.types.Material:
    """The shared plush material, created on first use and never overwritten afterwards."""
    material = bpy.data.materials.get(MATERIAL_NAME)
    if material is None:
        material = bpy.data.materials.new(MATERIAL_NAME)
        _build_material(material)
    return material
