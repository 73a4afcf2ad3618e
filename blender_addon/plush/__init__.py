"""Plush: warp-knitted pile over a NURBS surface or a UV-mapped mesh (docs/plush.md).

The core (`knitwear.plush`) does all the geometry: pile roots on the stitch grid, fractal-noise
directions, press-map bending and, per pile, horizontal or vertical slices for the view. This
module only moves buffers: the source is read with `sampling.sample_object`, the slices become
a mesh through `mesh_build` (the fast template route, with the core's edges), and the view is
the scene camera's, expressed in the plush object's space (the source's object space with its
scale baked in, see `sampling`).

Follow the camera. A plush's `knitwear.PlushField` (roots, frames, directions, colours) is kept
per object in a module-level cache; on every frame change and on `update_plush_view(obj)` the
camera's eye (perspective) or direction (orthographic) goes to `PlushField.view`, and only the
vertex positions and the "plush_mask" attribute are written: the slices keep their topology,
UVs and colours. After a file load (or on a farm machine) the field is grown again from the
stored settings, which is deterministic: same source, settings and seed, same field.

Scripting::

    from bl_ext.user_default.knitwear import plush
    obj = plush.knit_plush(bpy.data.objects["Cushion"], size_mode="COUNTS", courses=200,
                           wales=160, pile_length=0.01, seed=3, press_image_name="Palm")
    plush.update_plush_view(obj)   # after moving the camera by hand
"""

import bpy
from bpy.props import PointerProperty

from . import api, core_inputs, mesh, operators, properties
from .api import _fields, knit_plush, noise_image, plush, plush_objects, update_plush_view
from .core_inputs import core_settings, view_of
from .properties import PLUSH_SETTINGS, SETTING_NAMES, PlushSettings, PlushSettingsMixin

__all__ = [
    "PLUSH_SETTINGS",
    "SETTING_NAMES",
    "PlushSettingsMixin",
    "api",
    "core_inputs",
    "core_settings",
    "knit_plush",
    "mesh",
    "noise_image",
    "operators",
    "plush",
    "plush_objects",
    "properties",
    "update_plush_view",
    "view_of",
]

_CLASSES: tuple[type, ...] = (
    PlushSettings,
    operators.OBJECT_OT_knitwear_plush,
    operators.OBJECT_OT_knitwear_plush_view,
    operators.OBJECT_OT_knitwear_plush_noise,
    operators.VIEW3D_PT_knitwear_plush,
)
_HANDLERS = (
    (bpy.app.handlers.frame_change_post, api.on_frame_change),
    (bpy.app.handlers.load_post, api.on_load),
)


def register() -> None:
    for cls in _CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Object.knitwear_plush = PointerProperty(type=PlushSettings)
    bpy.types.VIEW3D_MT_object.append(operators.draw_object_menu)
    for handlers, handler in _HANDLERS:
        if handler not in handlers:
            handlers.append(handler)


def unregister() -> None:
    for handlers, handler in reversed(_HANDLERS):
        if handler in handlers:
            handlers.remove(handler)
    bpy.types.VIEW3D_MT_object.remove(operators.draw_object_menu)
    del bpy.types.Object.knitwear_plush
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
    _fields.clear()
