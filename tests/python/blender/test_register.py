"""Installing, enabling and registering the extension."""

from pathlib import Path
from types import ModuleType

import bpy
from blender_scenes import ADDON_MODULE, SMALL, nurbs_patch


def _registered() -> dict[str, bool]:
    return {
        "settings": hasattr(bpy.types.Object, "knitwear"),
        "knit operator": hasattr(bpy.types, "OBJECT_OT_knitwear_knit"),
        "update operator": hasattr(bpy.types, "OBJECT_OT_knitwear_update"),
        "panel": hasattr(bpy.types, "VIEW3D_PT_knitwear"),
    }


def _in_object_menu(addon: ModuleType) -> bool:
    return addon.operators.draw_object_menu in bpy.types.VIEW3D_MT_object._dyn_ui_initialize()


def test_core_comes_from_the_bundled_wheel(core: ModuleType) -> None:
    # The `core` fixture asserts where it was imported from; check it is the real thing too.
    assert issubclass(core.BudgetError, core.KnitError)
    assert "stockinette" in core.Pattern.presets()


def test_installed_extension_is_registered(addon: ModuleType) -> None:
    assert all(_registered().values()), _registered()
    assert _in_object_menu(addon)
    assert bpy.ops.object.knitwear_knit.idname() == "OBJECT_OT_knitwear_knit"


def test_unregister_register_is_symmetric_and_repeatable(addon: ModuleType) -> None:
    for _ in range(2):
        addon.unregister()
        assert not any(_registered().values()), _registered()
        assert not _in_object_menu(addon)
        addon.register()
        assert all(_registered().values()), _registered()
        assert _in_object_menu(addon)


def test_disable_enable_through_preferences(addon: ModuleType) -> None:
    bpy.ops.preferences.addon_disable(module=ADDON_MODULE)
    assert ADDON_MODULE not in bpy.context.preferences.addons
    assert not any(_registered().values())
    bpy.ops.preferences.addon_enable(module=ADDON_MODULE)
    assert all(_registered().values())


def test_settings_survive_save_and_reload(tmp_path: object, api: ModuleType) -> None:
    bpy.ops.surface.primitive_nurbs_surface_surface_add()
    source = bpy.context.active_object
    knit = api.knit_object(source, size_mode="COUNTS", courses=3, wales=4, pattern="seed")
    names = (knit.name, source.name)
    path = str(tmp_path / "knit.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path)  # invalidates every Python reference to data
    knit, source = (bpy.data.objects[name] for name in names)
    assert knit.knitwear.is_knit
    assert knit.knitwear.source == source
    assert (knit.knitwear.pattern, knit.knitwear.courses, knit.knitwear.wales) == ("seed", 3, 4)


def test_tunings_are_kept_in_the_extension_user_folder(
    addon: ModuleType, api: ModuleType, core: ModuleType
) -> None:
    # Blender's folder for an extension's own files; a knit's tuning is stored there, so the
    # next Blender (a reopened scene, a farm node) skips the search.
    folder = Path(bpy.utils.extension_path_user(ADDON_MODULE, path="tuning"))
    assert core.tuning_store() == str(folder)
    api.knit_object(nurbs_patch(), **(SMALL | {"pattern": "moss"}))
    files = list(folder.glob("*.tuning"))
    assert files and all(f.read_text().startswith("knitwear tuning store 1\n") for f in files)
    addon.unregister()
    try:
        assert core.tuning_store() is None, "unregister must give the core back as it was"
    finally:
        addon.register()
    assert core.tuning_store() == str(folder)
