"""Pictures of the add-on's UI (issue 22): the sidebar on a surface and on a knit, the Knit
operator's redo panel and the Object menu entries, drawn from the add-on's own draw code.

    .venv/bin/python scripts/ui_pictures.py [--zip dist/knitwear-0.1.0.zip] [--out docs/ui]

Headless Blender (the `bpy` module) has no window to take a screenshot of. So this installs the
extension as Install from Disk does, builds the scene a user would have, and runs the real
`draw` of every panel of the Knitwear sidebar tab whose `poll` passes, of the Knit operator and
of the Object menu entries, into a recording stand-in for `bpy.types.UILayout`. Each recorded
widget is then drawn with its property's real label, value and type from RNA (a number field,
a checkbox, a drop-down, a colour swatch, a button), in the colours of Blender's default dark
theme, a section closed where Blender closes it by default, an entry greyed where its `poll`
fails. It shows what the panels hold and in what order; fonts, icons and widget shapes are
simplified, so it is a picture of the UI state, not a pixel-exact screenshot.

Writes sidebar_source.png (a NURBS surface selected: Knit and Plush buttons), sidebar_knit.png
(a knit selected, sections as Blender first shows them), sidebar_knit_open.png (every section
open), redo_knit.png (the redo panel after Knit this surface), redo_scarf.png (the same, set
as the first-knit tutorial says) and object_menu.png.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from PIL import Image, ImageDraw, ImageFont

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from bench_setup import start_blender  # noqa: E402

# ---------------------------------------------------------------------------------------------
# Recording the draw calls


@dataclass
class Widget:
    """One drawn thing. ``kind``: prop, operator, label, separator, group (a row or column of
    ``children``) or panel (a collapsible section: ``text`` its title, ``children`` its body,
    ``closed`` when Blender shows it closed)."""

    kind: str
    data: Any = None
    name: str = ""
    text: str | None = None
    expand: bool = False
    split: bool = False
    dim: bool = False
    scale_y: float = 1.0
    horizontal: bool = False
    closed: bool = False
    children: list[Widget] = field(default_factory=list)


class RecordingLayout:
    """Takes a draw function's `UILayout` calls and records them as [`Widget`]s. Children
    inherit property split, `active` and `enabled` as Blender's layouts do. ``open_all``:
    draw every collapsible section open, whatever its default."""

    def __init__(self, out: list[Widget], split: bool = False, dim: bool = False,
                 open_all: bool = False) -> None:
        self._out = out
        self._open_all = open_all
        self._dim = dim
        self.use_property_split = split
        self.use_property_decorate = True
        self.scale_y = 1.0
        self.active = True
        self.enabled = True
        self.alignment = "EXPAND"

    def _dimmed(self) -> bool:
        return self._dim or not self.active or not self.enabled

    def _group(self, horizontal: bool) -> RecordingLayout:
        w = Widget("group", horizontal=horizontal, split=self.use_property_split)
        self._out.append(w)
        child = RecordingLayout(w.children, self.use_property_split, self._dimmed(),
                                self._open_all)
        return child

    def row(self, **_kwargs: Any) -> RecordingLayout:
        return self._group(True)

    def column(self, **_kwargs: Any) -> RecordingLayout:
        return self._group(False)

    box = column

    def panel(self, _idname: str, default_closed: bool = False
              ) -> tuple[RecordingLayout, RecordingLayout | None]:
        w = Widget("panel", closed=default_closed and not self._open_all)
        self._out.append(w)
        header = RecordingLayout([], False, self._dimmed(), self._open_all)
        header.label = lambda text="", **_k: setattr(w, "text", text)  # type: ignore[method-assign]
        body = RecordingLayout(w.children, self.use_property_split, self._dimmed(),
                               self._open_all)
        return header, None if w.closed else body

    def prop(self, data: Any, name: str, text: str | None = None, expand: bool = False,
             **_kwargs: Any) -> None:
        if name not in data.bl_rna.properties:
            raise KeyError(f"no property {name!r} on {data}")
        self._out.append(Widget("prop", data=data, name=name, text=text, expand=expand,
                                split=self.use_property_split, dim=self._dimmed(),
                                scale_y=self.scale_y))

    def prop_search(self, data: Any, name: str, _search_data: Any, _search: str,
                    text: str | None = None, **_kwargs: Any) -> None:
        self.prop(data, name, text=text)

    def operator(self, idname: str, text: str | None = None, **_kwargs: Any) -> None:
        import bpy

        category, op = idname.split(".")
        fn = getattr(getattr(bpy.ops, category), op)
        label = text if text is not None else fn.get_rna_type().name
        self._out.append(Widget("operator", name=idname, text=label,
                                dim=self._dimmed() or not fn.poll(), scale_y=self.scale_y))

    def label(self, text: str = "", **_kwargs: Any) -> None:
        self._out.append(Widget("label", text=text, dim=self._dimmed()))

    def separator(self, **_kwargs: Any) -> None:
        self._out.append(Widget("separator"))


class _Drawn:
    """What a `Panel.draw` or `Menu.draw` is given as ``self``."""

    def __init__(self, widgets: list[Widget], open_all: bool) -> None:
        self.layout = RecordingLayout(widgets, open_all=open_all)


def record(draw: Any, owner: Any = None, open_all: bool = False) -> list[Widget]:
    """Run ``draw(self, context)`` with a recording layout; ``owner`` stands in for ``self``
    (an operator's properties), else a bare object with a layout."""
    import bpy

    widgets: list[Widget] = []
    me = owner if owner is not None else _Drawn(widgets, open_all)
    if owner is not None:
        owner.layout = RecordingLayout(widgets, open_all=open_all)
    draw(me, bpy.context)
    return widgets


class OperatorDefaults:
    """An operator's properties at their defaults, as its redo panel first shows them, or at
    the ``values`` given: the ``bl_rna`` of the operator type, each property readable as an
    attribute."""

    def __init__(self, rna: Any, **values: Any) -> None:
        self.bl_rna = rna
        self.layout: RecordingLayout | None = None
        self._values = values  # set in the redo panel, as a user would

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        if name in self._values:
            return self._values[name]
        prop = self.bl_rna.properties[name]
        if getattr(prop, "is_array", False):
            return tuple(prop.default_array)
        return prop.default


# ---------------------------------------------------------------------------------------------
# Drawing, in the colours of Blender's default dark theme

SCALE = 1.25  # Blender's UI at a resolution scale of 1.25, as on a laptop screen
ROW = round(20 * SCALE)
GAP = round(2 * SCALE)
PAD = round(10 * SCALE)
BG, PANEL, HEADER = (48, 48, 48), (56, 56, 56), (64, 64, 64)
TEXT, LABEL, DIM = (230, 230, 230), (200, 200, 200), (120, 120, 120)
FIELD, MENU, TEXTBOX, BUTTON = (84, 84, 84), (40, 40, 40), (29, 29, 29), (84, 84, 84)
SELECTED = (71, 114, 179)


def font(size: float = 11 * SCALE) -> ImageFont.FreeTypeFont | ImageFont.ImageFont:
    return ImageFont.load_default(size=round(size))


def _fit(d: ImageDraw.ImageDraw, text: str, width: float) -> str:
    if d.textlength(text, font=font()) <= width:
        return text
    while text and d.textlength(text + "…", font=font()) > width:
        text = text[:-1]
    return text + "…"


def _value_text(data: Any, name: str) -> str:
    prop = data.bl_rna.properties[name]
    value = getattr(data, name)
    if prop.type == "ENUM":
        items = {i.identifier: i.name for i in prop.enum_items}
        return items.get(value, str(value))
    if prop.type == "POINTER":
        return getattr(value, "name", "") if value is not None else ""
    if prop.type == "FLOAT" and prop.unit == "LENGTH":  # as Blender's metric units show it
        return "0 m" if value == 0 else f"{value * 1000:.3g} mm" if abs(value) < 0.1 \
            else f"{value:.3g} m"
    if prop.type == "FLOAT":
        text = f"{value:.{min(prop.precision, 4)}f}"
        return text + {"PERCENTAGE": " %", "ANGLE": "°", "PIXEL": " px"}.get(prop.subtype, "")
    if prop.type == "STRING":
        return str(value).splitlines()[0] if value else ""
    return str(value)


def _box(d: ImageDraw.ImageDraw, x0: float, y0: float, x1: float, y1: float, fill: Any,
         dim: bool) -> None:
    if dim:
        fill = tuple(int(c * 0.7 + BG[i] * 0.3) for i, c in enumerate(fill))
    d.rounded_rectangle([x0, y0, x1, y1], radius=round(3 * SCALE), fill=fill)


def _text(d: ImageDraw.ImageDraw, xy: tuple[float, float], text: str, dim: bool,
          anchor: str = "lm", color: Any = TEXT) -> None:
    d.text(xy, text, fill=DIM if dim else color, font=font(), anchor=anchor)


def _prop(d: ImageDraw.ImageDraw, w: Widget, x: float, y: float, width: float) -> float:
    prop = w.data.bl_rna.properties[w.name]
    label = w.text if w.text is not None else prop.name
    h = ROW * w.scale_y
    cy = y + h / 2
    if w.split:
        lx = x + 0.4 * width
        if prop.type != "BOOLEAN":
            _text(d, (lx - 8, cy), _fit(d, label, 0.4 * width - 12), w.dim, "rm", LABEL)
        x, width = lx, 0.6 * width
        shown = "" if prop.type == "BOOLEAN" else None
    else:
        shown = label
    if prop.type == "BOOLEAN":
        s = ROW * 0.62
        on = bool(getattr(w.data, w.name))
        _box(d, x, cy - s / 2, x + s, cy + s / 2, SELECTED if on else FIELD, w.dim)
        if on:
            tick = [(x + s * 0.22, cy), (x + s * 0.42, cy + s * 0.22),
                    (x + s * 0.78, cy - s * 0.25)]
            d.line(tick, fill=DIM if w.dim else TEXT, width=2)
        _text(d, (x + s + 6, cy), _fit(d, label, width - s - 6), w.dim)
        return h
    if prop.type == "ENUM" and w.expand:
        items = list(prop.enum_items)
        cell = width / len(items)
        for i, item in enumerate(items):
            sel = item.identifier == getattr(w.data, w.name)
            _box(d, x + i * cell, y + 1, x + (i + 1) * cell - 1, y + h - 1,
                 SELECTED if sel else FIELD, w.dim)
            _text(d, (x + (i + 0.5) * cell, cy), _fit(d, item.name, cell - 6), w.dim, "mm")
        return h
    if prop.type == "FLOAT" and prop.subtype in {"COLOR", "COLOR_GAMMA"}:
        rgb = tuple(getattr(w.data, w.name))[:3]
        if prop.subtype == "COLOR":  # scene-linear: shown as the display shows it
            rgb = tuple(c * 12.92 if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055
                        for c in rgb)
        fill = tuple(round(max(0.0, min(1.0, c)) * 255) for c in rgb)
        _box(d, x, y + 1, x + width, y + h - 1, fill, w.dim)
        return h
    value = _value_text(w.data, w.name)
    if prop.type == "ENUM":
        _box(d, x, y + 1, x + width, y + h - 1, MENU, w.dim)
        text = value if shown is None else f"{shown}: {value}"
        _text(d, (x + 8, cy), _fit(d, text, width - 28), w.dim)
        ax = x + width - 12
        d.polygon([(ax - 4, cy - 2), (ax + 4, cy - 2), (ax, cy + 3)], fill=DIM if w.dim else TEXT)
        return h
    if prop.type in {"STRING", "POINTER"}:
        _box(d, x, y + 1, x + width, y + h - 1, TEXTBOX if prop.type == "STRING" else MENU,
             w.dim)
        text = value if shown is None else f"{shown}: {value}"
        _text(d, (x + 8, cy), _fit(d, text, width - 16), w.dim)
        return h
    # A number field: the value centred (its label inside when not split).
    _box(d, x, y + 1, x + width, y + h - 1, FIELD, w.dim)
    if prop.subtype == "FACTOR" and prop.type == "FLOAT" and prop.soft_max > prop.soft_min:
        # A slider, filled over its soft range as Blender fills it.
        t = (getattr(w.data, w.name) - prop.soft_min) / (prop.soft_max - prop.soft_min)
        t = max(0.0, min(1.0, t))
        _box(d, x, y + 1, x + max(6.0, width * t), y + h - 1, SELECTED, w.dim)
    if shown is None:
        _text(d, (x + width / 2, cy), value, w.dim, "mm")
    else:
        _text(d, (x + 8, cy), _fit(d, shown, width - 60), w.dim)
        _text(d, (x + width - 8, cy), value, w.dim, "rm")
    return h


def draw_widgets(d: ImageDraw.ImageDraw, widgets: list[Widget], x: float, y: float,
                 width: float) -> float:
    """Draw ``widgets`` stacked from ``y``; returns the y under the last."""
    for w in widgets:
        if w.kind == "group" and w.horizontal and len(w.children) > 1:
            cell = width / len(w.children)
            tall = max(draw_widgets(d, [c], x + i * cell, y, cell - GAP) - y
                       for i, c in enumerate(w.children))
            y += tall
        elif w.kind == "group":
            y = draw_widgets(d, w.children, x, y, width)
        elif w.kind == "prop":
            y += _prop(d, w, x, y, width) + GAP
        elif w.kind == "operator":
            h = ROW * w.scale_y
            _box(d, x, y + 1, x + width, y + h - 1, BUTTON, w.dim)
            _text(d, (x + width / 2, y + h / 2), w.text or "", w.dim, "mm")
            y += h + GAP
        elif w.kind == "label":
            _text(d, (x, y + ROW / 2), _fit(d, w.text or "", width), w.dim)
            y += ROW + GAP
        elif w.kind == "separator":
            y += ROW * 0.4
        elif w.kind == "panel":
            _box(d, x - PAD / 2, y, x + width + PAD / 2, y + ROW, HEADER, False)
            tx = x + 2
            if w.closed:
                d.polygon([(tx, y + ROW / 2 - 5), (tx, y + ROW / 2 + 5), (tx + 7, y + ROW / 2)],
                          fill=LABEL)
            else:
                d.polygon([(tx - 1, y + ROW / 2 - 3), (tx + 9, y + ROW / 2 - 3),
                           (tx + 4, y + ROW / 2 + 4)], fill=LABEL)
            _text(d, (tx + 16, y + ROW / 2), w.text or "", False)
            y += ROW + GAP
            if not w.closed:
                y = draw_widgets(d, w.children, x + PAD / 2, y + GAP, width - PAD) + GAP
    return y


def picture(path: Path, panels: list[tuple[str, list[Widget]]], width: int = 380,
            caption: str = "") -> None:
    """Panels (title, widgets) one under another, as a region of the given width shows them."""
    canvas = Image.new("RGB", (width, 4000), BG)
    d = ImageDraw.Draw(canvas)
    y = float(PAD)
    for title, widgets in panels:
        top = y
        body = top + ROW + 2 * GAP
        # Measure first (on a scratch canvas), then draw the panel's box and its widgets.
        scratch = ImageDraw.Draw(Image.new("RGB", (width, 4000)))
        y = draw_widgets(scratch, widgets, PAD * 2, body, width - 4 * PAD) + PAD
        d.rounded_rectangle([PAD / 2, top, width - PAD / 2, y], radius=5, fill=PANEL)
        d.rounded_rectangle([PAD / 2, top, width - PAD / 2, top + ROW + GAP], radius=5,
                            fill=HEADER)
        d.polygon([(PAD, top + ROW / 2 - 2), (PAD + 10, top + ROW / 2 - 2),
                   (PAD + 5, top + ROW / 2 + 5)], fill=LABEL)
        d.text((PAD + 18, top + ROW / 2 + 1), title, fill=TEXT, font=font(12 * SCALE),
               anchor="lm")
        draw_widgets(d, widgets, PAD * 2, body, width - 4 * PAD)
        y += GAP * 2
    if caption:
        d.text((PAD, y + 4), caption, fill=DIM, font=font(10 * SCALE), anchor="lt")
        y += ROW
    path.parent.mkdir(parents=True, exist_ok=True)
    canvas.crop((0, 0, width, int(y + PAD / 2))).save(path, optimize=True)


def menu_picture(path: Path, title: str, entries: list[Widget]) -> None:
    """A drop-down menu's entries under its title, greyed where the entry's poll fails."""
    width = 300
    rows = [e for e in entries if e.kind in {"operator", "separator"}]
    height = int(ROW * 1.4 + sum(ROW if e.kind == "operator" else ROW * 0.4 for e in rows)
                 + PAD * 2)
    img = Image.new("RGB", (width, height), BG)
    d = ImageDraw.Draw(img)
    d.rectangle([0, 0, width, ROW * 1.4], fill=HEADER)
    d.text((PAD, ROW * 0.7), title, fill=TEXT, font=font(12 * SCALE), anchor="lm")
    y = ROW * 1.4 + PAD
    d.rounded_rectangle([2, y - PAD / 2, width - 3, height - 3], radius=5, fill=MENU)
    for e in rows:
        if e.kind == "separator":
            d.line([(PAD, y + ROW * 0.2), (width - PAD, y + ROW * 0.2)], fill=FIELD)
            y += ROW * 0.4
            continue
        _text(d, (PAD * 2.5, y + ROW / 2), e.text or "", e.dim)
        y += ROW
    path.parent.mkdir(parents=True, exist_ok=True)
    img.save(path, optimize=True)


# ---------------------------------------------------------------------------------------------
# The scene and the pictures


def sidebar(open_all: bool = False) -> list[tuple[str, list[Widget]]]:
    """Every registered panel of the Knitwear sidebar tab whose poll passes, in registration
    order, with its widgets."""
    import bpy

    panels = []
    for cls in bpy.types.Panel.__subclasses__():
        if getattr(cls, "bl_category", "") != "Knitwear" or cls.bl_region_type != "UI":
            continue
        if hasattr(cls, "poll") and not cls.poll(bpy.context):
            continue
        panels.append((cls.bl_label, record(cls.draw, open_all=open_all)))
    return panels


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--zip", type=Path, default=None, help="extension zip to install")
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "ui")
    args = parser.parse_args()
    start_blender(args.zip)
    import bpy
    from bl_ext.user_default import knitwear as addon

    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    bpy.ops.surface.primitive_nurbs_surface_surface_add(location=(0, 0, 0))
    source = bpy.context.active_object
    source.scale = (0.1, 0.1, 0.1)  # 40 x 40 cm: a first knit of a few thousand stitches
    bpy.context.view_layer.update()
    picture(args.out / "sidebar_source.png", sidebar(),
            caption="a NURBS surface selected (N > Knitwear)")
    # Every entry the extension appended to the Object menu, in the order Blender draws them.
    object_menu = [w for fn in bpy.types.VIEW3D_MT_object.draw._draw_funcs
                   if fn.__module__.startswith(addon.__name__) for w in record(fn)]
    menu_picture(args.out / "object_menu.png", "Object  (the add-on's entries, at its foot)",
                 object_menu)

    result = bpy.ops.object.knitwear_knit()
    if result != {"FINISHED"}:
        sys.exit(f"ui_pictures: knitting the surface failed: {result}")
    knit = bpy.context.active_object
    picture(args.out / "sidebar_knit.png", sidebar(),
            caption=f"the knit selected: {knit.name}")
    picture(args.out / "sidebar_knit_open.png", sidebar(open_all=True),
            caption="every section open")
    op = bpy.types.OBJECT_OT_knitwear_knit
    defaults = OperatorDefaults(bpy.ops.object.knitwear_knit.get_rna_type())
    picture(args.out / "redo_knit.png", [(op.bl_label, record(op.draw, owner=defaults))],
            caption="the redo panel (bottom left of the viewport) after a knit")
    # The tutorial's scarf (docs/first-knit.md, step 4).
    scarf = OperatorDefaults(bpy.ops.object.knitwear_knit.get_rna_type(), pattern="rib_2x2",
                             color_mode="STRIPES", color_count=2, stripe_height=6)
    picture(args.out / "redo_scarf.png", [(op.bl_label, record(op.draw, owner=scarf))],
            caption="the redo panel set as in the first-knit tutorial")
    print(f"UI pictures in {args.out}")


if __name__ == "__main__":
    main()
