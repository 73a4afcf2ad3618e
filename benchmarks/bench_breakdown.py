"""Where a click's time goes: sampling the source, the core, the hidden-yarn pass, the Blender
mesh and the rest (material, knitwear texture, object), at 1k, 10k and 100k stitches, at the
add-on's defaults and with the hidden-yarn pass forced (Cull From 0).

    .venv/bin/python benchmarks/bench_breakdown.py [--repeats 3] [--out docs/charts]

The scene: Blender's NURBS Surface Patch (a gently domed 1 m square) knitted by counts, seen
whole by a 50 mm camera at 1920 x 1080 (auto detail, as the add-on knits for a scene camera;
the far stitches of the larger knits are built at reduced quality). Each figure is the median
of --repeats clicks of `api.knit` (the Knit operator's work) after one unmeasured click of the
same size, so the cached mesh template is warm. Prints a table and writes
docs/charts/speed_breakdown.png (Pillow). No assertions: figures only.
"""

import argparse
import math
import os
import statistics
import sys
from pathlib import Path
from typing import Any

from bench_setup import ROOT, start_blender
from PIL import Image, ImageDraw, ImageFont

#: The parts of `KnitOutcome.seconds`: the hidden-yarn pass is timed inside the core (building
#: the whole knit it looks at included) and taken out of the core's bar.
PARTS = ("sampling", "core", "hidden-yarn pass", "mesh", "rest")
COLOURS = ((120, 120, 120), (31, 100, 180), (200, 40, 40), (40, 150, 70), (225, 170, 40))


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--stitches", type=int, nargs="+", default=[1_000, 10_000, 100_000])
    parser.add_argument("--repeats", type=int, default=3, help="clicks per figure (median)")
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "charts")
    return parser.parse_args()


def scene() -> Any:
    """The patch and a camera that sees all of it; returns the patch."""
    import bpy
    from mathutils import Vector

    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.surface.primitive_nurbs_surface_surface_add()
    patch = bpy.context.active_object
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.data.lens = 50.0
    # The patch spans x, y in [-0.5, 0.5] at heights 0.69 to 0.92: seen from the front and
    # above, 1.9 m away, it fills most of the frame.
    cam.location = Vector((0.0, -1.5, 1.9))
    cam.rotation_euler = (Vector((0.0, 0.0, 0.8)) - cam.location).to_track_quat(
        "-Z", "Y"
    ).to_euler()
    s = bpy.context.scene
    s.collection.objects.link(cam)
    s.camera = cam
    s.render.resolution_x, s.render.resolution_y = 1920, 1080
    s.render.resolution_percentage = 100
    return patch


def clicks(api: Any, source: Any, settings: dict[str, Any], repeats: int) -> dict[str, Any]:
    """Median seconds of each part over `repeats` clicks, after a warm-up click."""
    import bpy

    parts: dict[str, list[float]] = {p: [] for p in PARTS}
    total: list[float] = []
    last = None
    for k in range(repeats + 1):
        o = api.knit(source, **settings)
        if k:
            core = o.core_seconds - o.hidden_pass_seconds
            rest = o.seconds - o.sampling_seconds - o.core_seconds - o.mesh_seconds
            for name, v in zip(PARTS, (o.sampling_seconds, core, o.hidden_pass_seconds,
                                       o.mesh_seconds, rest), strict=True):
                parts[name].append(v)
            total.append(o.seconds)
        last = (o.stitches, o.triangles, o.triangles_hidden, o.hidden_pass, dict(o.levels))
        mesh = o.object.data
        bpy.data.objects.remove(o.object)
        bpy.data.meshes.remove(mesh)
    stitches, triangles, hidden, ran, levels = last
    return {
        "parts": {p: statistics.median(v) for p, v in parts.items()},
        "total": statistics.median(total),
        "stitches": stitches, "triangles": triangles, "hidden": hidden, "ran": ran,
        "levels": levels,
    }


def chart(rows: list[tuple[str, dict[str, Any]]], path: Path) -> None:
    """Horizontal stacked bars, one per row, each labelled with its total; the bars of one
    stitch count share a scale (its slowest bar fills the width)."""
    w, bar, gap, left, top = 1000, 34, 14, 300, 70
    h = top + len(rows) * (bar + gap) + 90
    img = Image.new("RGB", (w, h), (255, 255, 255))
    d = ImageDraw.Draw(img)
    f, small = ImageFont.load_default(size=15), ImageFont.load_default(size=13)
    d.text((w / 2, 14), "Where a click's time goes (2 cores; bars scaled per stitch count)",
           fill=(40, 40, 40), font=ImageFont.load_default(size=19), anchor="mt")
    groups: dict[int, float] = {}
    for _, r in rows:
        groups[r["stitches"]] = max(groups.get(r["stitches"], 0.0), r["total"])
    for i, (label, r) in enumerate(rows):
        y = top + i * (bar + gap)
        d.text((left - 10, y + bar / 2), label, fill=(40, 40, 40), font=small, anchor="rm")
        scale = (w - left - 190) / groups[r["stitches"]]
        x = float(left)
        for name, colour in zip(PARTS, COLOURS, strict=True):
            dx = max(0.0, r["parts"][name]) * scale
            d.rectangle([x, y, x + dx, y + bar], fill=colour)
            x += dx
        d.text((x + 8, y + bar / 2), f"{r['total']:.3f} s, {r['triangles'] / 1e6:.2f}M tris",
               fill=(40, 40, 40), font=f, anchor="lm")
    y = h - 60
    x = float(left)
    for name, colour in zip(PARTS, COLOURS, strict=True):
        d.rectangle([x, y, x + 18, y + 18], fill=colour)
        d.text((x + 24, y + 9), name, fill=(40, 40, 40), font=small, anchor="lm")
        x += 34 + d.textlength(name, font=small) + 20
    path.parent.mkdir(parents=True, exist_ok=True)
    img.quantize(64).save(path, optimize=True)


def main() -> None:
    args = parse_args()
    start_blender(args.zip)
    import bpy

    api = sys.modules["bl_ext.user_default.knitwear.api"]
    print(f"bench: Blender {bpy.app.version_string}, {os.cpu_count()} CPUs, "
          f"median of {args.repeats} clicks")
    source = scene()
    rows: list[tuple[str, dict[str, Any]]] = []
    for n in args.stitches:
        side = math.isqrt(n)
        counts = {"size_mode": "COUNTS", "courses": side, "wales": side}
        for name, extra in (("defaults", {}), ("pass forced", {"cull_hidden_min_triangles": 0})):
            r = clicks(api, source, counts | extra, args.repeats)
            rows.append((f"{side * side:,} stitches, {name}", r))
            parts = "  ".join(f"{p} {r['parts'][p]:.3f}" for p in PARTS)
            print(f"{side * side:>7,} {name:<12} click {r['total']:.3f} s: {parts}; "
                  f"{r['triangles']:,} triangles, {r['hidden']:,} hidden (pass ran: "
                  f"{r['ran']}), levels {r['levels']}", flush=True)
    path = args.out / "speed_breakdown.png"
    chart(rows, path)
    print(f"bench: wrote {path}")


if __name__ == "__main__":
    main()
