"""From the add-on's settings to the core's inputs: the stitch pattern, the colours, the size
and the keyword settings, and the source surface sampled for them.

Shared by a knit (`api`) and the knitwear texture (`texture`), so that the texture shows the
stitches, perturbation and colours a knit of the same settings builds. Converts and checks;
creates nothing in the blend file.
"""

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import bpy
import knitwear

from . import sampling, shared_inputs
from .properties import CUSTOM_PATTERN, FILE_PATTERN, KNIT_SETTINGS, MAX_COLORS

#: Called with the fraction done (0..1) between the steps of a knit.
Progress = Callable[[float], None]


complete = KNIT_SETTINGS.complete


def _chart_text(text: str) -> str:
    # A one-line UI field cannot hold line breaks, so ';' separates rows too.
    rows = [row.strip() for row in text.replace(";", "\n").splitlines()]
    return "\n".join(row for row in rows if row)


def pattern_of(settings: Mapping[str, Any]) -> "knitwear.Pattern":
    if settings["pattern"] == CUSTOM_PATTERN:
        text = settings["pattern_chart"]
        # Knitspeak uses ';' inside its rows, so it is read as written; a chart's rows may be
        # separated with ';' in the one-line field.
        if knitwear.Pattern.looks_like_knitspeak(text):
            return knitwear.Pattern.from_knitspeak(text)
        return knitwear.Pattern.from_chart(_chart_text(text))
    if settings["pattern"] == FILE_PATTERN:
        return _pattern_from_file(settings)
    return knitwear.Pattern.preset(settings["pattern"])


def _pattern_from_file(settings: Mapping[str, Any]) -> "knitwear.Pattern":
    """Pattern is From File: a Blender Text if one is named, else the file (Knitspeak or a
    chart, told apart by content)."""
    name = settings["pattern_text"]
    if name:
        text = bpy.data.texts.get(name)
        if text is None:
            raise knitwear.PatternError(f"no Blender Text named {name!r} (Pattern Text)")
        return knitwear.Pattern.from_text(text.as_string())
    path = settings["pattern_file"]
    if not path:
        raise knitwear.PatternError(
            "Pattern is From File but neither Pattern File nor Pattern Text is set"
        )
    return knitwear.Pattern.from_file(bpy.path.abspath(path))


def _colors(settings: Mapping[str, Any]) -> dict[str, Any]:
    """The core's `colors` / `color_image` arguments."""
    mode = settings["color_mode"]
    palette = shared_inputs.palette(settings, MAX_COLORS)
    if mode == "SINGLE":
        return {"colors": knitwear.ColorPattern(palette[:1], "0")}
    if mode == "STRIPES":
        return {"colors": shared_inputs.stripes(settings, MAX_COLORS)}
    if mode == "CHART":
        chart = str(settings["color_chart"]).strip()
        if chart in knitwear.ColorPattern.presets():
            # A named colourwork chart (e.g. "fair_isle_band") in the yarn colours.
            return {"colors": knitwear.ColorPattern.preset(chart, palette)}
        return {"colors": knitwear.ColorPattern(palette, _chart_text(chart))}
    if mode == "IMAGE":
        name = settings["color_image_name"]
        image = bpy.data.images.get(name) if name else None
        if image is None:
            raise knitwear.ParameterError(
                f"colour image '{name}' not found: pick an image for the Image colour mode"
                if name
                else "no colour image chosen: pick an image for the Image colour mode"
            )
        return {"color_image": sampling.image_pixels(image)}
    raise knitwear.ParameterError(
        f"unknown color_mode {mode!r}; expected SINGLE, STRIPES, CHART or IMAGE"
    )


def _estimated_count(n: float) -> int:
    """A stitch count measured on a probe, as a whole number the budget check takes (a
    non-finite one as the largest)."""
    return max(1, round(min(n, 1e12))) if math.isfinite(n) else 10**12


def _min_samples(
    source: bpy.types.Object,
    context: bpy.types.Context,
    settings: Mapping[str, Any],
    kwargs: Mapping[str, Any],
    pattern: "knitwear.Pattern",
) -> tuple[int, int] | None:
    """Grid samples (along the courses, along the wales) a NURBS source is tessellated with:
    enough for the stitch count it will get. None for a mesh, which is used as it is.

    A count over the core's memory budget is refused here (`knitwear.check_budget`, the check
    the knit makes first), before the surface is sampled densely for it: a 500 m surface at a
    knitting gauge answers in a fraction of a second."""
    size = {k: kwargs[k] for k in ("gauge", "courses", "wales") if k in kwargs}
    if source.type == "MESH":
        return None
    if "gauge" in size:
        # The stitch count follows from the surface's size: measure it on Blender's own
        # tessellation first (cheap), then sample densely.
        probe = sampling.sample_object(source, context, direction=settings["direction"])
        if probe.grid_shape is None:
            return None  # modifiers made it a mesh: used as it is
        extent_u, extent_v = probe.surface.extent
        wales = extent_u * size["gauge"][0] / shared_inputs.GAUGE_LENGTH
        courses = extent_v * size["gauge"][1] / shared_inputs.GAUGE_LENGTH
    else:
        wales, courses = size["wales"], size["courses"]
    knitwear.check_budget(
        pattern,
        _estimated_count(courses),
        _estimated_count(wales),
        ring_segments=kwargs["ring_segments"],
        samples_per_loop=kwargs["samples_per_loop"],
        budget_bytes=kwargs.get("budget_bytes"),
    )
    per = sampling.SAMPLES_PER_STITCH
    # Capped so an absurd count reaches the core's budget check instead of a huge grid.
    return (int(min(wales, 1e7) * per) + 1, int(min(courses, 1e7) * per) + 1)



def core_settings(settings: Mapping[str, Any], scene: bpy.types.Scene) -> dict[str, Any]:
    """`knitwear.knit` / `knitwear.Knit` keywords for ``settings`` (all but the pinned ones)."""
    radius = float(settings["yarn_radius"])
    return {
        **shared_inputs.size(settings, scene),
        **_colors(settings),
        "yarn_radius": radius if radius > 0 else None,
        "fluffiness": float(settings["fluffiness"]),
        "ring_segments": int(settings["ring_segments"]),
        "plies": int(settings["plies"]),
        "live_loops": bool(settings["live_loops"]),
        "samples_per_loop": int(settings["samples_per_loop"]),
        "tension": float(settings["tension"]),
        "kappa": float(settings["kappa"]),
        "seed": int(settings["seed"]),
        "color_variation": float(settings["color_variation"]),
        "threads": scene.render.threads,
    }



@dataclass(frozen=True)
class CoreInputs:
    """What the core is called with for a knit of a source: its surface, the pattern and the
    keyword settings."""

    sampled: sampling.Sampled
    pattern: "knitwear.Pattern"
    kwargs: dict[str, Any]
    #: Grid samples the NURBS source was tessellated with, or None for a mesh.
    min_samples: tuple[int, int] | None


def core_inputs(
    source: bpy.types.Object,
    context: bpy.types.Context,
    settings: Mapping[str, Any],
    progress: Progress | None = None,
) -> CoreInputs:
    """Sample ``source`` and convert complete ``settings`` for the core, as a knit does (the
    knitwear texture shares it). Creates nothing; raises `knitwear.KnitError`."""
    pattern = pattern_of(settings)
    kwargs = core_settings(settings, context.scene)
    if progress:
        progress(0.05)
    min_samples = _min_samples(source, context, settings, kwargs, pattern)
    sampled = sampling.sample_object(
        source, context, direction=settings["direction"], min_samples=min_samples
    )
    if progress:
        progress(0.2)
    return CoreInputs(sampled, pattern, kwargs, min_samples)



def check_source(source: bpy.types.Object | None, what: str) -> bpy.types.Object:
    if source is None:
        raise knitwear.SurfaceError(f"{what} has no source surface (was it deleted?)")
    if source.type not in {"SURFACE", "MESH"}:
        raise knitwear.SurfaceError(
            f"'{source.name}' is a {source.type.lower()}: knitwear knits NURBS surfaces and "
            "meshes with a UV map"
        )
    if source.knitwear.is_knit:
        raise knitwear.SurfaceError(f"'{source.name}' is itself a knit: knit its source instead")
    if source.knitwear_plush.is_plush:
        raise knitwear.SurfaceError(f"'{source.name}' is a plush: knit its source instead")
    return source
