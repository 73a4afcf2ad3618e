"""The plush operators, panel and Object menu entry."""

import bpy
import knitwear

from .api import PlushOutcome, noise_image, plush, update_plush_view
from .properties import SETTING_NAMES, PlushSettingsMixin


class OBJECT_OT_knitwear_plush_noise(bpy.types.Operator):
    """Make an image of this plush's fractal-noise pile directions (open it in the Image
    Editor)"""

    bl_idname = "object.knitwear_plush_noise"
    bl_label = "Show Pile Noise"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        return obj is not None and obj.knitwear_plush.is_plush

    def execute(self, context: bpy.types.Context) -> set[str]:
        try:
            image = noise_image(context.active_object, context=context)
        except knitwear.KnitError as err:
            self.report({"ERROR"}, str(err))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Pile noise in image '{image.name}' ({image.size[0]}x"
                    f"{image.size[1]})")
        return {"FINISHED"}


def _draw_settings(layout: bpy.types.UILayout, settings: bpy.types.AnyType, prefix: str) -> None:
    layout.use_property_split = True
    layout.use_property_decorate = False
    header, body = layout.panel(f"{prefix}_size")
    header.label(text="Size")
    if body is not None:
        body.row().prop(settings, "size_mode", expand=True)
        col = body.column(align=True)
        if settings.size_mode == "GAUGE":
            col.prop(settings, "gauge_stitches")
            col.prop(settings, "gauge_rows")
        else:
            col.prop(settings, "courses")
            col.prop(settings, "wales")
        body.prop(settings, "piles_per_stitch")
    header, body = layout.panel(f"{prefix}_pile")
    header.label(text="Pile")
    if body is not None:
        for name in ("pile_length", "pile_radius", "slices", "lean_angle", "lean_direction",
                     "theta_max", "noise_scales", "seed"):
            body.prop(settings, name)
    header, body = layout.panel(f"{prefix}_colour")
    header.label(text="Colour")
    if body is not None:
        body.prop(settings, "color_mode")
        shown = 1
        if settings.color_mode == "STRIPES":
            body.prop(settings, "color_count")
            body.prop(settings, "stripe_height")
            shown = settings.color_count
        elif settings.color_mode == "IMAGE":
            body.prop_search(settings, "color_image_name", bpy.data, "images")
            shown = 0
        col = body.column(align=True)
        for i in range(shown):
            col.prop(settings, f"color_{i + 1}")
    header, body = layout.panel(f"{prefix}_press", default_closed=True)
    header.label(text="Press")
    if body is not None:
        body.prop_search(settings, "press_image_name", bpy.data, "images")
        body.prop(settings, "press_strength")


def _summary(outcome: PlushOutcome) -> str:
    return (
        f"Plush: {outcome.piles:,} piles, {outcome.triangles:,} triangles "
        f"({outcome.horizontal:,} horizontal, {outcome.vertical:,} vertical) "
        f"in {outcome.seconds:.2f} s"
    )


class OBJECT_OT_knitwear_plush(PlushSettingsMixin, bpy.types.Operator):
    """Grow warp-knit plush (pile) over the active NURBS surface or UV-mapped mesh, as a new
    object whose slices follow the scene camera"""

    bl_idname = "object.knitwear_plush"
    bl_label = "Plush this surface"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        if obj is None or obj.type not in {"SURFACE", "MESH"}:
            cls.poll_message_set("Select a NURBS surface or a mesh with a UV map")
            return False
        if context.mode != "OBJECT":
            cls.poll_message_set("Switch to Object Mode to grow plush")
            return False
        if obj.knitwear_plush.is_plush or obj.knitwear.is_knit:
            cls.poll_message_set("The active object is already a plush or a knit")
            return False
        return True

    def execute(self, context: bpy.types.Context) -> set[str]:
        settings = {name: getattr(self, name) for name in SETTING_NAMES}
        try:
            outcome = plush(context.active_object, context=context, **settings)
        except knitwear.KnitError as err:
            self.report({"ERROR"}, str(err))
            return {"CANCELLED"}
        for other in context.selected_objects:
            other.select_set(False)
        try:
            outcome.object.select_set(True)
            context.view_layer.objects.active = outcome.object
        except RuntimeError:
            pass  # the source's collection is excluded from this view layer
        self.report({"INFO"}, _summary(outcome))
        return {"FINISHED"}

    def draw(self, _context: bpy.types.Context) -> None:
        _draw_settings(self.layout, self, "knitwear_plush_redo")


class OBJECT_OT_knitwear_plush_view(bpy.types.Operator):
    """Choose the active plush's slices for the scene camera now"""

    bl_idname = "object.knitwear_plush_view"
    bl_label = "Update Plush View"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        if obj is None or obj.type != "MESH" or not obj.knitwear_plush.is_plush:
            cls.poll_message_set("The active object is not a plush")
            return False
        return True

    def execute(self, context: bpy.types.Context) -> set[str]:
        try:
            update_plush_view(context.active_object, context=context, force=True)
        except knitwear.KnitError as err:
            self.report({"ERROR"}, str(err))
            return {"CANCELLED"}
        return {"FINISHED"}


class VIEW3D_PT_knitwear_plush(bpy.types.Panel):
    """A plush's source, camera following and the settings it was grown with."""

    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Knitwear"
    bl_label = "Plush"

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        return obj is not None and obj.type in {"SURFACE", "MESH"}

    def draw(self, context: bpy.types.Context) -> None:
        layout = self.layout
        stored = context.active_object.knitwear_plush
        if not stored.is_plush:
            layout.operator(OBJECT_OT_knitwear_plush.bl_idname, icon="OUTLINER_OB_CURVES")
            return
        layout.use_property_split = True
        layout.use_property_decorate = False
        layout.prop(stored, "source")
        layout.prop(stored, "follow_camera")
        layout.operator(OBJECT_OT_knitwear_plush_view.bl_idname, icon="VIEW_CAMERA")
        layout.operator(OBJECT_OT_knitwear_plush_noise.bl_idname, icon="IMAGE_DATA")
        box = layout.column()
        box.label(text="Grown with (undo and redo the operator to change):")
        box.enabled = False
        _draw_settings(box, stored, "knitwear_plush_panel")


def draw_object_menu(self: bpy.types.Menu, _context: bpy.types.Context) -> None:
    """Object menu entries (which also makes them searchable with F3)."""
    self.layout.operator(OBJECT_OT_knitwear_plush.bl_idname, icon="OUTLINER_OB_CURVES")
