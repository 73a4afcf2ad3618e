"""Knit settings: one definition shared by the stored settings and the operator.

`KnitSettingsMixin` declares every setting once. `KnitwearSettings` (``obj.knitwear``) stores
them on the knit object so Update can rebuild it, and the Knit operator inherits the same
annotations so its redo panel edits exactly the same values. Lengths are stored in Blender
units; the UI shows them in the scene's unit system. Gauge is a knitter's gauge in stitches
and rows per 10 cm, converted to scene units with the scene's unit scale (1 unit = 1 m x
``unit_settings.scale_length``).
"""

import bpy
import knitwear
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    FloatVectorProperty,
    IntProperty,
    IntVectorProperty,
    PointerProperty,
    StringProperty,
)

from . import poll_knit_source
from .core_settings import from_core
from .settings_schema import SettingsSchema

#: How many yarn colours the palette offers (``color_1`` .. ``color_4``).
MAX_COLORS = 4

CUSTOM_PATTERN = "CUSTOM"
FILE_PATTERN = "FILE"

# Display names and tooltips for the core's presets. A preset the core adds later still shows
# up (title-cased) because the list itself comes from `knitwear.Pattern.presets()`.
_PRESET_LABELS: dict[str, tuple[str, str]] = {
    "stockinette": ("Stockinette", "Knit on the right side: smooth V columns"),
    "reverse_stockinette": ("Reverse Stockinette", "Purl on the right side: horizontal bumps"),
    "garter": ("Garter", "Alternate knit and purl rows: ridged and reversible"),
    "rib_1x1": ("1x1 Rib", "Knit 1, purl 1 columns"),
    "rib_2x2": ("2x2 Rib", "Knit 2, purl 2 columns"),
    "seed": ("Seed", "Knit 1, purl 1, offset every row: pebbly texture"),
    "moss": ("Moss", "Knit 1, purl 1, offset every second row"),
    "basketweave": ("Basketweave", "Alternating blocks of knit and purl"),
    "twisted_rib": ("Twisted Rib", "1x1 rib with the knits worked through the back loop"),
    "cable_c4": ("C4 Cable", "4-stitch rope cables (C4B every 6 rows) on purl ground"),
    "cable_c6": ("C6 Cable", "6-stitch rope cables (C6B every 8 rows) on purl ground"),
    "horseshoe_cable": ("Horseshoe Cable", "16-stitch panel: 3/3 right and left crosses"),
    "honeycomb_cable": ("Honeycomb Cable", "2/2 crosses meeting and parting in a honeycomb"),
    "mock_cable_rib": ("Mock Cable Rib", "2x2 rib with 1/1 right twists: cables without a needle"),
    "twisted_cable_rib": ("Twisted Cable Rib", "Little 1/1 left twists between purls"),
    "diamond": ("Diamond Brocade", "Purl diamonds on stockinette"),
    "chevron": ("Chevron", "Purl zigzags on stockinette"),
    "feather_and_fan": ("Feather and Fan", "Old shale lace: scallops of yarn-overs"),
    "eyelet_rows": ("Eyelet Rows", "Rows of yarn-over holes on stockinette"),
    "lace_diamond": ("Lace Diamond", "Yarn-overs with paired decreases in a diamond"),
    "bobbles": ("Bobbles", "Staggered bobbles on stockinette"),
    "linen_stitch": ("Linen Stitch", "Slipped stitches with little bars of yarn in front"),
    "fair_isle": (
        "Fair Isle",
        "Stockinette in the round: give it colours with Colour > Chart (e.g. "
        "knitwear.ColorPattern.preset('fair_isle_band', ...))",
    ),
}


def _pattern_items() -> list[tuple[str, str, str]]:
    items = []
    for name in knitwear.Pattern.presets():
        label, tip = _PRESET_LABELS.get(name, (name.replace("_", " ").title(), ""))
        items.append((name, label, tip))
    items.append((CUSTOM_PATTERN, "Custom Chart", "The stitch chart or Knitspeak typed in Chart"))
    items.append(
        (
            FILE_PATTERN,
            "From File",
            "A Knitspeak or chart file, or a Blender Text (Pattern Text, which wins)",
        )
    )
    return items


# Built once at import: an EnumProperty keeps a reference to a static list, whereas a callback
# would have to keep its result alive itself (Blender does not copy the strings).
PATTERN_ITEMS = _pattern_items()
DEFAULT_PATTERN = (
    "stockinette" if any(i[0] == "stockinette" for i in PATTERN_ITEMS) else (PATTERN_ITEMS[0][0])
)

SIZE_MODE_ITEMS = [
    ("GAUGE", "Gauge", "Stitch size from a knitter's gauge: stitches and rows per 10 cm"),
    ("COUNTS", "Counts", "A fixed number of courses (rows) and wales (columns) over the surface"),
]

DIRECTION_ITEMS = [
    (
        "AUTO",
        "Auto",
        "Courses go round a surface that is closed in one direction, as when "
        "knitting in the round; otherwise along U",
    ),
    ("U", "Along U", "Courses (the yarn's rows) run along the surface's U direction"),
    ("V", "Along V", "Courses (the yarn's rows) run along the surface's V direction"),
]

DETAIL_MODE_ITEMS = [
    (
        "AUTO",
        "Auto",
        "Model each stitch as finely as the scene camera sees it: full quality "
        "near the camera, fewer segments further away, plain tubes in the distance, the "
        "knitwear texture on the source where stitches are a few pixels; stitches outside the "
        "camera's view are not built. Without a scene camera, every stitch is full quality",
    ),
    (
        "FULL",
        "Full",
        "Every stitch at the quality set in Yarn (ring segments, samples per "
        "loop), whatever the camera sees",
    ),
]

COLOR_MODE_ITEMS = [
    ("SINGLE", "Single", "One yarn colour"),
    ("STRIPES", "Stripes", "Horizontal stripes cycling through the yarn colours"),
    ("CHART", "Chart", "A colour chart of yarn colour numbers (colourwork)"),
    ("IMAGE", "Image", "Each stitch takes the colour of an image at its (u,v)"),
]

_DEFAULT_COLORS = (
    (0.50, 0.05, 0.05),  # cranberry
    (0.80, 0.75, 0.65),  # oatmeal
    (0.03, 0.10, 0.30),  # navy
    (0.25, 0.40, 0.10),  # moss green
)


def _color_prop(index: int) -> FloatVectorProperty:
    return FloatVectorProperty(
        name=f"Colour {index + 1}",
        description=f"Yarn colour {index + 1} (linear RGB); colour number {index} in charts",
        subtype="COLOR",
        size=3,
        min=0.0,
        max=1.0,
        default=_DEFAULT_COLORS[index],
    )


class KnitSettingsMixin:
    """Every knit setting, declared once (see the module docstring)."""

    # -- Pattern
    pattern: EnumProperty(
        name="Pattern",
        description="Stitch pattern (knit, purl, cables, lace, bobbles...), repeated over the "
        "surface",
        items=PATTERN_ITEMS,
        default=DEFAULT_PATTERN,
    )
    pattern_chart: StringProperty(
        name="Chart",
        description="Custom stitch chart, used when Pattern is Custom Chart. One line per row "
        "(top line = top row); rows may also be separated with ';'. "
        "k = knit, p = purl (also | v for knit, - . for purl), O yo, / k2tog, \\ ssk, "
        "^ cdd, B bobble, Q k tbl; other symbols need a legend row such as 'X = 2/2 RC' "
        "(a cable is a run of its symbol over its columns: XXXX). Or Knitspeak rows: "
        "'Row 1 (RS): P2, *2/2 RC, p2; rep from *. Row 2: K2, *p4, k2; rep from *.'",
        default="kkpp;kkpp;pppp;kkkk",
    )
    pattern_file: StringProperty(
        name="Pattern File",
        description="A text file of Knitspeak rows or a chart with its legend, used when "
        "Pattern is From File (Pattern Text, if set, is used instead)",
        default="",
        subtype="FILE_PATH",
    )
    pattern_text: StringProperty(
        name="Pattern Text",
        description="A Blender Text (Text Editor) holding Knitspeak rows or a chart with its "
        "legend, used when Pattern is From File",
        default="",
    )
    # -- Size
    size_mode: EnumProperty(
        name="Size",
        description="How the stitch size is given",
        items=SIZE_MODE_ITEMS,
        default="GAUGE",
    )
    gauge_stitches: FloatProperty(
        **from_core(
            "gauge_stitches",
            soft_min=2.0,
            soft_max=60.0,
            precision=1,
        )
    )
    gauge_rows: FloatProperty(**from_core("gauge_rows", soft_min=2.0, soft_max=80.0, precision=1))
    # The counts' hard maximum is the core's (a million a direction), far beyond what fits in
    # memory: the core's budget check gives a precise error (with the size it would need).
    courses: IntProperty(**from_core("courses", soft_max=2000))
    wales: IntProperty(**from_core("wales", soft_max=2000))
    direction: EnumProperty(
        name="Course Direction",
        description="Which surface direction the courses (rows of stitches) run along",
        items=DIRECTION_ITEMS,
        default="AUTO",
    )
    # -- Yarn
    yarn_radius: FloatProperty(
        **from_core(
            "yarn_radius",
            soft_max=0.01,
            subtype="DISTANCE",
            unit="LENGTH",
            precision=4,
        )
    )
    fluffiness: FloatProperty(**from_core("fluffiness", soft_max=1.0, subtype="FACTOR"))
    ring_segments: IntProperty(**from_core("ring_segments", soft_max=16))
    plies: IntProperty(**from_core("plies"))
    live_loops: BoolProperty(**from_core("live_loops"))
    samples_per_loop: IntProperty(**from_core("samples_per_loop", soft_max=48))
    tension: FloatProperty(**from_core("tension", subtype="FACTOR"))
    kappa: FloatProperty(**from_core("kappa", step=0.05, precision=4))
    seed: IntProperty(**from_core("seed"))
    # -- Colour
    color_mode: EnumProperty(
        name="Colour",
        description="How yarn colours are laid out",
        items=COLOR_MODE_ITEMS,
        default="SINGLE",
    )
    color_count: IntProperty(
        name="Colours",
        description="How many of the yarn colours stripes use",
        default=2,
        min=1,
        max=MAX_COLORS,
    )
    color_1: _color_prop(0)
    color_2: _color_prop(1)
    color_3: _color_prop(2)
    color_4: _color_prop(3)
    color_chart: StringProperty(
        name="Colour Chart",
        description="Colourwork chart of colour numbers (0 = Colour 1 .. 3 = Colour 4), one "
        "line per row (top line = top row); rows may also be separated with ';'. Or the name "
        "of a colourwork chart: fair_isle_band. A colour skipped between two of its stitches "
        "floats behind them, as in stranded knitting",
        default="0001;0010;0100;1000",
    )
    stripe_height: IntProperty(
        name="Stripe Height",
        description="Rows (courses) per stripe",
        default=2,
        min=1,
        soft_max=50,
        max=100_000,
    )
    color_image_name: StringProperty(
        name="Image",
        description="Image whose colours the stitches take (looked up at each stitch's "
        "(u,v) in the surface's parameter space or UV map)",
        default="",
    )
    color_variation: FloatProperty(**from_core("color_variation", subtype="FACTOR"))
    # -- Detail (camera-driven level of detail and culling)
    detail_mode: EnumProperty(
        name="Detail",
        description="How finely stitches are modelled",
        items=DETAIL_MODE_ITEMS,
        default="AUTO",
    )
    detail_full_px: FloatProperty(
        **from_core(
            "detail_full_px",
            soft_max=200.0,
            precision=1,
            subtype="PIXEL",
        )
    )
    detail_mid_px: FloatProperty(
        **from_core(
            "detail_mid_px",
            soft_max=100.0,
            precision=1,
            subtype="PIXEL",
        )
    )
    detail_texture_px: FloatProperty(
        **from_core(
            "detail_texture_px",
            soft_max=20.0,
            precision=1,
            subtype="PIXEL",
        )
    )
    frustum_margin: FloatProperty(
        **from_core(
            "frustum_margin",
            soft_min=0.0,
            soft_max=1.0,
            subtype="FACTOR",
        )
    )
    cull_back_faces: BoolProperty(**from_core("cull_back_faces"))
    cull_hidden: BoolProperty(**from_core("cull_hidden"))
    cull_hidden_samples: IntProperty(**from_core("cull_hidden_samples"))
    cull_hidden_min_triangles: IntProperty(
        **from_core("cull_hidden_min_triangles", soft_max=20_000_000, step=100_000)
    )


class KnitwearSettings(KnitSettingsMixin, bpy.types.PropertyGroup):
    """``obj.knitwear``: whether an object is a knit, what it was knitted from, and how."""

    is_knit: BoolProperty(
        name="Is Knit",
        description="This object's mesh was made by Knitwear and can be updated",
        default=False,
    )
    source: PointerProperty(
        name="Source",
        description="The NURBS surface or UV-mapped mesh this knit follows",
        type=bpy.types.Object,
        poll=poll_knit_source,
    )
    follow_source: BoolProperty(
        name="Follow Source",
        description="On every frame, move the yarn with its source surface as it deforms "
        "(armature, shape keys, modifiers, animated points): stitches stay bound to the "
        "surface and the mesh topology never changes",
        default=True,
    )
    save_as_recipe: BoolProperty(
        name="Save as Recipe",
        description="Save the knit's source, settings and pins but not its yarn, which is "
        "rebuilt when the file opens (a much smaller .blend; needs the Knitwear extension to "
        "show the knit, and rebuilds it in the pose its source has then)",
        default=False,
    )
    # Pinned at knit time (and by Update) so that every later pose, and a farm machine that
    # opens the file at any frame, rebuilds exactly this knit's topology and loop shapes.
    bound_counts: IntVectorProperty(
        name="Bound Counts", description="Courses and wales at knit time", size=2, min=0
    )
    bound_yarn_radius: FloatProperty(
        name="Bound Yarn Radius", description="Yarn radius at knit time", min=0.0
    )
    bound_stitch_size: FloatVectorProperty(
        name="Bound Stitch Size",
        description="Stitch width and height measured at knit time",
        size=2,
        min=0.0,
    )
    bound_samples: IntVectorProperty(
        name="Bound Samples",
        description="Grid samples the NURBS source was tessellated with at knit time",
        size=2,
        min=0,
    )


#: The knit settings as the scripting API sees them.
KNIT_SETTINGS = SettingsSchema("knit", KnitSettingsMixin)
#: The settings' names, in declaration order (the scripting API's keyword arguments).
SETTING_NAMES: tuple[str, ...] = KNIT_SETTINGS.names


def register() -> None:
    bpy.utils.register_class(KnitwearSettings)
    bpy.types.Object.knitwear = PointerProperty(type=KnitwearSettings)


def unregister() -> None:
    del bpy.types.Object.knitwear
    bpy.utils.unregister_class(KnitwearSettings)
