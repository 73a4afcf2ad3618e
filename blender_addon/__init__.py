"""Knitwear: realistic knitted yarn over NURBS surfaces and UV-mapped meshes.

Registration only. The work is in `api` (the scripting API), fed by `sampling`
(Blender -> core) and `mesh_build` (core -> Blender); the compiled core is the `knitwear`
package this extension bundles as a wheel.
"""

import bpy


# The `poll` functions of the add-on's object pointers live here, in the package itself, and
# are defined before the submodules that use them are imported: bpy 4.2 segfaults at exit
# (rc 139, after everything worked) when a PointerProperty's poll is a function of a
# submodule.
def poll_knit_source(_self: bpy.types.PropertyGroup, obj: bpy.types.Object) -> bool:
    """What a knit's Source may be: a NURBS surface or a mesh that is not itself a knit."""
    return obj.type in {"SURFACE", "MESH"} and not obj.knitwear.is_knit


def poll_plush_source(_self: bpy.types.PropertyGroup, obj: bpy.types.Object) -> bool:
    """What a plush's Source may be: a NURBS surface or a mesh."""
    return obj.type in {"SURFACE", "MESH"}


from . import (  # noqa: E402
    bake,
    follow,
    operators,
    panels,
    plush,
    properties,
    recipe,
    texture,
    tuning_store,
)

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
    recipe.register()
    plush.register()
    texture.register()
    tuning_store.register()


def unregister() -> None:
    tuning_store.unregister()
    texture.unregister()
    plush.unregister()
    recipe.unregister()
    follow.unregister()
    bpy.types.VIEW3D_MT_object.remove(operators.draw_object_menu)
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
    properties.unregister()
