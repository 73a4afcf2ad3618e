"""Knitwear texture: the knit drawn in the source's (u,v) as an image, worn by the source
itself as a material ([Zhong 2001], section 3). No yarn geometry, so it costs one image: the
stand-in for knitwear seen from afar.

The source is sampled and the settings converted exactly as for a knit (`core_inputs`),
so the texture shows the stitches, perturbation and colours the Knit operator would build.
The image, "<source> Knit Texture", holds the core's linear RGBA pixels over the knit's
(u,v) domain (a NURBS surface's whole parameter range, a mesh's UV bounding box); the
material of the same name samples it by the surface's UV map (a NURBS surface's UV map is
its (u,v)), with u and v swapped where the courses run along V.
"""

from typing import Any

import bpy
import knitwear
import numpy as np
from bpy.props import IntProperty

from . import core_inputs
from .properties import SETTING_NAMES, KnitSettingsMixin
from .settings_ui import draw_settings

#: Largest texture side, pixels (the core's limit).
MAX_SIZE = 16384

#: Most pixels a texture may have. The image is packed into the .blend (generated pixels are
#: otherwise lost on save) as a float EXR of 16 bytes a pixel, and Blender 5.0.1 cannot pack
#: 2 GiB or more: measured with incompressible pixels, 11584 x 11584 packs in 2,147,303,341
#: bytes, 8192 x 16384 gives a negative size and 16384 x 16384 crashes it. 64 MiB is left
#: for the EXR's headers and offset tables (about 0.3 MiB at 11584 rows).
MAX_PIXELS = (2**31 - 2**26) // 16


def check_size(width: int, height: int) -> None:
    """Refuse a ``width x height`` texture Blender could not keep (`MAX_PIXELS`), naming it."""
    if not (1 <= width <= MAX_SIZE and 1 <= height <= MAX_SIZE):
        raise knitwear.ParameterError(
            f"texture size {width} x {height}: each side must be 1 to {MAX_SIZE} pixels"
        )
    if width * height > MAX_PIXELS:
        side = int(MAX_PIXELS**0.5)
        raise knitwear.BudgetError(
            f"a {width} x {height} texture is {width * height * 16 / 2**30:.1f} GiB of float "
            f"pixels, and Blender cannot pack an image of 2 GiB or more into the .blend: use at "
            f"most {MAX_PIXELS:,} pixels (e.g. {side} x {side}, or {MAX_SIZE} x "
            f"{MAX_PIXELS // MAX_SIZE})"
        )


def texture_name(source: bpy.types.Object) -> str:
    """The name of ``source``'s knit texture image and material."""
    return f"{source.name} Knit Texture"


def _store_image(name: str, pixels: np.ndarray) -> bpy.types.Image:
    height, width = pixels.shape[:2]
    image = bpy.data.images.get(name)
    if image is not None and (tuple(image.size) != (width, height) or not image.is_float):
        bpy.data.images.remove(image)
        image = None
    if image is None:
        image = bpy.data.images.new(name, width, height, alpha=True, float_buffer=True)
    # Float images hold scene-linear values, which is what the core writes.
    image.colorspace_settings.name = "Linear Rec.709"
    image.alpha_mode = "STRAIGHT"
    image.pixels.foreach_set(pixels.ravel())
    image.update()
    # Generated pixels are lost on save unless packed into the blend file.
    image.pack()
    return image


def _build_material(
    material: bpy.types.Material,
    image: bpy.types.Image,
    domain: tuple[tuple[float, float], tuple[float, float]],
    repeat: bool,
) -> None:
    if material.node_tree is None:
        material.use_nodes = True  # Blender 4.x; 5.0 always has a tree
    nodes = material.node_tree.nodes
    links = material.node_tree.links
    nodes.clear()

    coords = nodes.new("ShaderNodeTexCoord")
    coords.location = (-600, 0)
    # The image spans the knit's (u,v) domain, in the UV map's order: map it onto [0, 1]
    # (the identity for a NURBS surface and a mesh unwrapped over the whole UV square).
    (u0, v0), (u1, v1) = domain
    mapping = nodes.new("ShaderNodeMapping")
    mapping.location = (-400, 0)
    mapping.vector_type = "POINT"
    du, dv = max(u1 - u0, 1e-12), max(v1 - v0, 1e-12)
    mapping.inputs["Scale"].default_value = (1.0 / du, 1.0 / dv, 1.0)
    mapping.inputs["Location"].default_value = (-u0 / du, -v0 / dv, 0.0)
    links.new(coords.outputs["UV"], mapping.inputs["Vector"])

    tex = nodes.new("ShaderNodeTexImage")
    tex.location = (-200, 0)
    tex.image = image
    tex.interpolation = "Linear"
    tex.extension = "REPEAT" if repeat else "EXTEND"
    links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    nodes.active = tex  # what Workbench's Texture colour shows

    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.location = (200, 0)
    # Wool, as the yarn material (material.py): rough, with a strong sheen.
    inputs = bsdf.inputs
    inputs["Roughness"].default_value = 0.8
    inputs["Sheen Weight"].default_value = 0.7
    inputs["Sheen Roughness"].default_value = 0.5
    inputs["Specular IOR Level"].default_value = 0.3
    links.new(tex.outputs["Color"], inputs["Base Color"])
    links.new(tex.outputs["Alpha"], inputs["Alpha"])
    output = nodes.new("ShaderNodeOutputMaterial")
    output.location = (500, 0)
    links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])


def _mean_color(pixels: np.ndarray) -> tuple[float, float, float, float]:
    alpha = pixels[..., 3]
    covered = float(alpha.sum())
    if covered <= 0:
        return (0.0, 0.0, 0.0, 1.0)
    rgb = (pixels[..., :3] * alpha[..., None]).reshape(-1, 3).sum(axis=0) / covered
    return (float(rgb[0]), float(rgb[1]), float(rgb[2]), 1.0)


def texture_object(
    source: bpy.types.Object,
    *,
    context: bpy.types.Context | None = None,
    width: int = 1024,
    height: int = 1024,
    **settings: Any,
) -> bpy.types.Material:
    """Give ``source`` (a NURBS surface or a mesh with a UV map) the knitwear texture of
    ``settings`` (the knit settings of `api.knit_object`), ``width x height`` pixels, as the
    material "<source> Knit Texture" in its first slot; return the material.

    Raises `knitwear.KnitError` (nothing is created then).
    """
    context = context or bpy.context
    check_size(int(width), int(height))
    settings = core_inputs.complete(settings)
    source = core_inputs.check_source(source, "the object")
    inputs = core_inputs.core_inputs(source, context, settings)
    surface = inputs.sampled.surface
    # The core's u runs along the courses: the surface's v where they run along V. The image
    # is stored in the UV map's order (transposed then), so that viewers that sample it by
    # the UV map directly (Workbench's Texture colour) show it the right way round too.
    swap = inputs.sampled.courses_along == "V"
    pixels = knitwear.knit_texture(
        surface,
        inputs.pattern,
        width=int(height if swap else width),
        height=int(width if swap else height),
        **inputs.kwargs,
    )
    # Everything that can fail has run: from here on the blend file changes.
    if isinstance(surface, knitwear.MeshSurface):
        (u0, v0), (u1, v1) = surface.domain
    else:
        (u0, v0), (u1, v1) = (0.0, 0.0), (1.0, 1.0)
    if swap:
        pixels = np.ascontiguousarray(pixels.transpose(1, 0, 2))
        (u0, v0), (u1, v1) = (v0, u0), (v1, u1)
    repeat = source.type == "SURFACE" and any(
        (s.use_cyclic_u or s.use_cyclic_v) for s in source.data.splines
    )
    name = texture_name(source)
    image = _store_image(name, pixels)
    material = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    _build_material(material, image, ((u0, v0), (u1, v1)), repeat)
    material.diffuse_color = _mean_color(pixels)
    material.roughness = 0.8
    slots = source.data.materials
    if material.name not in slots:
        if len(slots) == 0:
            slots.append(material)
        else:
            slots[0] = material
    return material


class OBJECT_OT_knitwear_texture(KnitSettingsMixin, bpy.types.Operator):
    """Give the active NURBS surface or UV-mapped mesh an image of knitted stitches as its
    material: a cheap stand-in for a knit seen from afar"""

    bl_idname = "object.knitwear_texture"
    bl_label = "Knitwear Texture"
    bl_options = {"REGISTER", "UNDO"}

    texture_width: IntProperty(
        name="Width",
        description="Texture width in pixels",
        default=1024,
        min=1,
        max=MAX_SIZE,
        soft_max=8192,
    )
    texture_height: IntProperty(
        name="Height",
        description="Texture height in pixels",
        default=1024,
        min=1,
        max=MAX_SIZE,
        soft_max=8192,
    )

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        if obj is None or obj.type not in {"SURFACE", "MESH"}:
            cls.poll_message_set("Select a NURBS surface or a mesh with a UV map")
            return False
        if context.mode != "OBJECT":
            cls.poll_message_set("Switch to Object Mode to texture it")
            return False
        if obj.knitwear.is_knit:
            cls.poll_message_set("The active object is a knit: texture its source instead")
            return False
        if obj.knitwear_plush.is_plush:
            cls.poll_message_set("The active object is a plush: texture its source instead")
            return False
        return True

    def execute(self, context: bpy.types.Context) -> set[str]:
        settings = {name: getattr(self, name) for name in SETTING_NAMES}
        try:
            material = texture_object(
                context.active_object,
                context=context,
                width=self.texture_width,
                height=self.texture_height,
                **settings,
            )
        except knitwear.KnitError as err:
            self.report({"ERROR"}, str(err))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Knitwear texture in material '{material.name}'")
        return {"FINISHED"}

    def draw(self, _context: bpy.types.Context) -> None:
        layout = self.layout
        layout.use_property_split = True
        col = layout.column(align=True)
        col.prop(self, "texture_width")
        col.prop(self, "texture_height")
        draw_settings(layout, self, "knitwear_texture_redo")


def draw_object_menu(self: bpy.types.Menu, _context: bpy.types.Context) -> None:
    """The Object menu entry (after the Knit entries, which add the separator)."""
    self.layout.operator(OBJECT_OT_knitwear_texture.bl_idname, icon="TEXTURE")


def register() -> None:
    bpy.utils.register_class(OBJECT_OT_knitwear_texture)
    bpy.types.VIEW3D_MT_object.append(draw_object_menu)


def unregister() -> None:
    bpy.types.VIEW3D_MT_object.remove(draw_object_menu)
    bpy.utils.unregister_class(OBJECT_OT_knitwear_texture)
