"""Knitwear: realistic knitted yarn over NURBS surfaces and UV-mapped meshes.

Registration only. The work is in `api` (the scripting API), fed by `sampling`
(Blender -> core) and `mesh_build` (core -> Blender); the compiled core is the `knitwear`
package this extension bundles as a wheel.
"""

import bpy

from . import bake, follow, operators, panels, plush, properties, texture

_CLASSES: tuple[type, ...] = (
    operators.OBJECT_OT_knitwear_knit,
    operators.OBJECT_OT_knitwear_update,
    bake.OBJECT_OT_knitwear_bake,
    panels.VIEW3D_PT_knitwear,
)


def register() -> None:
    # The settings first: the operators' polls and the panel read `Object.knitwear`.
    properties.register()
    for cls in _CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.VIEW3D_MT_object.append(operators.draw_object_menu)
    follow.register()
    plush.register()
    texture.register()


def unregister() -> None:
    texture.unregister()
    plush.unregister()
    follow.unregister()
    bpy.types.VIEW3D_MT_object.remove(operators.draw_object_menu)
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
    properties.unregister()
