"""Per-frame cost of a knit following its animated source, against the bare cost of writing
that many positions into a Blender mesh (measured in the same run).

    .venv/bin/python benchmarks/bench_follow.py                 # 10k and 50k stitches
    .venv/bin/python benchmarks/bench_follow.py --stitches 2500 --frames 5

The source is a UV-mapped grid (1 m square) with an animated shape key (a travelling wave), the
knit at default quality (6 ring segments, 16 samples per loop). For each stitch count it prints
medians over --frames frame changes:
  sample    reading the evaluated source into the core's surface (positions, normals, UVs);
  core      `Knit.positions` with `normals_out` into the kept buffers (the core, in parallel:
            positions and the smooth normals, one pass);
  write     `foreach_set` of the positions and of the custom normals, plus `Mesh.update()`;
  frame     the whole `follow()` (what the frame handler does per knit);
  unshare   frame less sample, core and write: Blender's copy of the arrays the mesh shares
            with its evaluated copy, which the frame's first write pays (the parts, timed
            again after it, do not). Arrays over 32 MB (10,000 stitches: 36 MB each) come
            from fresh pages every frame; glibc's huge pages make that about 6x cheaper;
  floor     `foreach_set` of the same number of positions alone (the bare cost);
  normals   what the next draw or render pays for normals afterwards (Blender shades with the
            custom normals the frame wrote, from 4.5: about nothing);
  fps       1 / frame, and 1 / (frame + normals);
and, for comparison, the path that writes positions only (what a knit did before it brought
its normals, and still does in Blender 4.2): its frame, the recompute Blender then pays on the
next draw, and its fps with it. Then it runs itself again with
GLIBC_TUNABLES=glibc.malloc.hugetlb=1 (a launch-time setting of Blender's process, see
docs/performance.md) and prints that run's rows.
No assertions: figures only.
"""

import argparse
import math
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from bench_setup import start_blender


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--stitches", type=int, nargs="+", default=[10_000, 50_000])
    parser.add_argument("--frames", type=int, default=9, help="frame changes per figure")
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    parser.add_argument("--once", action="store_true", help="no second run with huge pages")
    return parser.parse_args()




def waving_grid(subdivisions: int) -> "bpy.types.Object":  # noqa: F821  (late import)
    import bpy

    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.mesh.primitive_grid_add(
        x_subdivisions=subdivisions, y_subdivisions=subdivisions, size=1.0
    )
    cloth = bpy.context.active_object
    cloth.shape_key_add(name="Basis")
    wave = cloth.shape_key_add(name="Wave")
    co = np.empty(3 * len(wave.data), np.float32)
    wave.data.foreach_get("co", co)
    co = co.reshape(-1, 3)
    co[:, 2] = 0.1 * np.sin(2 * np.pi * (co[:, 0] + co[:, 1]))
    wave.data.foreach_set("co", co.ravel())
    for frame, value in ((1, 0.0), (100, 1.0)):
        wave.value = value
        wave.keyframe_insert("value", frame=frame)
    bpy.context.scene.frame_set(1)
    return cloth


def median_ms(times: list[float]) -> float:
    return 1000 * statistics.median(times)


def bench(stitches: int, frames: int) -> dict[str, float]:
    import bpy
    from bl_ext.user_default.knitwear import api, follow, mesh_build

    side = math.isqrt(stitches)
    source = waving_grid(max(16, side // 2))
    knit = api.knit_object(source, size_mode="COUNTS", courses=side, wales=side)
    knit.knitwear.follow_source = False  # the bench drives follow() itself
    scene = bpy.context.scene
    mesh = knit.data
    nv = len(mesh.vertices)
    t: dict[str, list[float]] = {k: [] for k in ("sample", "core", "write", "frame", "floor",
                                                  "normals", "old_frame", "old_normals")}
    follow.follow(knit)  # bind once
    follower = follow._followers[knit.session_uid]
    buffer = np.empty((nv, 3), np.float32)
    normals = np.empty((nv, 3), np.float32)
    for k in range(frames):
        scene.frame_set(2 + 7 * k)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        t0 = time.perf_counter()
        follow.follow(knit, depsgraph=depsgraph)
        t["frame"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        mesh.vertex_normals[0].vector  # noqa: B018  (forces the lazy normal recompute)
        t["normals"].append(time.perf_counter() - t0)
        # The parts, again, one by one.
        t0 = time.perf_counter()
        sampled = api.sample_source(knit, bpy.context, depsgraph)
        t["sample"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        follower.knit.positions(sampled.surface, out=buffer, normals_out=normals)
        t["core"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        mesh_build.write_normals(mesh, normals)
        mesh_build.write_positions(mesh, buffer)
        t["write"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        mesh.attributes["position"].data.foreach_set("vector", buffer.ravel())
        t["floor"].append(time.perf_counter() - t0)
    # The positions-only path: Blender computes the normals on the next draw.
    mesh_build.write_normals(mesh, None)
    for k in range(frames):
        scene.frame_set(2 + 7 * k)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        t0 = time.perf_counter()
        follow.follow(knit, depsgraph=depsgraph, normals=False)
        t["old_frame"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        mesh.vertex_normals[0].vector  # noqa: B018
        t["old_normals"].append(time.perf_counter() - t0)
    row = {k: median_ms(v) for k, v in t.items()}
    row["stitches"] = side * side
    row["vertices"] = nv
    row["triangles"] = len(mesh.polygons)
    return row


def main() -> None:
    args = parse_args()
    start_blender(args.zip)
    import bpy

    print(f"bench: Blender {bpy.app.version_string}, {os.cpu_count()} CPUs, "
          f"medians over {args.frames} frames")
    rows = [bench(n, args.frames) for n in args.stitches]
    print()
    print(f"{'stitches':>9} {'vertices':>10} {'sample':>8} {'core':>8} {'write':>8} "
          f"{'unshare':>8} {'frame':>8} {'floor':>8} {'normals':>8} {'fps':>6} {'+norm':>6}"
          "   (ms)")
    for r in rows:
        unshare = r["frame"] - r["sample"] - r["core"] - r["write"]
        print(f"{r['stitches']:9,} {r['vertices']:10,} {r['sample']:8.1f} {r['core']:8.1f} "
              f"{r['write']:8.1f} {unshare:8.1f} {r['frame']:8.1f} {r['floor']:8.1f} "
              f"{r['normals']:8.1f} {1000 / r['frame']:6.1f} "
              f"{1000 / (r['frame'] + r['normals']):6.1f}")
    print()
    print("positions only (Blender recomputes the normals on the next draw):")
    print(f"{'stitches':>9} {'frame':>8} {'normals':>8} {'fps':>6} {'+norm':>6}   (ms)")
    for r in rows:
        print(f"{r['stitches']:9,} {r['old_frame']:8.1f} {r['old_normals']:8.1f} "
              f"{1000 / r['old_frame']:6.1f} {1000 / (r['old_frame'] + r['old_normals']):6.1f}")
    tunable = "glibc.malloc.hugetlb=1"
    if args.once or os.environ.get("GLIBC_TUNABLES") == tunable:
        return
    print()
    print(f"again, Blender started with GLIBC_TUNABLES={tunable}:")
    sys.stdout.flush()
    argv = [sys.executable, __file__, "--once", "--frames", str(args.frames), "--stitches",
            *map(str, args.stitches)] + (["--zip", str(args.zip)] if args.zip else [])
    subprocess.run(argv, env={**os.environ, "GLIBC_TUNABLES": tunable}, check=True)


if __name__ == "__main__":
    main()
