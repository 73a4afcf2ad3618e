"""The sidebar panel (3D Viewport > N > Knitwear)."""

import bpy

from .bake import OBJECT_OT_knitwear_bake
from .operators import OBJECT_OT_knitwear_knit, OBJECT_OT_knitwear_update
from .settings_ui import draw_settings


class VIEW3D_PT_knitwear(bpy.types.Panel):
    """A knit's settings and Update button, or a Knit button on a surface or mesh."""

    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Knitwear"
    bl_label = "Knitwear"

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        # A plush object has a panel of its own (plush/operators.py).
        return (
            obj is not None
            and obj.type in {"SURFACE", "MESH"}
            and not obj.knitwear_plush.is_plush
        )

    def draw(self, context: bpy.types.Context) -> None:
        layout = self.layout
        obj = context.active_object
        settings = obj.knitwear
        if not settings.is_knit:
            layout.operator(OBJECT_OT_knitwear_knit.bl_idname, icon="MOD_CLOTH")
            return
        layout.use_property_split = True
        layout.use_property_decorate = False
        layout.prop(settings, "source")
        layout.prop(settings, "follow_source")
        layout.prop(settings, "save_as_recipe")
        draw_settings(layout, settings, "knitwear_panel")
        layout.separator()
        row = layout.row()
        row.scale_y = 1.4
        row.operator(OBJECT_OT_knitwear_update.bl_idname, icon="FILE_REFRESH")
        layout.operator(OBJECT_OT_knitwear_bake.bl_idname, icon="FILE_CACHE")
