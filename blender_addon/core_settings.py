"""The core's settings table (`knitwear.settings()`, declared once in `src/settings.rs`) as
keyword arguments of bpy properties: each knit property takes its label, tooltip, default
and hard range from there, and adds only what the UI alone knows (soft range, subtype,
precision, step). Where the add-on's default differs from the core's, the table says so and
why (``addon_why``).
"""

from typing import Any

import knitwear

#: The tables of a knit's and a plush's settings, by Blender property name.
BY_PROPERTY: dict[str, dict[str, dict[str, Any]]] = {
    kind: {s["property"]: s for s in knitwear.settings(kind)} for kind in ("knit", "plush")
}


def from_core(prop: str, kind: str = "knit", **ui: Any) -> dict[str, Any]:
    """Keyword arguments of the bpy property ``prop`` of a ``kind`` ("knit", "plush"): the
    table's label, doc, add-on default and range, then ``ui`` (which may not override
    them)."""
    s = BY_PROPERTY[kind][prop]
    kw: dict[str, Any] = {
        "name": s["label"],
        "description": s["doc"],
        "default": s["addon_default"],
    }
    if s["type"] != "bool":
        for end in ("min", "max"):
            if s[end] is not None:
                kw[end] = s[end]
    clash = sorted(set(ui) & set(kw))
    if clash:
        raise TypeError(f"{prop}: {', '.join(clash)} come from the core's settings table")
    return kw | ui
