"""Knit a swatch headless, as a user would with the extension, and render it.

Installs the built extension (dist/knitwear-*.zip) into a throw-away Blender user folder,
builds a scene (a gently draped NURBS swatch, camera, light, world), knits the swatch with
the Knit operator in 2x2 rib with two-colour stripes, renders it with Workbench and saves the
.blend:

    .venv/bin/python examples/demo.py --out out     # -> out/demo.png, out/demo.blend
"""

import argparse
import math
import time
from pathlib import Path

from example_setup import ROOT, extension_zip, look_at, start_blender, workbench


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "out", help="output folder")
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    parser.add_argument("--width", type=int, default=960, help="render width, pixels")
    parser.add_argument("--height", type=int, default=720, help="render height, pixels")
    return parser.parse_args()


def swatch() -> "bpy.types.Object":  # noqa: F821  (bpy is imported late, on purpose)
    """A 16 x 12 cm swatch as a bicubic NURBS patch, draped over something round."""
    import bpy

    bpy.ops.surface.primitive_nurbs_surface_surface_add()
    obj = bpy.context.active_object
    obj.name = "Swatch"
    spline = obj.data.splines[0]
    # Endpoint knots: the surface reaches its border control points, so the swatch has the
    # size its control net says.
    spline.use_endpoint_u = spline.use_endpoint_v = True
    nu, nv = spline.point_count_u, spline.point_count_v
    for j in range(nv):
        for i in range(nu):
            s, t = i / (nu - 1), j / (nv - 1)
            x = (s - 0.5) * 0.16
            y = (t - 0.5) * 0.12
            # A soft hump across, as if laid over a rolled towel, and the far edge lifting.
            z = 0.012 + 0.018 * math.sin(math.pi * s) + 0.012 * t**2
            spline.points[j * nu + i].co = (x, y, z, 1.0)
    return obj


def table() -> "bpy.types.Object":  # noqa: F821
    """A tabletop under the swatch: seen through the gaps between loops, it reads as fabric
    lying on something rather than floating in a void."""
    import bpy
    import numpy as np

    bpy.ops.mesh.primitive_plane_add(size=1.2)
    obj = bpy.context.active_object
    obj.name = "Table"
    # Workbench shows colour attributes: give the table one too, a warm pale wood.
    attribute = obj.data.color_attributes.new("Col", "FLOAT_COLOR", "POINT")
    attribute.data.foreach_set("color", np.tile((0.42, 0.30, 0.19, 1.0), len(obj.data.vertices)))
    return obj


def stage() -> None:
    """Camera, light and world."""
    import bpy
    from mathutils import Vector

    scene = bpy.context.scene
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = 50.0
    camera.location = Vector((0.045, -0.215, 0.185))
    target = (-0.004, 0.0, 0.012)
    look_at(camera, target)
    scene.collection.objects.link(camera)
    scene.camera = camera

    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (math.radians(40), math.radians(10), math.radians(30))
    scene.collection.objects.link(sun)

    world = bpy.data.worlds.new("World")
    world.color = (0.018, 0.018, 0.022)
    scene.world = world


def main() -> None:
    args = parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    zip_path = extension_zip(args.zip)
    start_blender(zip_path)
    import bpy

    print(f"demo: installed {zip_path.name}")

    table()
    source = swatch()
    stage()
    bpy.context.view_layer.objects.active = source

    t0 = time.perf_counter()
    result = bpy.ops.object.knitwear_knit(
        size_mode="GAUGE",
        gauge_stitches=20.0,  # a DK-weight wool: 20 stitches x 28 rows per 10 cm
        gauge_rows=28.0,
        pattern="rib_2x2",
        color_mode="STRIPES",
        color_count=2,
        stripe_height=4,
        color_1=(0.50, 0.045, 0.04),  # cranberry
        color_2=(0.78, 0.70, 0.56),  # oatmeal
        # A DK wool is about 1.2 mm thick: a quarter of the 5 mm stitch, rounder and fuller
        # than the core's default (a fifth), which suits a close-up.
        yarn_radius=0.0006,
        seed=3,
    )
    knit = bpy.context.active_object
    print(
        f"demo: knitted {source.name!r} -> {knit.name!r} ({result}): "
        f"{len(knit.data.vertices):,} vertices, {len(knit.data.polygons):,} triangles "
        f"in {time.perf_counter() - t0:.2f} s"
    )
    # The swatch is the knit's shape, not part of the picture: through the gaps between
    # loops one should see what lies behind the fabric, as with real knitting.
    source.hide_render = True
    source.hide_set(True)

    png = args.out / "demo.png"
    workbench(args.width, args.height, png)
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print(f"demo: rendered {png} ({args.width}x{args.height}, Workbench) "
          f"in {time.perf_counter() - t0:.1f} s")

    blend = args.out / "demo.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend.resolve()))
    print(f"demo: saved {blend}")


if __name__ == "__main__":
    main()
