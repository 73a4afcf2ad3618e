"""The yarn close up (issue 16): a stockinette swatch 8 stitches across the frame, at
fluffiness 0, the default and high, in Workbench, EEVEE and Cycles, as one labelled sheet:

    .venv/bin/python scripts/yarn_closeups.py [--zip dist/knitwear-0.1.0.zip]
        [--before old.zip] [--out docs/charts/yarn_closeups.png]

With ``--before`` (another build's extension zip) a first column shows that build at the
default fluffiness, for a before/after. Each column renders in its own Blender process, which
installs its zip in a fresh user folder. Look at the sheet: the yarn should read as soft round
strands, the stitches as V columns.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

from PIL import Image, ImageDraw

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "examples"))
from example_setup import extension_zip, look_at, start_blender, workbench  # noqa: E402

ENGINES = ("WORKBENCH", "EEVEE", "CYCLES")
FLUFFINESS = (0.0, 0.5, 1.5)  # none, the default, high
SIZE = (400, 300)


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    parser.add_argument("--before", type=Path, help="another build's zip, for a first column")
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "charts" / "yarn_closeups.png")
    # Internal: render one column into a folder (run in a fresh process per zip).
    parser.add_argument("--column", type=Path, help=argparse.SUPPRESS)
    parser.add_argument("--fluffiness", type=float, nargs="+", help=argparse.SUPPRESS)
    return parser.parse_args()


def set_engine(engine: str) -> None:
    import bpy

    scene = bpy.context.scene
    if engine == "WORKBENCH":
        workbench(*SIZE, Path(scene.render.filepath))
        return
    scene.render.engine = (
        "CYCLES" if engine == "CYCLES"
        else "BLENDER_EEVEE_NEXT" if bpy.app.version < (4, 5, 0) else "BLENDER_EEVEE"
    )
    if engine == "CYCLES":
        scene.cycles.samples = 48
        scene.cycles.use_denoising = False
        scene.cycles.device = "CPU"
    world = bpy.data.worlds.get("yarn") or bpy.data.worlds.new("yarn")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs[1].default_value = 0.3
    if "sun" not in bpy.data.objects:
        sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
        scene.collection.objects.link(sun)
        sun.rotation_euler = (0.6, 0.3, 0.4)
        sun.data.energy = 4.0


def render_column(folder: Path, fluffiness: list[float], zip_path: Path) -> None:
    """Renders ``<folder>/<engine>_<fluffiness>.png`` for every engine and fluffiness."""
    start_blender(zip_path)
    import bpy
    from bl_ext.user_default.knitwear import api

    for fluff in fluffiness:
        for engine in ENGINES:
            bpy.ops.wm.read_homefile(use_empty=True)
            scene = bpy.context.scene
            scene.render.resolution_x, scene.render.resolution_y = SIZE
            scene.render.resolution_percentage = 100
            scene.render.filepath = str(folder / f"{engine}_{fluff}.png")
            set_engine(engine)
            scene.render.use_stamp_date = False
            scene.render.use_stamp_render_time = False
            bpy.ops.mesh.primitive_plane_add(size=0.05)
            source = bpy.context.active_object
            api.knit_object(source, size_mode="COUNTS", courses=14, wales=10,
                            fluffiness=fluff, detail_mode="FULL")
            source.hide_render = True
            camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
            scene.collection.objects.link(camera)
            scene.camera = camera
            camera.location = (0.0, -0.012, 0.03)
            look_at(camera, (0.0, 0.0, 0.0))
            camera.data.lens = 50
            camera.data.clip_start = 0.001
            bpy.ops.render.render(write_still=True)


def compose(columns: list[tuple[str, Path, float]], out: Path) -> None:
    """One row per engine, one column per (label, folder, fluffiness)."""
    label_h, label_w = 22, 90
    w, h = SIZE
    sheet = Image.new("RGB", (label_w + w * len(columns), label_h + h * len(ENGINES)), "white")
    draw = ImageDraw.Draw(sheet)
    for c, (label, folder, fluff) in enumerate(columns):
        draw.text((label_w + c * w + 6, 5), label, fill="black")
        for r, engine in enumerate(ENGINES):
            tile = Image.open(folder / f"{engine}_{fluff}.png").convert("RGB")
            sheet.paste(tile, (label_w + c * w, label_h + r * h))
    for r, engine in enumerate(ENGINES):
        draw.text((6, label_h + r * h + h // 2), engine.title(), fill="black")
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out)
    print(f"yarn_closeups: wrote {out}")


def main() -> None:
    args = parse_args()
    zip_path = extension_zip(args.zip)
    if args.column is not None:
        render_column(args.column, args.fluffiness, zip_path)
        return
    with tempfile.TemporaryDirectory() as tmp:
        columns: list[tuple[str, Path, float]] = []
        jobs: list[tuple[Path, Path, list[float]]] = []
        if args.before is not None:
            before = Path(tmp) / "before"
            jobs.append((args.before, before, [0.5]))
            columns.append(("before, fluffiness 0.5", before, 0.5))
        after = Path(tmp) / "after"
        jobs.append((zip_path, after, list(FLUFFINESS)))
        columns += [(f"fluffiness {f:g}", after, f) for f in FLUFFINESS]
        for job_zip, folder, fluffs in jobs:
            folder.mkdir()
            subprocess.run(
                [sys.executable, __file__, "--zip", str(job_zip), "--column", str(folder),
                 "--fluffiness", *map(str, fluffs)],
                check=True,
            )
        compose(columns, args.out)


if __name__ == "__main__":
    main()
