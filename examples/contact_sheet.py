"""Knit a list of patterns in a list of colourways and render a contact sheet.

Each pattern x colourway is knitted on the same small NURBS swatch with the scripting API,
rendered headless with Workbench, and pasted into one labelled PNG (one row per pattern, one
column per colourway). The tiles are jobs of the batch runner (`batch_render.py`): rendered
side by side on local worker processes, or on a Dask cluster, and only the missing ones when
the sheet is made again:

    .venv/bin/python examples/contact_sheet.py --out out/sheet
    .venv/bin/python examples/contact_sheet.py --patterns seed rib_1x1 --out out/sheet
    .venv/bin/python examples/contact_sheet.py --out out/sheet --scheduler tcp://farm:8786

With `--output`, it renders the one tile of `--pattern` and `--colourway` (what a job runs).
"""

import argparse
import sys
import time
from pathlib import Path

from batch_render import grid, run_batch
from example_setup import ROOT, extension_zip, look_at, start_blender, workbench
from PIL import Image, ImageDraw

#: Colourways: name, then the yarn colours (linear RGB) that stripes cycle through.
COLOURWAYS: dict[str, tuple[tuple[float, float, float], ...]] = {
    "oatmeal": ((0.55, 0.42, 0.30),),
    "nordic": ((0.50, 0.05, 0.05), (0.80, 0.75, 0.65)),
    "sea": ((0.03, 0.10, 0.30), (0.25, 0.40, 0.10), (0.80, 0.75, 0.65)),
}


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "out" / "sheet")
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    parser.add_argument("--patterns", nargs="+", help="presets (default: all of them)")
    parser.add_argument("--colourways", nargs="+", choices=sorted(COLOURWAYS),
                        default=list(COLOURWAYS))
    parser.add_argument("--tile", type=int, nargs=2, default=(320, 240), metavar=("W", "H"))
    parser.add_argument("--workers", type=int, default=2, help="local worker processes")
    parser.add_argument("--scheduler", help="a Dask scheduler's address (tcp://host:port)")
    parser.add_argument("--pattern", help="with --output: the one tile's pattern")
    parser.add_argument("--colourway", choices=sorted(COLOURWAYS), help="with --output")
    parser.add_argument("--output", type=Path, help="render one tile to this PNG")
    return parser.parse_args()


def swatch() -> "bpy.types.Object":  # noqa: F821  (bpy is imported late, on purpose)
    """Blender's NURBS patch scaled to a 12 x 12 cm swatch."""
    import bpy

    bpy.ops.surface.primitive_nurbs_surface_surface_add()
    obj = bpy.context.active_object
    obj.scale = (0.06, 0.06, 0.06)
    obj.hide_render = True
    return obj


def camera() -> None:
    import bpy

    scene = bpy.context.scene
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.data.type = "ORTHO"
    cam.data.ortho_scale = 0.1
    cam.location = (0.0, -0.03, 0.2)  # from above, tilted a little: the loops' relief shows
    look_at(cam, (0.0, 0.0, 0.0))
    scene.collection.objects.link(cam)
    scene.camera = cam


def render_one(
    pattern: str, colours: tuple[tuple[float, float, float], ...], png: Path, size: tuple[int, int]
) -> None:
    import bpy
    from bl_ext.user_default.knitwear import api

    bpy.ops.wm.read_homefile(use_empty=True)
    workbench(*size, png, aa="FXAA")
    source = swatch()
    camera()
    palette = {f"color_{i + 1}": c for i, c in enumerate(colours)}
    knit = api.knit_object(
        source,
        pattern=pattern,
        direction="V",  # Blender's patch runs u along y: courses along x read as rows here
        color_mode="STRIPES" if len(colours) > 1 else "SINGLE",
        color_count=len(colours),
        stripe_height=3,
        **palette,
    )
    knit.knitwear.follow_source = False  # a still
    bpy.ops.render.render(write_still=True)


def main() -> None:
    args = parse_args()
    zip_path = extension_zip(args.zip)
    if args.output is not None:  # one tile: a job of the batch
        if not args.pattern or not args.colourway:
            sys.exit("contact_sheet: --output needs --pattern and --colourway")
        start_blender(zip_path)
        render_one(args.pattern, COLOURWAYS[args.colourway], args.output, tuple(args.tile))
        return
    args.out.mkdir(parents=True, exist_ok=True)
    if args.patterns:
        patterns = args.patterns
    else:
        start_blender(zip_path)
        import knitwear

        patterns = knitwear.Pattern.presets()
    w, h = args.tile
    jobs = grid(
        Path(__file__).resolve(), args.out.resolve(),
        variations={"pattern": patterns, "colourway": args.colourways},
        extra=["--tile", str(w), str(h), "--zip", str(zip_path.resolve())],
    )
    t0 = time.perf_counter()
    report = run_batch(jobs, scheduler=args.scheduler, workers=args.workers)
    label_w, label_h = 160, 24
    sheet = Image.new("RGB", (label_w + w * len(args.colourways), label_h + h * len(patterns)),
                      (24, 24, 28))
    draw = ImageDraw.Draw(sheet)
    for j, way in enumerate(args.colourways):
        draw.text((label_w + j * w + 8, 6), way, fill=(230, 230, 230))
    for i, pattern in enumerate(patterns):
        draw.text((8, label_h + i * h + h // 2), pattern, fill=(230, 230, 230))
        for j, way in enumerate(args.colourways):
            png = args.out / f"{pattern}_{way}.png"
            sheet.paste(Image.open(png).convert("RGB"), (label_w + j * w, label_h + i * h))
    path = args.out / "contact_sheet.png"
    sheet.save(path)
    print(f"contact_sheet: {report['rendered']} knits rendered ({report['skipped']} already "
          f"there) in {time.perf_counter() - t0:.1f} s -> {path}")


if __name__ == "__main__":
    main()
