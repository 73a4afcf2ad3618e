"""Plush settings: one definition shared by the stored settings (``obj.knitwear_plush``) and
the Plush operator's redo panel, as the knit's `properties` module does for knits."""

import math

import bpy
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

from ..settings_schema import SettingsSchema

SIZE_MODE_ITEMS = [
    ("GAUGE", "Gauge", "Pile density from a gauge: wales and courses per 10 cm"),
    ("COUNTS", "Counts", "A fixed number of courses and wales over the whole surface"),
]
COLOR_MODE_ITEMS = [
    ("SINGLE", "Single", "One pile colour"),
    ("STRIPES", "Stripes", "Stripes of courses cycling through the colours"),
    ("IMAGE", "Image", "Each pile takes the colour of an image at its (u,v)"),
]
MAX_COLORS = 4
_DEFAULT_COLORS = (
    (0.30, 0.012, 0.03),  # deep red velvet
    (0.60, 0.50, 0.35),  # camel
    (0.02, 0.05, 0.25),  # navy
    (0.05, 0.20, 0.06),  # bottle green
)


def _color_prop(index: int) -> FloatVectorProperty:
    return FloatVectorProperty(
        name=f"Colour {index + 1}",
        description="Pile colour (linear RGB); the tip is lighter and the root darker",
        subtype="COLOR",
        size=3,
        min=0.0,
        max=1.0,
        default=_DEFAULT_COLORS[index],
    )


class PlushSettingsMixin:
    """Every plush setting, declared once: stored on the object and edited in the redo panel."""

    size_mode: EnumProperty(name="Size", items=SIZE_MODE_ITEMS, default="GAUGE")
    gauge_stitches: FloatProperty(
        name="Wales / 10 cm",
        description="Stitches along a course per 10 cm (the paper's fabric: about 48)",
        default=48.0,
        min=0.1,
        soft_max=200.0,
    )
    gauge_rows: FloatProperty(
        name="Courses / 10 cm",
        description="Courses (rows) per 10 cm along a wale",
        default=64.0,
        min=0.1,
        soft_max=200.0,
    )
    courses: IntProperty(
        name="Courses", description="Courses over the whole surface (along v)",
        default=96, min=1, max=1_000_000, soft_max=2000,
    )
    wales: IntProperty(
        name="Wales", description="Wales over the whole surface (along u)",
        default=64, min=1, max=1_000_000, soft_max=2000,
    )
    piles_per_stitch: IntProperty(
        name="Piles per Stitch",
        description="Piles grown from each stitch, on a near-square sub-grid (4: 2x2)",
        default=1, min=1, max=64,
    )
    pile_length: FloatProperty(
        name="Pile Length",
        description="Length of a pile; 0 = automatic (2.5 stitch widths)",
        default=0.0, min=0.0, soft_max=0.1, subtype="DISTANCE", unit="LENGTH", precision=4,
    )
    pile_radius: FloatProperty(
        name="Pile Radius",
        description="Half width of a slice; 0 = automatic (0.6 pile spacings)",
        default=0.0, min=0.0, soft_max=0.05, subtype="DISTANCE", unit="LENGTH", precision=4,
    )
    slices: IntProperty(
        name="Slices", description="Quads per pile", default=8, min=1, max=64,
    )
    lean_angle: FloatProperty(
        name="Lean",
        description="Angle of the pile's nominal direction from the surface normal",
        default=math.radians(30.0), min=0.0, max=math.radians(89.0), subtype="ANGLE",
    )
    lean_direction: FloatProperty(
        name="Lean Direction",
        description="Azimuth of the lean in the fabric plane, from the course (u) towards the "
        "wale (v)",
        default=math.radians(-90.0), min=-2 * math.pi, max=2 * math.pi, subtype="ANGLE",
    )
    theta_max: FloatProperty(
        name="Noise Angle",
        description="Largest deviation of a pile from the nominal direction (theta_max, below "
        "45 degrees)",
        default=math.radians(20.0), min=0.0, max=math.radians(44.9), subtype="ANGLE",
    )
    noise_scales: StringProperty(
        name="Noise Scales",
        description="Sampling coefficients k of the fractal noise, e.g. '1 2 4 8' (larger k: "
        "coarser features, more weight)",
        default="1 2 4 8",
    )
    seed: IntProperty(
        name="Seed", description="Random seed of the noise: same seed, same plush",
        default=0, min=0,
    )
    color_mode: EnumProperty(name="Colour", items=COLOR_MODE_ITEMS, default="SINGLE")
    color_1: _color_prop(0)
    color_2: _color_prop(1)
    color_3: _color_prop(2)
    color_4: _color_prop(3)
    color_count: IntProperty(
        name="Colours", description="How many colours the stripes cycle through",
        default=2, min=1, max=MAX_COLORS,
    )
    stripe_height: IntProperty(
        name="Stripe Height", description="Courses per stripe", default=8, min=1,
    )
    color_image_name: StringProperty(
        name="Image", description="Image giving each pile its colour at the pile's (u,v)",
    )
    press_image_name: StringProperty(
        name="Press Map",
        description="Image whose brightness (0..1) over (u,v) says where the fabric was "
        "pressed: the pile bends towards the fabric there",
    )
    press_strength: FloatProperty(
        name="Press Strength", description="How far a fully pressed pile bends (0..1)",
        default=0.9, min=0.0, max=1.0, subtype="FACTOR",
    )


#: The plush settings as the scripting API sees them.
PLUSH_SETTINGS = SettingsSchema(
    "plush",
    PlushSettingsMixin,
    # Named as the knit's gauge since "One source per setting".
    renamed={"gauge_wales": "gauge_stitches", "gauge_courses": "gauge_rows"},
)
#: Settings by name, in declaration order.
SETTING_NAMES: tuple[str, ...] = PLUSH_SETTINGS.names


def _poll_source(_self: bpy.types.PropertyGroup, obj: bpy.types.Object) -> bool:
    return obj.type in {"SURFACE", "MESH"}


class PlushSettings(PlushSettingsMixin, bpy.types.PropertyGroup):
    """A plush object's settings (``Object.knitwear_plush``), kept to re-grow it."""

    is_plush: BoolProperty(name="Is Plush", default=False)
    source: PointerProperty(
        name="Source", type=bpy.types.Object, poll=_poll_source,
        description="The surface this plush grows on",
    )
    follow_camera: BoolProperty(
        name="Follow Camera",
        description="Choose horizontal or vertical slices for the scene camera on every frame "
        "change (and in renders)",
        default=True,
    )
    #: Pinned when grown: the stitch counts and the grid density, so a re-grown field after a
    #: file load has exactly this topology.
    bound_counts: IntVectorProperty(size=2, default=(0, 0), options={"HIDDEN"})
    bound_samples: IntVectorProperty(size=2, default=(0, 0), options={"HIDDEN"})
