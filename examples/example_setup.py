"""What every example does first: install the built extension into a throw-away Blender user
folder (as Edit > Preferences > Get Extensions > Install from Disk does), and set up a
Workbench render that shows the knit's yarn colours.

`bpy` is imported inside the functions: Blender reads BLENDER_USER_RESOURCES once, when `bpy`
is first imported, so `start_blender` must run before anything else imports it.
"""

import os
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def extension_zip(given: Path | None) -> Path:
    """``given``, or the newest dist/knitwear-*.zip (scripts/bootstrap.sh builds it)."""
    if given is not None:
        return given
    zips = sorted((ROOT / "dist").glob("knitwear-*.zip"), key=lambda p: p.stat().st_mtime)
    if not zips:
        sys.exit("example: no dist/knitwear-*.zip; run scripts/bootstrap.sh first")
    return zips[-1]


def start_blender(zip_path: Path) -> None:
    """Import bpy with a fresh user folder and install and enable the extension from the zip."""
    os.environ["BLENDER_USER_RESOURCES"] = tempfile.mkdtemp(prefix="knitwear-example-")
    import bpy

    result = bpy.ops.extensions.package_install_files(
        filepath=str(zip_path), repo="user_default", enable_on_install=True
    )
    if result != {"FINISHED"}:
        sys.exit(f"example: installing {zip_path} failed: {result}")
    bpy.ops.wm.read_homefile(use_empty=True)


def workbench(width: int, height: int, path: Path, *, aa: str = "8") -> None:
    """Workbench with studio light, cavity and the colour attribute, writing PNGs to ``path``."""
    import bpy

    scene = bpy.context.scene
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.display.render_aa = aa
    shading = scene.display.shading
    shading.light = "STUDIO"
    shading.color_type = "VERTEX"  # "Attribute" in the UI: the knit's yarn colours
    shading.show_cavity = True  # darkens the crevices between loops: reads as depth
    shading.cavity_type = "BOTH"
    shading.show_specular_highlight = False  # wool has no gloss
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "PNG"
    # No date or render time in the PNG's metadata: the same frame is the same file on every
    # run and every machine (a farm's frame can be checked against one rendered alone).
    scene.render.use_stamp_date = False
    scene.render.use_stamp_render_time = False
    scene.render.filepath = str(path)


def look_at(camera: "bpy.types.Object", target: tuple[float, float, float]) -> None:  # noqa: F821
    """Point ``camera`` at ``target`` with world Z up."""
    from mathutils import Vector

    direction = Vector(target) - camera.location
    camera.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
