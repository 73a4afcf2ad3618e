"""Swatch gallery of the stitch presets (issue 3): every `knitwear.Pattern.presets()` name knitted
on a small flat swatch in headless Blender with the installed extension, rendered straight on
with Workbench (studio light, cavity, the yarn's vertex colours) and pasted into a labelled
contact sheet:

    .venv/bin/python scripts/swatches.py [--zip dist/knitwear-0.1.0.zip] [--out docs/swatches]
    .venv/bin/python scripts/swatches.py --patterns cable_c4 bobbles   # just these (no gallery)
    .venv/bin/python scripts/swatches.py --files tests/data/corpus/braid.ks ... --out docs/corpus

Writes `<out>/<preset>.png` (256 x 256 px) and, when every preset is rendered, `<out>/gallery.png`.
With `--files`, Knitspeak or chart files are knitted instead (the add-on's Pattern > From File),
each named by its file's stem, and the gallery holds them all.
Each swatch is a whole number of pattern repeats, at least two each way and at least 16 stitches
wide, and about square on the page (the default gauge, 20 x 28 per 10 cm). `fair_isle` is worn in
the Fair Isle colour chart `ColorPattern.preset("fair_isle_band", ...)`, passed to the add-on as
its Colour > Chart setting.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image, ImageDraw

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "examples"))
from example_setup import extension_zip, start_blender, workbench  # noqa: E402

#: Default gauge (stitches, rows per 10 cm): the stitch's width and height in metres.
STITCH_W, STITCH_H = 0.1 / 20, 0.1 / 28
#: Swatches are at least this many stitches wide.
MIN_WALES = 16
#: Yarn radius in stitch widths (the core's default, which its loop shapes are tuned for).
YARN_RADIUS = 0.1
#: Yarn (linear RGB): an undyed, Aran-like cream, light enough for cavity shading to read.
YARN = (0.70, 0.60, 0.45)
#: Fair Isle: background and pattern colours (linear RGB): navy and oatmeal.
FAIR_ISLE_COLOURS = ((0.03, 0.10, 0.30), (0.80, 0.75, 0.65))
#: Background (linear grey): dark enough that lace holes read as holes.
BACKGROUND = (0.04, 0.04, 0.04)
#: The core's `fair_isle_band` colour chart (src/pattern/presets.rs), top row first, for the
#: add-on's Colour > Chart setting; `check_fair_isle_chart` holds it to the core's preset.
FAIR_ISLE_BAND = "00000000;01000100;00101000;10010001;00101000;01000100;00000000;11111111"
#: Presets worn in a colour chart: preset -> (chart, its width, its height).
COLOUR_CHARTS = {"fair_isle": (FAIR_ISLE_BAND, 8, 8)}
#: Gallery layout: columns, label strip height (px).
COLUMNS, LABEL_H = 6, 22


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "swatches")
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    parser.add_argument("--patterns", nargs="+", help="presets (default: all of them)")
    parser.add_argument("--files", nargs="+", type=Path, help="pattern files instead of presets")
    parser.add_argument("--size", type=int, default=256, help="swatch image size, px")
    return parser.parse_args()


def swatch_counts(width: int, height: int) -> tuple[int, int]:
    """(wales, courses) for a pattern repeat of `width` stitches by `height` rows: whole
    repeats, at least two each way, at least `MIN_WALES` wide and about square on the page."""
    wales = width * max(2, math.ceil(MIN_WALES / width))
    rows = wales * STITCH_W / STITCH_H
    courses = height * max(2, math.ceil(rows / height - 0.25))
    return wales, courses


def repeat_of(name: str, file: Path | None = None) -> tuple[int, int]:
    """The repeat (stitches, rows) of preset `name` (or of the pattern in `file`), with its
    colour chart's where it has one."""
    import knitwear

    pattern = knitwear.Pattern.from_file(file) if file else knitwear.Pattern.preset(name)
    w, h = pattern.width, pattern.height
    if name in COLOUR_CHARTS:
        _, cw, ch = COLOUR_CHARTS[name]
        w, h = math.lcm(w, cw), math.lcm(h, ch)
    return w, h


def check_fair_isle_chart() -> None:
    """`FAIR_ISLE_BAND` must colour a knit exactly as the core's `fair_isle_band` preset does
    (the core exposes no chart text of a colour preset, so this script carries a copy)."""
    import knitwear

    u, v = np.meshgrid(np.linspace(0, 1, 8), np.linspace(0, 1, 8))
    pos = np.stack([0.08 * u, 0.06 * v, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    surface = knitwear.GridSurface(pos, nrm)
    pattern = knitwear.Pattern.preset("fair_isle")
    colours = []
    for chart in (
        knitwear.ColorPattern.preset("fair_isle_band", FAIR_ISLE_COLOURS),
        knitwear.ColorPattern(FAIR_ISLE_COLOURS, FAIR_ISLE_BAND.replace(";", "\n")),
    ):
        result = knitwear.knit(surface, pattern, courses=16, wales=16, colors=chart,
                               ring_segments=3, samples_per_loop=6)
        colours.append(result.colors)
    if not np.array_equal(*colours):
        sys.exit("swatches: FAIR_ISLE_BAND no longer matches the core's fair_isle_band preset")


def sheet_source(width: float, height: float) -> Any:
    """A flat `width x height` mesh rectangle (scene units) centred on the origin in z = 0,
    facing +Z, UV map 0..1 over it: courses run along x, rows go up along y."""
    import bpy

    bpy.ops.mesh.primitive_plane_add(size=1.0)
    obj = bpy.context.active_object
    obj.scale = (width, height, 1.0)
    bpy.ops.object.transform_apply(location=False, rotation=False, scale=True)
    obj.hide_render = True
    return obj


def top_camera(extent: float) -> None:
    """An orthographic camera looking straight down -Z at the origin, `extent` across."""
    import bpy

    scene = bpy.context.scene
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.data.type = "ORTHO"
    cam.data.ortho_scale = extent
    cam.location = (0.0, 0.0, 1.0)  # no rotation: looks down -Z with +Y up in the image
    scene.collection.objects.link(cam)
    scene.camera = cam


def lighting() -> None:
    """A neutral dark background behind the knit. Workbench shadows are left off: seen
    straight on, a flat knit casts nearly nothing, and they cost six times the render."""
    import bpy

    world = bpy.data.worlds.new("Background")
    world.color = BACKGROUND
    bpy.context.scene.world = world


def render_swatch(
    name: str, png: Path, size: int = 256, file: Path | None = None
) -> dict[str, Any]:
    """Knit preset `name` (or the pattern in `file`) on a flat swatch (`swatch_counts`) in an
    empty scene and render it to `png` (`size` px square). Needs the extension installed and
    enabled; returns the counts, stitches, triangles and seconds."""
    import bpy
    from bl_ext.user_default.knitwear import api

    bpy.ops.wm.read_homefile(use_empty=True)
    workbench(size, size, png)
    lighting()
    wales, courses = swatch_counts(*repeat_of(name, file))
    width, height = wales * STITCH_W, courses * STITCH_H
    source = sheet_source(width, height)
    # A margin round the swatch for its cast-on and bind-off, which hang past the border.
    top_camera(1.12 * max(width, height))
    colours: dict[str, Any] = {"color_mode": "SINGLE", "color_1": YARN}
    chosen: dict[str, Any] = (
        {"pattern": "FILE", "pattern_file": str(file)} if file else {"pattern": name}
    )
    if name in COLOUR_CHARTS:
        colours = {
            "color_mode": "CHART",
            "color_chart": COLOUR_CHARTS[name][0],
            "color_1": FAIR_ISLE_COLOURS[0],
            "color_2": FAIR_ISLE_COLOURS[1],
        }
    t0 = time.perf_counter()
    outcome = api.knit(
        source,
        **chosen,
        size_mode="COUNTS",
        courses=courses,
        wales=wales,
        direction="U",
        detail_mode="FULL",  # every stitch at full quality: the camera sees them all anyway
        yarn_radius=YARN_RADIUS * STITCH_W,
        **colours,
    )
    outcome.object.knitwear.follow_source = False  # a still
    bpy.ops.render.render(write_still=True)
    save_small(Image.open(png), png)
    return {
        "name": name, "wales": wales, "courses": courses, "stitches": outcome.stitches,
        "triangles": outcome.triangles, "seconds": time.perf_counter() - t0,
    }


def save_small(image: Image.Image, path: Path) -> None:
    """`image` as a 256-colour PNG: the yarn's fibre noise makes a full-colour PNG three times
    larger, and the docs are committed."""
    quantized = image.convert("RGB").quantize(
        256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE
    )
    quantized.save(path, optimize=True)


def gallery(names: list[str], folder: Path, size: int) -> Path:
    """`folder/gallery.png`: the swatches in a grid, `COLUMNS` wide, each named below."""
    rows = math.ceil(len(names) / COLUMNS)
    pad = 6
    cell_w, cell_h = size + pad, size + LABEL_H + pad
    sheet = Image.new("RGB", (pad + COLUMNS * cell_w, pad + rows * cell_h), (32, 32, 34))
    draw = ImageDraw.Draw(sheet)
    for i, name in enumerate(names):
        x, y = pad + (i % COLUMNS) * cell_w, pad + (i // COLUMNS) * cell_h
        sheet.paste(Image.open(folder / f"{name}.png").convert("RGB"), (x, y))
        draw.text((x + 4, y + size + 5), name, fill=(230, 230, 230))
    path = folder / "gallery.png"
    save_small(sheet, path)
    return path


def main() -> None:
    args = parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    start_blender(extension_zip(args.zip))
    import knitwear

    check_fair_isle_chart()
    presets = knitwear.Pattern.presets()
    files = {f.stem: f.resolve() for f in args.files or []}
    names = list(files) or args.patterns or presets
    t0 = time.perf_counter()
    for name in names:
        info = render_swatch(name, args.out / f"{name}.png", args.size, files.get(name))
        print(f"{name:20s} {info['wales']:3d} x {info['courses']:3d} stitches "
              f"{info['triangles']:>9,} triangles {info['seconds']:5.1f} s")
    if files or set(names) == set(presets):
        print(f"swatches: gallery -> {gallery(names, args.out, args.size)}")
    print(f"swatches: {len(names)} presets in {time.perf_counter() - t0:.1f} s -> {args.out}")


if __name__ == "__main__":
    main()
