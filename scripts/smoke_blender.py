"""A smoke run of the extension in whatever Blender (`bpy` module) runs this script: install the
zip as a user does, knit a NURBS patch and a UV sphere, render them in Workbench, Update, Bake,
save, reopen the file and knit again. Prints each step and exits 1 at the first failure.

    <python with bpy> scripts/smoke_blender.py [dist/knitwear-0.1.0.zip]

For the Blender versions the test suite does not run on (issue 21): for example a venv of
Python 3.13 with `pip install bpy==5.2.3`.
"""

import os
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main() -> int:
    os.environ["BLENDER_USER_RESOURCES"] = tempfile.mkdtemp(prefix="knitwear-smoke-")
    import bpy

    zips = sorted((ROOT / "dist").glob("knitwear-*.zip"), key=lambda p: p.stat().st_mtime)
    zip_path = Path(sys.argv[1]) if len(sys.argv) > 1 else zips[-1]
    out = Path(tempfile.mkdtemp(prefix="knitwear-smoke-out-"))
    print(f"smoke: Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, {zip_path}")

    def step(name: str, run) -> object:  # noqa: ANN001 - a callable of no arguments
        t0 = time.perf_counter()
        try:
            value = run()
        except BaseException as e:  # noqa: BLE001 - every failure is this run's answer
            print(f"FAIL {name}: {type(e).__name__}: {e}")
            raise SystemExit(1) from e
        print(f"ok   {name} ({time.perf_counter() - t0:.2f} s)")
        return value

    step("install", lambda: bpy.ops.extensions.package_install_files(
        filepath=str(zip_path), repo="user_default", enable_on_install=True))
    from bl_ext.user_default.knitwear import api, bake

    bpy.ops.wm.read_homefile(use_empty=True)
    small = {"size_mode": "COUNTS", "courses": 12, "wales": 12}

    def nurbs() -> object:
        bpy.ops.surface.primitive_nurbs_surface_surface_add()
        return api.knit_object(bpy.context.active_object, **small)

    def sphere() -> object:
        bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, location=(2.5, 0, 0))
        return api.knit_object(bpy.context.active_object, **small)

    knit = step("knit a NURBS patch", nurbs)
    step("knit a UV sphere", sphere)

    def render() -> None:
        scene = bpy.context.scene
        bpy.ops.object.camera_add(location=(1.2, -6, 4), rotation=(0.95, 0, 0.1))
        scene.camera = bpy.context.active_object
        scene.render.engine = "BLENDER_WORKBENCH"
        scene.render.resolution_x, scene.render.resolution_y = 320, 240
        scene.render.filepath = str(out / "smoke.png")
        bpy.ops.render.render(write_still=True)
        assert (out / "smoke.png").stat().st_size > 1000

    step("render (Workbench)", render)
    step("update", lambda: api.update_knit(knit, seed=3))
    step("update, new topology", lambda: api.update_knit(knit, courses=10))
    step("bake", lambda: bake.bake_animation(knit, frame_start=1, frame_end=3,
                                               filepath=str(out / "knit.pc2")))
    name = knit.name
    blend = out / "smoke.blend"
    step("save", lambda: bpy.ops.wm.save_as_mainfile(filepath=str(blend)))
    step("reopen", lambda: bpy.ops.wm.open_mainfile(filepath=str(blend)))
    step("update after reopening", lambda: api.update_knit(bpy.data.objects[name]))
    print("smoke: all steps passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
