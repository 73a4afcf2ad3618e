"""A knitted sleeve on a bending arm, rendered frame by frame headless.

Builds a character-like deforming surface (a UV-mapped tube, skinned to a two-bone armature
whose elbow bends and straightens), knits it in the round with a chosen preset, and renders a
frame range to PNGs with Workbench. The knit follows the armature on every frame through the
extension's frame handler, exactly as it does for F12 or `blender -b file.blend -a`; the
.blend is saved too, so any single frame can be rendered alone on a farm machine:

    .venv/bin/python examples/animate.py --out out/sleeve                 # frames 1-24
    .venv/bin/python examples/animate.py --pattern seed --frames 1 48 --out out/sleeve
    .venv/bin/python examples/animate.py --engine eevee --still 12 --lens 60 --size 1200 600
    .venv/bin/python examples/animate.py --bake --out out/sleeve   # and a PC2 cache for a farm

With --bake the frames are also baked to OUT/sleeve.pc2 (Bake Knit Animation), and the bake's
check of the yarn's clearance is printed frame by frame: the inner elbow squashes the rows,
and the bake names the frames where yarn passes through yarn.
"""

import argparse
import math
import time
from pathlib import Path

import numpy as np
from example_setup import ROOT, extension_zip, look_at, start_blender, workbench

RINGS, SEGMENTS = 48, 32  # the tube's resolution
LENGTH, RADIUS = 0.6, 0.055  # metres: a forearm and upper arm


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "out" / "sleeve")
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    parser.add_argument("--pattern", default="rib_2x2", help="a preset (knitwear.Pattern)")
    parser.add_argument("--frames", type=int, nargs=2, default=(1, 24), metavar=("FIRST", "LAST"))
    parser.add_argument("--size", type=int, nargs=2, default=(640, 480), metavar=("W", "H"))
    parser.add_argument("--gauge", type=float, default=20.0, help="stitches per 10 cm")
    parser.add_argument("--engine", choices=("workbench", "eevee", "cycles"), default="workbench",
                        help="render engine (eevee and cycles light the wool material)")
    parser.add_argument("--still", type=int, metavar="FRAME",
                        help="render only this frame, to OUT/still.png")
    parser.add_argument("--lens", type=float, default=35.0, help="camera focal length, mm")
    parser.add_argument("--bake", action="store_true",
                        help="also bake the frames to OUT/sleeve.pc2 and print its clearance check")
    return parser.parse_args()


def tube() -> "bpy.types.Object":  # noqa: F821  (bpy is imported late, on purpose)
    """An open tube along z with a UV map: u around (0..1, seam at x > 0), v along."""
    import bpy

    a = np.linspace(0.0, 2 * np.pi, SEGMENTS + 1)  # the seam column is duplicated for UVs
    z = np.linspace(0.0, LENGTH, RINGS)
    aa, zz = np.meshgrid(a, z)
    verts = np.stack([RADIUS * np.cos(aa), RADIUS * np.sin(aa), zz], -1).reshape(-1, 3)
    cols = SEGMENTS + 1
    r, c = np.meshgrid(np.arange(RINGS - 1), np.arange(SEGMENTS), indexing="ij")
    v0 = (r * cols + c).ravel()
    quads = np.stack([v0, v0 + 1, v0 + 1 + cols, v0 + cols], -1)
    mesh = bpy.data.meshes.new("Sleeve")
    mesh.from_pydata(verts.tolist(), [], quads.tolist())
    uv = mesh.uv_layers.new(name="UVMap")
    corner_verts = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("vertex_index", corner_verts)
    u = (corner_verts % cols) / SEGMENTS
    v = (corner_verts // cols) / (RINGS - 1)
    uv.uv.foreach_set("vector", np.stack([u, v], -1).astype(np.float32).ravel())
    mesh.shade_smooth()
    obj = bpy.data.objects.new("Sleeve", mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def rig(sleeve: "bpy.types.Object", first: int, last: int) -> None:  # noqa: F821
    """Two bones along the tube, smoothly weighted, the elbow bending 70 degrees and back."""
    import bpy

    arm_data = bpy.data.armatures.new("Arm")
    arm = bpy.data.objects.new("Arm", arm_data)
    bpy.context.scene.collection.objects.link(arm)
    bpy.context.view_layer.objects.active = arm
    bpy.ops.object.mode_set(mode="EDIT")
    upper = arm_data.edit_bones.new("upper")
    upper.head, upper.tail = (0, 0, 0), (0, 0, LENGTH / 2)
    lower = arm_data.edit_bones.new("lower")
    lower.head, lower.tail = (0, 0, LENGTH / 2), (0, 0, LENGTH)
    lower.parent = upper
    bpy.ops.object.mode_set(mode="OBJECT")

    z = np.array([v.co.z for v in sleeve.data.vertices]) / LENGTH
    t = np.clip((z - 0.35) / 0.3, 0.0, 1.0)
    w_lower = t * t * (3 - 2 * t)  # smoothstep across the elbow
    for name, weights in (("upper", 1 - w_lower), ("lower", w_lower)):
        group = sleeve.vertex_groups.new(name=name)
        for i, w in enumerate(weights):
            if w > 0:
                group.add([i], float(w), "REPLACE")
    modifier = sleeve.modifiers.new("Armature", "ARMATURE")
    modifier.object = arm

    bone = arm.pose.bones["lower"]
    bone.rotation_mode = "XYZ"
    middle = (first + last) // 2
    for frame, angle in ((first, 0.0), (middle, 70.0), (last, 0.0)):
        bone.rotation_euler = (math.radians(angle), 0.0, 0.0)
        bone.keyframe_insert("rotation_euler", frame=frame)


def stage(lens: float) -> None:
    import bpy

    scene = bpy.context.scene
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = lens
    camera.location = (1.1, -0.45, 0.4)
    look_at(camera, (0.0, -0.12, 0.3))
    scene.collection.objects.link(camera)
    scene.camera = camera
    world = bpy.data.worlds.new("World")
    world.color = (0.05, 0.05, 0.06)
    scene.world = world


def lit(engine: str, width: int, height: int, path: Path) -> None:
    """EEVEE or Cycles, lit by a sun and a grey sky, so the wool material shows."""
    import bpy

    scene = bpy.context.scene
    if engine == "cycles":
        scene.render.engine = "CYCLES"
        scene.cycles.samples = 64
    else:
        try:
            scene.render.engine = "BLENDER_EEVEE"
        except TypeError:
            scene.render.engine = "BLENDER_EEVEE_NEXT"  # Blender 4.2 to 4.5
        scene.eevee.taa_render_samples = 16
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (math.radians(50), math.radians(10), math.radians(60))
    scene.collection.objects.link(sun)
    scene.world.color = (0.18, 0.19, 0.21)
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "PNG"
    scene.render.use_stamp_date = False
    scene.render.use_stamp_render_time = False
    scene.render.filepath = str(path)


def main() -> None:
    args = parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    start_blender(extension_zip(args.zip))
    import bpy
    from bl_ext.user_default.knitwear import api

    scene = bpy.context.scene
    first, last = args.frames
    scene.frame_start, scene.frame_end = first, last
    sleeve = tube()
    rig(sleeve, first, last)
    stage(args.lens)
    scene.frame_set(first)

    t0 = time.perf_counter()
    knit = api.knit_object(
        sleeve,
        pattern=args.pattern,
        gauge_stitches=args.gauge,
        gauge_rows=args.gauge * 1.4,
        color_mode="STRIPES",
        color_count=3,
        stripe_height=6,
        color_1=(0.55, 0.42, 0.30),  # oatmeal
        color_2=(0.03, 0.10, 0.30),  # navy
        color_3=(0.50, 0.05, 0.05),  # cranberry
        seed=7,
    )
    print(f"animate: knitted {len(knit.data.vertices):,} vertices, "
          f"{len(knit.data.polygons):,} triangles in {time.perf_counter() - t0:.2f} s")
    sleeve.hide_render = True
    sleeve.hide_set(True)

    path = args.out / ("still.png" if args.still is not None else "frame_")
    if args.engine == "workbench":
        # FXAA: one anti-aliasing pass per frame keeps a long animation quick on a CPU renderer.
        workbench(*args.size, path, aa="8" if args.still is not None else "FXAA")
    else:
        lit(args.engine, *args.size, path)
    t0 = time.perf_counter()
    if args.still is not None:
        scene.frame_set(args.still)
        bpy.ops.render.render(write_still=True)
        print(f"animate: rendered frame {args.still} to {path} in "
              f"{time.perf_counter() - t0:.1f} s")
    else:
        bpy.ops.render.render(animation=True)
        frames = last - first + 1
        print(f"animate: rendered {frames} frames to {args.out} in "
              f"{time.perf_counter() - t0:.1f} s")
    if args.bake:
        from bl_ext.user_default.knitwear import bake

        t0 = time.perf_counter()
        baked = bake.bake_animation(knit, frame_start=first, frame_end=last,
                                    filepath=str((args.out / "sleeve.pc2").resolve()))
        print(f"animate: baked frames {first}-{last} to {baked.path} in "
              f"{time.perf_counter() - t0:.1f} s")
        print("animate: clearance (min / 1st percentile, yarn diameters): " + ", ".join(
            f"{c.frame}: {c.min:.2f} / {c.p01:.2f}" for c in baked.clearance))
        print(f"animate: {baked.summary() or 'no yarn passes through yarn'}")
    blend = (args.out / "sleeve.blend").resolve()
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    print(f"animate: saved {blend} (render any frame alone: blender -b {blend.name} -f N)")


if __name__ == "__main__":
    main()
