"""Plush settings: one definition shared by the stored settings (``obj.knitwear_plush``) and
the Plush operator's redo panel, as the knit's `properties` module does for knits."""


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

from .. import poll_plush_source
from ..core_settings import from_core
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
    gauge_stitches: FloatProperty(**from_core("gauge_stitches", "plush", soft_max=200.0))
    gauge_rows: FloatProperty(**from_core("gauge_rows", "plush", soft_max=200.0))
    courses: IntProperty(**from_core("courses", "plush", soft_max=2000))
    wales: IntProperty(**from_core("wales", "plush", soft_max=2000))
    piles_per_stitch: IntProperty(**from_core("piles_per_stitch", "plush"))
    pile_length: FloatProperty(
        **from_core(
            "pile_length", "plush", soft_max=0.1, subtype="DISTANCE", unit="LENGTH", precision=4
        )
    )
    pile_radius: FloatProperty(
        **from_core(
            "pile_radius", "plush", soft_max=0.05, subtype="DISTANCE", unit="LENGTH", precision=4
        )
    )
    slices: IntProperty(**from_core("slices", "plush"))
    lean_angle: FloatProperty(**from_core("lean_angle", "plush", subtype="ANGLE"))
    lean_direction: FloatProperty(**from_core("lean_direction", "plush", subtype="ANGLE"))
    theta_max: FloatProperty(**from_core("theta_max", "plush", subtype="ANGLE"))
    noise_scales: StringProperty(
        name="Noise Scales",
        description="Sampling coefficients k of the fractal noise, e.g. '1 2 4 8' (larger k: "
        "coarser features, more weight)",
        default="1 2 4 8",
    )
    seed: IntProperty(**from_core("seed", "plush"))
    color_mode: EnumProperty(name="Colour", items=COLOR_MODE_ITEMS, default="SINGLE")
    color_1: _color_prop(0)
    color_2: _color_prop(1)
    color_3: _color_prop(2)
    color_4: _color_prop(3)
    color_count: IntProperty(
        name="Colours",
        description="How many colours the stripes cycle through",
        default=2,
        min=1,
        max=MAX_COLORS,
    )
    stripe_height: IntProperty(
        name="Stripe Height",
        description="Courses per stripe",
        default=8,
        min=1,
    )
    color_image_name: StringProperty(
        name="Image",
        description="Image giving each pile its colour at the pile's (u,v)",
    )
    press_image_name: StringProperty(
        name="Press Map",
        description="Image whose brightness (0..1) over (u,v) says where the fabric was "
        "pressed: the pile bends towards the fabric there",
    )
    press_strength: FloatProperty(**from_core("press_strength", "plush", subtype="FACTOR"))


#: The plush settings as the scripting API sees them.
PLUSH_SETTINGS = SettingsSchema(
    "plush",
    PlushSettingsMixin,
    # Named as the knit's gauge since "One source per setting".
    renamed={"gauge_wales": "gauge_stitches", "gauge_courses": "gauge_rows"},
)
#: Settings by name, in declaration order.
SETTING_NAMES: tuple[str, ...] = PLUSH_SETTINGS.names


class PlushSettings(PlushSettingsMixin, bpy.types.PropertyGroup):
    """A plush object's settings (``Object.knitwear_plush``), kept to re-grow it."""

    is_plush: BoolProperty(name="Is Plush", default=False)
    source: PointerProperty(
        name="Source",
        type=bpy.types.Object,
        poll=poll_plush_source,
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
