"""The yarn material: the knit's vertex colours through a cloth-like Principled BSDF.

One material, "Knitwear Yarn", shared by every knit and reused if it exists, so that a user's
edits to it survive new knits and updates. Colours live on the mesh (the "Col" attribute),
not in the material, which is why one material serves every palette.
"""

import bpy

from .mesh_build import COLOR_ATTRIBUTE, TANGENT_ATTRIBUTE

MATERIAL_NAME = "Knitwear Yarn"

#: How much the highlight stretches across the fibres (the Principled BSDF's Anisotropic,
#: with the fibres' direction as its tangent): fibres are thin cylinders, whose highlight
#: is a band across them.
FIBRE_ANISOTROPY = 0.8


def _build(material: bpy.types.Material) -> None:
    if material.node_tree is None:
        # Blender 4.x creates materials without nodes; 5.0 always has a tree (and deprecates
        # `use_nodes`), so only switch it on where it is needed.
        material.use_nodes = True
    nodes = material.node_tree.nodes
    links = material.node_tree.links
    nodes.clear()

    output = nodes.new("ShaderNodeOutputMaterial")
    output.location = (300, 0)
    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.location = (0, 0)
    color = nodes.new("ShaderNodeVertexColor")  # the "Color Attribute" node
    color.location = (-300, 0)
    color.layer_name = COLOR_ATTRIBUTE

    # Wool is a rough dielectric whose fibres scatter light at grazing angles: high roughness
    # and a strong sheen give the soft rim that reads as cloth in EEVEE and Cycles.
    inputs = bsdf.inputs
    inputs["Roughness"].default_value = 0.8
    inputs["Sheen Weight"].default_value = 0.7
    inputs["Sheen Roughness"].default_value = 0.5
    inputs["Specular IOR Level"].default_value = 0.3

    links.new(color.outputs["Color"], bsdf.inputs["Base Color"])
    links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])

    # The fibres' direction (the core's tangents, slanted with the twist) draws the highlight
    # along each strand. A mesh without them (a baked knit, a user's own mesh) reads a zero
    # vector: its length switches the anisotropy off, leaving a round highlight.
    fibre = nodes.new("ShaderNodeAttribute")
    fibre.location = (-600, -300)
    fibre.attribute_type = "GEOMETRY"
    fibre.attribute_name = TANGENT_ATTRIBUTE
    present = nodes.new("ShaderNodeVectorMath")
    present.location = (-400, -450)
    present.operation = "LENGTH"
    anisotropy = nodes.new("ShaderNodeMath")
    anisotropy.location = (-200, -450)
    anisotropy.operation = "MULTIPLY"
    anisotropy.use_clamp = True
    anisotropy.inputs[1].default_value = FIBRE_ANISOTROPY
    links.new(fibre.outputs["Vector"], bsdf.inputs["Tangent"])
    links.new(fibre.outputs["Vector"], present.inputs[0])
    links.new(present.outputs["Value"], anisotropy.inputs[0])
    links.new(anisotropy.outputs["Value"], bsdf.inputs["Anisotropic"])

    # Solid/Workbench "Material" colour and the material preview swatch: a neutral wool tone.
    material.diffuse_color = (0.6, 0.55, 0.5, 1.0)
    material.roughness = 0.8


def yarn_material() -> bpy.types.Material:
    """The shared yarn material, created on first use."""
    material = bpy.data.materials.get(MATERIAL_NAME)
    if material is None:
        material = bpy.data.materials.new(MATERIAL_NAME)
        _build(material)
    return material


def assign(mesh: bpy.types.Mesh) -> None:
    """Give ``mesh`` the yarn material unless it already has one (a user's choice stays)."""
    if len(mesh.materials) == 0:
        mesh.materials.append(yarn_material())
