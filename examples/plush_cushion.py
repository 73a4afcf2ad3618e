"""The paper's palm print ([Zhang plush], figure 7): a velvet cushion pressed by a hand.

Installs the built extension into a throw-away Blender user folder, builds a cushion top (a
domed NURBS patch), draws a press map of a palm (an ellipse and five finger capsules) with
NumPy into a Blender image, grows plush over the cushion with the "Plush this surface"
operator, and renders it with Workbench (and, with --eevee, EEVEE):

    .venv/bin/python examples/plush_cushion.py --out out   # -> out/plush_cushion.png

Where the hand pressed, the pile lies down towards the fabric: seen from above those piles
turn to vertical slices and show their darker roots, so the print reads as a darker hand in
the lighter upright pile, as on real velvet.
"""

import argparse
import math
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
#: Size of the cushion's top (metres) and of the press map (pixels).
CUSHION = 0.45
PRESS_SIZE = 256


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "out", help="output folder")
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    parser.add_argument("--width", type=int, default=900, help="render width, pixels")
    parser.add_argument("--height", type=int, default=700, help="render height, pixels")
    parser.add_argument("--stitches", type=int, default=220, help="courses and wales")
    parser.add_argument("--eevee", action="store_true", help="also render with EEVEE")
    return parser.parse_args()


def install(given: Path | None) -> None:
    """Install and enable the extension as Edit > Preferences > Get Extensions > Install from
    Disk does, into a temporary user folder (set before `bpy` is imported)."""
    os.environ["BLENDER_USER_RESOURCES"] = tempfile.mkdtemp(prefix="knitwear-plush-demo-")
    import bpy

    zips = sorted((ROOT / "dist").glob("knitwear-*.zip"), key=lambda p: p.stat().st_mtime)
    zip_path = given or (zips[-1] if zips else None)
    if zip_path is None:
        sys.exit("plush_cushion: no dist/knitwear-*.zip; run scripts/bootstrap.sh first")
    result = bpy.ops.extensions.package_install_files(
        filepath=str(zip_path), repo="user_default", enable_on_install=True
    )
    if result != {"FINISHED"}:
        sys.exit(f"plush_cushion: installing {zip_path} failed: {result}")
    print(f"plush_cushion: installed {zip_path.name}")


def palm_press(size: int) -> np.ndarray:
    """A right hand's print as press weights in 0..1: (size, size), row 0 at v = 0.

    A palm ellipse and five finger capsules (distance to a segment below a radius), with a
    soft rim so the pressed pile blends into the upright pile around it.
    """
    v, u = np.mgrid[0:size, 0:size].astype(np.float32) / (size - 1)
    p = np.stack([u, v], axis=-1)

    def capsule(a: tuple[float, float], b: tuple[float, float], radius: float) -> np.ndarray:
        a_, b_ = np.array(a, np.float32), np.array(b, np.float32)
        ab = b_ - a_
        t = np.clip(((p - a_) @ ab) / (ab @ ab), 0.0, 1.0)
        return np.linalg.norm(p - (a_ + t[..., None] * ab), axis=-1) - radius

    # Signed distance (negative inside) of the palm ellipse, approximately.
    centre, radii = np.array((0.5, 0.36), np.float32), np.array((0.17, 0.19), np.float32)
    q = (p - centre) / radii
    palm = (np.linalg.norm(q, axis=-1) - 1.0) * radii.min()
    fingers = [
        capsule((0.37, 0.50), (0.33, 0.74), 0.035),  # little finger
        capsule((0.45, 0.53), (0.44, 0.84), 0.039),  # ring
        capsule((0.53, 0.54), (0.54, 0.87), 0.040),  # middle
        capsule((0.61, 0.52), (0.65, 0.82), 0.038),  # index
        capsule((0.64, 0.33), (0.80, 0.50), 0.042),  # thumb
    ]
    distance = np.minimum.reduce([palm, *fingers])
    rim = 0.012
    return np.clip(0.5 - distance / (2 * rim), 0.0, 1.0).astype(np.float32)


def press_image(weights: np.ndarray) -> "bpy.types.Image":  # noqa: F821
    import bpy

    h, w = weights.shape
    image = bpy.data.images.new("Palm Print", w, h, float_buffer=True)
    rgba = np.ones((h, w, 4), np.float32)
    rgba[..., :3] = weights[..., None]
    image.pixels.foreach_set(rgba.ravel())  # Blender's rows go bottom-up, as v does
    image.pack()  # a generated image: keep it in the .blend
    return image


def cushion() -> "bpy.types.Object":  # noqa: F821
    """A cushion top: a bicubic NURBS patch, square, domed like a stuffed pillow."""
    import bpy

    bpy.ops.surface.primitive_nurbs_surface_surface_add()
    obj = bpy.context.active_object
    obj.name = "Cushion"
    spline = obj.data.splines[0]
    spline.use_endpoint_u = spline.use_endpoint_v = True
    nu, nv = spline.point_count_u, spline.point_count_v
    for j in range(nv):
        for i in range(nu):
            s, t = i / (nu - 1), j / (nv - 1)
            dome = math.sin(math.pi * s) * math.sin(math.pi * t)
            # x runs against u so that the surface's normal (u x v) points up, out of the
            # cushion: the pile grows on the normal's side.
            spline.points[j * nu + i].co = (
                (0.5 - s) * CUSHION, (t - 0.5) * CUSHION, 0.05 + 0.09 * dome, 1.0
            )
    return obj


def stage(width: int, height: int) -> None:
    import bpy
    from mathutils import Vector

    scene = bpy.context.scene
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = 50
    camera.location = (0.0, -0.62, 0.95)
    camera.rotation_euler = (Vector((0, 0.0, 0.05)) - camera.location).to_track_quat(
        "-Z", "Y"
    ).to_euler()
    scene.collection.objects.link(camera)
    scene.camera = camera

    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.5
    sun.rotation_euler = (math.radians(35), math.radians(-15), math.radians(20))
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("World")
    world.color = (0.05, 0.05, 0.06)
    scene.world = world

    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "PNG"
    scene.view_settings.view_transform = "Standard"


def render(engine: str, path: Path) -> None:
    import bpy

    scene = bpy.context.scene
    try:
        scene.render.engine = engine
    except TypeError:
        if engine != "BLENDER_EEVEE":
            raise
        scene.render.engine = "BLENDER_EEVEE_NEXT"  # the name Blender 4.2 to 4.5 give EEVEE
    if engine == "BLENDER_WORKBENCH":
        shading = scene.display.shading
        shading.light = "STUDIO"  # lit: the pressed pile faces the light differently
        shading.color_type = "VERTEX"  # "Attribute" in the UI: the pile colours
        shading.show_cavity = False
        scene.display.render_aa = "16"
    else:
        scene.eevee.taa_render_samples = 16
    scene.render.filepath = str(path.resolve())
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print(f"plush_cushion: rendered {path} ({engine}) in {time.perf_counter() - t0:.1f} s")


def main() -> None:
    args = parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    install(args.zip)
    import bpy

    bpy.ops.wm.read_homefile(use_empty=True)
    source = cushion()
    press_image(palm_press(PRESS_SIZE))
    stage(args.width, args.height)
    bpy.context.view_layer.objects.active = source

    t0 = time.perf_counter()
    result = bpy.ops.object.knitwear_plush(
        size_mode="COUNTS",
        courses=args.stitches,
        wales=args.stitches,
        slices=8,
        lean_angle=math.radians(25.0),
        lean_direction=math.radians(-90.0),  # the pile lies towards -v: brushed down
        color_1=(0.32, 0.02, 0.05),  # deep red velvet
        press_image_name="Palm Print",
        press_strength=0.95,
        seed=7,
    )
    plush = bpy.context.active_object
    print(
        f"plush_cushion: {result} {plush.name!r}: {len(plush.data.vertices):,} vertices, "
        f"{len(plush.data.polygons):,} triangles in {time.perf_counter() - t0:.2f} s"
    )
    # The cushion's own surface stays as the backing under the pile, in a darker tone.
    backing = bpy.data.materials.new("Backing")
    backing.diffuse_color = (0.08, 0.005, 0.01, 1.0)  # Workbench
    if backing.node_tree is None:
        backing.use_nodes = True  # Blender 4.x; 5.0 always has a tree
    bsdf = backing.node_tree.nodes.get("Principled BSDF")
    if bsdf is not None:
        bsdf.inputs["Base Color"].default_value = backing.diffuse_color
    source.data.materials.append(backing)

    render("BLENDER_WORKBENCH", args.out / "plush_cushion.png")
    if args.eevee:
        render("BLENDER_EEVEE", args.out / "plush_cushion_eevee.png")
    blend = args.out / "plush_cushion.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend.resolve()))
    print(f"plush_cushion: saved {blend}")


if __name__ == "__main__":
    main()
