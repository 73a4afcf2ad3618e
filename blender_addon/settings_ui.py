"""Drawing the knit settings: shared by the sidebar panel and the operator's redo panel, so
both show the same sections in the same order."""

import bpy

from .properties import CUSTOM_PATTERN, FILE_PATTERN, MAX_COLORS


def _pattern(layout: bpy.types.UILayout, settings: bpy.types.AnyType) -> None:
    layout.prop(settings, "pattern")
    if settings.pattern == CUSTOM_PATTERN:
        layout.prop(settings, "pattern_chart")
    elif settings.pattern == FILE_PATTERN:
        layout.prop_search(settings, "pattern_text", bpy.data, "texts")
        layout.prop(settings, "pattern_file")


def _size(layout: bpy.types.UILayout, settings: bpy.types.AnyType) -> None:
    layout.row().prop(settings, "size_mode", expand=True)
    col = layout.column(align=True)
    if settings.size_mode == "GAUGE":
        col.prop(settings, "gauge_stitches")
        col.prop(settings, "gauge_rows")
    else:
        col.prop(settings, "courses")
        col.prop(settings, "wales")
    layout.prop(settings, "direction")
    layout.prop(settings, "live_loops")


def _yarn(layout: bpy.types.UILayout, settings: bpy.types.AnyType) -> None:
    layout.prop(settings, "yarn_radius")
    layout.prop(settings, "fluffiness")
    col = layout.column(align=True)
    col.prop(settings, "ring_segments")
    col.prop(settings, "plies")
    col.prop(settings, "samples_per_loop")
    layout.prop(settings, "tension")
    layout.prop(settings, "kappa")
    layout.prop(settings, "seed")


def _colour(layout: bpy.types.UILayout, settings: bpy.types.AnyType) -> None:
    mode = settings.color_mode
    layout.prop(settings, "color_mode")
    shown = 0
    if mode == "SINGLE":
        shown = 1
    elif mode == "STRIPES":
        layout.prop(settings, "color_count")
        layout.prop(settings, "stripe_height")
        shown = settings.color_count
    elif mode == "CHART":
        layout.prop(settings, "color_chart")
        shown = MAX_COLORS
    elif mode == "IMAGE":
        layout.prop_search(settings, "color_image_name", bpy.data, "images")
    col = layout.column(align=True)
    for i in range(shown):
        col.prop(settings, f"color_{i + 1}")
    layout.prop(settings, "color_variation")


def _detail(layout: bpy.types.UILayout, settings: bpy.types.AnyType) -> None:
    layout.row().prop(settings, "detail_mode", expand=True)
    if settings.detail_mode != "AUTO":
        return
    col = layout.column(align=True)
    col.prop(settings, "detail_full_px")
    col.prop(settings, "detail_mid_px")
    col.prop(settings, "detail_texture_px")
    layout.prop(settings, "frustum_margin")
    layout.prop(settings, "cull_back_faces")
    layout.prop(settings, "cull_hidden")
    sub = layout.column()
    sub.active = settings.cull_hidden
    sub.prop(settings, "cull_hidden_samples")
    sub.prop(settings, "cull_hidden_min_triangles")


_SECTIONS = (
    ("pattern", "Pattern", _pattern, False),
    ("size", "Size", _size, False),
    ("yarn", "Yarn", _yarn, True),
    ("colour", "Colour", _colour, False),
    ("detail", "Detail", _detail, True),
)


def draw_settings(layout: bpy.types.UILayout, settings: bpy.types.AnyType, prefix: str) -> None:
    """Draw ``settings`` (the stored settings or an operator) in collapsible sections.

    ``prefix`` keeps the sections' open/closed state apart between the places they appear.
    """
    layout.use_property_split = True
    layout.use_property_decorate = False
    for key, title, draw, closed in _SECTIONS:
        header, body = layout.panel(f"{prefix}_{key}", default_closed=closed)
        header.label(text=title)
        if body is not None:
            draw(body, settings)
