"""Size on disk of a baked knit animation in each cache format plain Blender plays back: the
PC2 the extension's bake writes, Alembic and USD (issue "A sweater on an animated
character", item 4: a farm carries these files).

    .venv/bin/python benchmarks/bench_cache_formats.py
    .venv/bin/python benchmarks/bench_cache_formats.py --stitches 2500 --frames 6

The source is bench_follow.py's shape-keyed UV grid, knitted at default quality and baked
with `bake.bake_animation` (Follow Source off afterwards, the Mesh Cache modifier playing the
PC2). The baked knit is then exported as each format writes an animated mesh: Alembic
(`wm.alembic_export`, Ogawa) and USD (`wm.usd_export`, binary crate), each with and without
per-frame normals, no UVs, colours written once where the format can. For each file it
prints its size, bytes per frame (the whole file over the frames), bytes per vertex per
frame, and what each further frame adds (from the same export over half the frames), and
checks that the file plays the animation back: it is imported beside the
knit and its positions at the middle frame compared with the baked knit's.
No assertions: figures only.
"""

import argparse
import os
import tempfile
from pathlib import Path

import numpy as np
from bench_follow import waving_grid
from bench_setup import start_blender


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--stitches", type=int, default=10_000)
    parser.add_argument("--frames", type=int, default=12, help="frames baked and exported")
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    return parser.parse_args()


def positions(obj: "bpy.types.Object", frame: int) -> np.ndarray:  # noqa: F821
    """World-space evaluated positions of ``obj`` at ``frame``."""
    import bpy

    bpy.context.scene.frame_set(frame)
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    co = np.empty(3 * len(mesh.vertices), np.float32)
    mesh.vertices.foreach_get("co", co)
    evaluated.to_mesh_clear()
    co = co.reshape(-1, 3)
    m = np.array(obj.matrix_world, np.float32)
    return co @ m[:3, :3].T + m[:3, 3]


def played_back(path: Path, frame: int, want: np.ndarray) -> str:
    """Imports ``path`` beside the baked knit, compares its positions at ``frame`` with
    ``want`` and removes what it imported."""
    import bpy

    before = set(bpy.data.objects)
    if path.suffix == ".abc":
        bpy.ops.wm.alembic_import(filepath=str(path))
    else:
        bpy.ops.wm.usd_import(filepath=str(path))
    new = [o for o in bpy.data.objects if o not in before]
    meshes = [o for o in new if o.type == "MESH"]
    if len(meshes) != 1:
        verdict = f"{len(meshes)} meshes imported"
    else:
        got = positions(meshes[0], frame)
        if got.shape != want.shape:
            verdict = f"{len(got):,} vertices, baked {len(want):,}"
        else:
            verdict = f"plays back, max error {np.abs(got - want).max():.1e} m"
    for obj in new:
        bpy.data.objects.remove(obj)
    return verdict


def main() -> None:
    args = parse_args()
    start_blender(args.zip)
    import bpy
    from bl_ext.user_default.knitwear import api, bake

    side = int(args.stitches**0.5)
    source = waving_grid(max(16, side // 2))
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, args.frames
    # The wave runs over frames 1-100: bake a stretch that moves.
    knit = api.knit_object(source, size_mode="COUNTS", courses=side, wales=side)
    out = Path(tempfile.mkdtemp(prefix="knitwear-caches-"))
    pc2 = bake.bake_animation(knit, frame_start=1, frame_end=args.frames,
                              filepath=str(out / "knit.pc2"), check_clearance=False).path
    vertices = len(knit.data.vertices)
    middle = 1 + args.frames // 2
    want = positions(knit, middle)
    def export(kind: str, normals: bool, frames: int) -> Path:
        path = out / f"knit_{frames}{'_normals' if normals else ''}.{kind}"
        # The knit alone (an import selects what it brings).
        for obj in scene.objects:
            obj.select_set(obj == knit)
        bpy.context.view_layer.objects.active = knit
        if kind == "abc":
            bpy.ops.wm.alembic_export(filepath=str(path), start=1, end=frames, selected=True,
                                      uvs=False, normals=normals, face_sets=False,
                                      export_custom_properties=False,
                                      evaluation_mode="RENDER")
        else:
            scene.frame_end = frames
            bpy.ops.wm.usd_export(filepath=str(path), selected_objects_only=True,
                                  export_animation=True, export_normals=normals,
                                  export_uvmaps=False, export_materials=False,
                                  evaluation_mode="RENDER")
            scene.frame_end = args.frames
        return path

    print(f"bench: Blender {bpy.app.version_string}, {side * side:,} stitches, "
          f"{vertices:,} vertices, {len(knit.data.polygons):,} triangles, "
          f"frames 1-{args.frames}")
    print(f"{'format':<16} {'size MB':>8} {'MB/frame':>9} {'B/vertex/frame':>15} "
          f"{'a frame more':>13}  playback (frame {middle})")
    size = os.path.getsize(pc2)
    # PC2: a 32-byte header, then 12 bytes a vertex a frame.
    print(f"{'PC2 (the bake)':<16} {size / 1e6:8.1f} {size / args.frames / 1e6:9.2f} "
          f"{size / args.frames / vertices:15.2f} {(size - 32) / args.frames / vertices:13.2f}"
          "  the bake itself")
    half = max(1, args.frames // 2)
    for kind, name in (("abc", "Alembic"), ("usdc", "USD")):
        for normals in (False, True):
            path = export(kind, normals, args.frames)
            shorter = export(kind, normals, half)
            size, less = os.path.getsize(path), os.path.getsize(shorter)
            more = (size - less) / (args.frames - half) / vertices if args.frames > half else 0
            label = f"{name}{', normals' if normals else ''}"
            print(f"{label:<16} {size / 1e6:8.1f} {size / args.frames / 1e6:9.2f} "
                  f"{size / args.frames / vertices:15.2f} {more:13.2f}  "
                  f"{played_back(path, middle, want)}")


if __name__ == "__main__":
    main()
