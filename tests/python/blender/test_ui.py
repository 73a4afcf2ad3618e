"""The panel and the redo panel draw every setting, by names that exist.

Headless there is no UI to draw into, so a recording stand-in for `bpy.types.UILayout` takes
the calls: enough to catch a misspelt property or a setting that no mode ever shows.
"""

import sys
from pathlib import Path
from types import ModuleType
from typing import Any

import bpy
import numpy as np
from blender_scenes import SMALL, nurbs_patch
from PIL import Image

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "scripts"))
import ui_pictures  # noqa: E402


class FakeLayout:
    """Records `prop`/`prop_search`/`operator` calls from a draw function, recursively."""

    def __init__(self, log: list[tuple[str, str]]) -> None:
        self.log = log
        self.use_property_split = False
        self.use_property_decorate = True
        self.scale_y = 1.0

    def _child(self, *_args: Any, **_kwargs: Any) -> "FakeLayout":
        return FakeLayout(self.log)

    row = column = box = _child

    def panel(self, idname: str, default_closed: bool = False) -> tuple["FakeLayout", ...]:
        return FakeLayout(self.log), FakeLayout(self.log)  # drawn open

    def prop(self, data: Any, name: str, **_kwargs: Any) -> None:
        assert name in data.bl_rna.properties, f"no property {name!r} on {data}"
        self.log.append(("prop", name))

    def prop_search(self, data: Any, name: str, search_data: Any, search: str) -> None:
        assert name in data.bl_rna.properties
        assert hasattr(search_data, search)
        self.log.append(("prop", name))

    def operator(self, idname: str, **_kwargs: Any) -> None:
        category, name = idname.split(".")
        assert hasattr(getattr(bpy.ops, category), name), idname
        self.log.append(("operator", idname))

    def label(self, **_kwargs: Any) -> None:
        pass

    def separator(self, **_kwargs: Any) -> None:
        pass


class FakePanel:
    def __init__(self, log: list[tuple[str, str]]) -> None:
        self.layout = FakeLayout(log)


def test_settings_sections_draw_every_setting(addon: ModuleType, api: ModuleType) -> None:
    knit = api.knit_object(nurbs_patch(), **SMALL)
    settings = knit.knitwear
    drawn: set[str] = set()
    for pattern in ("stockinette", "CUSTOM", "FILE"):
        for size_mode in ("GAUGE", "COUNTS"):
            for color_mode in ("SINGLE", "STRIPES", "CHART", "IMAGE"):
                settings.pattern, settings.size_mode = pattern, size_mode
                settings.color_mode = color_mode
                settings.color_count = 4
                log: list[tuple[str, str]] = []
                addon.settings_ui.draw_settings(FakeLayout(log), settings, "test")
                drawn |= {name for kind, name in log if kind == "prop"}
    assert drawn == set(addon.properties.SETTING_NAMES)


def test_panel_on_a_knit_and_on_a_source(addon: ModuleType, api: ModuleType) -> None:
    panel = addon.panels.VIEW3D_PT_knitwear
    source = nurbs_patch()
    assert panel.poll(bpy.context)
    log: list[tuple[str, str]] = []
    panel.draw(FakePanel(log), bpy.context)
    assert log == [("operator", "object.knitwear_knit")]

    knit = api.knit_object(source, **SMALL)
    bpy.context.view_layer.objects.active = knit
    log = []
    panel.draw(FakePanel(log), bpy.context)
    assert ("prop", "source") in log and ("prop", "follow_source") in log
    assert log[-2:] == [
        ("operator", "object.knitwear_update"),
        ("operator", "object.knitwear_bake"),
    ]


def test_object_menu_entries(addon: ModuleType) -> None:
    log: list[tuple[str, str]] = []
    addon.operators.draw_object_menu(FakePanel(log), bpy.context)
    assert log == [
        ("operator", "object.knitwear_knit"),
        ("operator", "object.knitwear_update"),
    ]


def test_ui_pictures_draw_the_panels_as_they_stand(
    addon: ModuleType, api: ModuleType, tmp_path: Path
) -> None:
    """scripts/ui_pictures.py (the pictures of docs/blender.md) draws the sidebar from the
    panels' real draw code and the knit's real values: a yarn colour set on the knit shows as
    its swatch, and a section Blender shows closed hides its widgets."""
    knit = api.knit_object(nurbs_patch(), **SMALL)
    bpy.context.view_layer.objects.active = knit
    knit.knitwear.color_1 = (1.0, 0.0, 0.0)
    opened = ui_pictures.sidebar(open_all=True)
    assert [title for title, _ in opened] == ["Knitwear", "Plush"]
    ui_pictures.picture(tmp_path / "open.png", opened)
    ui_pictures.picture(tmp_path / "default.png", ui_pictures.sidebar())
    shown = np.asarray(Image.open(tmp_path / "open.png").convert("RGB")).reshape(-1, 3)
    red = np.all(shown == (255, 0, 0), axis=1).sum()
    assert red > 200, f"{red} pixels of the red swatch"

    def props(widgets: list[Any]) -> set[str]:
        return {w.name for w in widgets if w.kind == "prop"} | {
            name for w in widgets for name in props(w.children)
        }

    default = dict(ui_pictures.sidebar())["Knitwear"]
    assert "ring_segments" in props(dict(opened)["Knitwear"])
    assert "ring_segments" not in props(default)  # Yarn starts closed
    h_open = Image.open(tmp_path / "open.png").height
    assert Image.open(tmp_path / "default.png").height < h_open
