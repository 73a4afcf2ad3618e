"""What a knit and a plush both translate from their settings to the core: the size (a gauge
per 10 cm or explicit counts, both settings named alike), the stripe colours of the palette,
and images looked up by name. Each raises `knitwear.ParameterError` with a message fit for a
report.
"""

from collections.abc import Mapping
from typing import Any

import bpy
import knitwear

#: The core reads a gauge as stitches per this many scene units (10 cm in metres).
GAUGE_LENGTH = 0.1


def gauge(per_10cm: float, scene: bpy.types.Scene) -> float:
    """A gauge per 10 cm as the core reads it: per 0.1 scene units, as if a unit were a metre.

    One scene unit is ``scale_length`` metres, so 0.1 units hold ``scale_length`` times the
    stitches that 10 cm hold.
    """
    return per_10cm * scene.unit_settings.scale_length


def size(settings: Mapping[str, Any], scene: bpy.types.Scene) -> dict[str, Any]:
    """The core's size arguments from ``size_mode``: explicit ``courses`` and ``wales``, or
    ``gauge_stitches`` and ``gauge_rows`` per 10 cm as a gauge per 0.1 scene units."""
    mode = settings["size_mode"]
    if mode == "COUNTS":
        return {"courses": int(settings["courses"]), "wales": int(settings["wales"])}
    if mode == "GAUGE":
        stitches, rows = float(settings["gauge_stitches"]), float(settings["gauge_rows"])
        if not (stitches > 0 and rows > 0):
            raise knitwear.ParameterError(
                f"gauge must be positive, not {stitches:g} stitches x {rows:g} rows per 10 cm"
            )
        return {"gauge": (gauge(stitches, scene), gauge(rows, scene))}
    raise knitwear.ParameterError(f"unknown size_mode {mode!r}; expected GAUGE or COUNTS")


def palette(settings: Mapping[str, Any], count: int) -> list[tuple[float, float, float]]:
    """The colours ``color_1`` .. ``color_<count>``."""
    return [tuple(settings[f"color_{i + 1}"]) for i in range(count)]


def stripes(settings: Mapping[str, Any], max_colors: int) -> "knitwear.ColorPattern":
    """Stripes of ``stripe_height`` rows cycling through the first ``color_count`` colours."""
    count = int(settings["color_count"])
    if not 1 <= count <= max_colors:
        raise knitwear.ParameterError(f"color_count must be 1 to {max_colors}, not {count}")
    return knitwear.ColorPattern.stripes(
        palette(settings, count), rows_each=int(settings["stripe_height"])
    )


def image_named(name: str, what: str) -> bpy.types.Image:
    """The image ``name``; ``what`` names its use in the message when there is none."""
    image = bpy.data.images.get(name) if name else None
    if image is None:
        raise knitwear.ParameterError(
            f"{what} image '{name}' not found" if name else f"no {what} image chosen"
        )
    return image
