"""Knitting throughput, from the core alone to a finished Blender mesh, against its floors and
against Blender's own Geometry Nodes doing the nearest equivalent (measured in the same run).

    .venv/bin/python benchmarks/bench_knit.py                  # 10k and 100k stitches
    .venv/bin/python benchmarks/bench_knit.py --stitches 2500 --repeats 1

For each stitch count, on a NURBS surface patch at default quality (6 ring segments,
16 samples per loop), it prints:
  core      seconds inside `knitwear.knit` (sampled surface given), and triangles per second;
  floor     seconds to copy the core's output bytes once in memory with NumPy (the physical
            floor for producing them), into touched memory; "fresh": into newly allocated
            memory, page faults and kernel zeroing included (what any new mesh pays);
  mesh      seconds to build the Blender mesh from the core's arrays (the add-on's fast route);
            "1st" is the first mesh of its face count, which builds the cached template;
  click     seconds from calling the Knit operator to a finished mesh (sampling, core, mesh,
            material, object);
  GN peer   /work/shared/peers/gn_knit.py at the same stitch count, ring and samples: loop
            curves instanced on a grid, realised and swept (Blender's native C++ path).
Medians over --repeats runs. No assertions: figures only.
"""

import argparse
import math
import os
import re
import subprocess
import sys
from pathlib import Path

from bench_setup import ROOT, median_seconds, start_blender

GN_PEER = ROOT / ".." / "shared" / "peers" / "gn_knit.py"
RING, SAMPLES = 6, 16  # the add-on's defaults


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--stitches", type=int, nargs="+", default=[10_000, 100_000])
    parser.add_argument("--repeats", type=int, default=3, help="runs per figure (median)")
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    parser.add_argument("--no-peer", action="store_true", help="skip the Geometry Nodes peer")
    return parser.parse_args()






def patch() -> "bpy.types.Object":  # noqa: F821  (bpy is imported late, on purpose)
    """Blender's NURBS Surface Patch (a gently domed 1 m square) in an empty scene."""
    import bpy

    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.surface.primitive_nurbs_surface_surface_add()
    return bpy.context.active_object


def copy_floor(result: object, repeats: int) -> tuple[float, float, int]:
    """Seconds to copy the output's bytes into memory already touched (the pure copy), and
    into freshly allocated memory (what any new mesh pays: the kernel zeroes each new page)."""
    import numpy as np

    arrays = [result.vertices, result.triangles, result.edges, result.corner_edges,
              result.colors]
    targets = [np.empty_like(a) for a in arrays]

    def copy() -> None:
        for dst, src in zip(targets, arrays, strict=True):
            np.copyto(dst, src)

    def fresh_copy() -> None:
        # Large blocks are mapped fresh by malloc and unmapped on free: new pages each time.
        copies = [a.copy() for a in arrays]
        del copies

    copy()  # touch the pages once: the floor is copying, not page faults
    return (median_seconds(copy, repeats), median_seconds(fresh_copy, repeats),
            sum(a.nbytes for a in arrays))


def gn_peer(cols: int, rows: int) -> tuple[float, int] | None:
    if not GN_PEER.exists():
        print(f"bench: peer {GN_PEER} not found")
        return None
    done = subprocess.run(
        [sys.executable, str(GN_PEER), str(cols), str(rows), str(RING), str(SAMPLES)],
        capture_output=True,
        text=True,
        check=False,
    )
    found = re.search(r"triangles=(\d+) seconds=([\d.]+)", done.stdout)
    if found is None:
        print(f"bench: peer failed ({done.returncode}): {done.stderr.strip()[-400:]}")
        return None
    return float(found.group(2)), int(found.group(1))


def bench(stitches: int, repeats: int, peer: bool) -> dict[str, object]:
    import bpy
    import knitwear
    from bl_ext.user_default.knitwear import mesh_build, sampling

    side = math.isqrt(stitches)
    cols = rows = side
    settings = {"size_mode": "COUNTS", "courses": rows, "wales": cols}
    source = patch()
    scene = bpy.context.scene

    sampled = sampling.sample_object(
        source, bpy.context, min_samples=(4 * cols + 1, 4 * rows + 1), direction="U"
    )
    pattern = knitwear.Pattern.preset("stockinette")

    def core() -> object:
        return knitwear.knit(sampled.surface, pattern, courses=rows, wales=cols,
                             threads=scene.render.threads)

    result = core()
    core_s = median_seconds(core, repeats)
    floor_s, fresh_s, nbytes = copy_floor(result, repeats)

    def mesh(result: object = result) -> None:
        bpy.data.meshes.remove(mesh_build.new_mesh("bench", result))

    def drop_templates() -> None:
        for m in [m for m in bpy.data.meshes if m.name.startswith(mesh_build.TEMPLATE_PREFIX)]:
            bpy.data.meshes.remove(m)

    # The first mesh of a face count pays for the cached template's face offsets.
    drop_templates()
    mesh_first_s = median_seconds(mesh, 1)
    mesh_s = median_seconds(mesh, repeats)
    triangles = len(result.triangles)
    del result, mesh  # free the arrays before the operator makes its own

    def click() -> None:
        bpy.context.view_layer.objects.active = source
        assert bpy.ops.object.knitwear_knit(**settings) == {"FINISHED"}
        knit = bpy.context.active_object
        mesh = knit.data
        bpy.data.objects.remove(knit)
        bpy.data.meshes.remove(mesh)

    drop_templates()
    click_first_s = median_seconds(click, 1)
    click_s = median_seconds(click, repeats)
    row: dict[str, object] = {
        "stitches": cols * rows,
        "triangles": triangles,
        "core_s": core_s,
        "floor_s": floor_s,
        "fresh_s": fresh_s,
        "bytes": nbytes,
        "mesh_s": mesh_s,
        "mesh_first_s": mesh_first_s,
        "click_s": click_s,
        "click_first_s": click_first_s,
    }
    if peer:
        row["peer"] = gn_peer(cols, rows)
    return row


def print_table(rows: list[dict[str, object]]) -> None:
    print()
    print(f"{'stitches':>9} {'triangles':>11} {'core s':>8} {'Mtri/s':>8} {'floor s':>8} "
          f"{'fresh s':>8} "
          f"{'mesh s':>8} {'1st':>6} {'click s':>8} {'1st':>6} {'GN peer s':>10} "
          f"{'GN tris':>11}")
    for r in rows:
        peer = r.get("peer")
        peer_s = f"{peer[0]:10.3f}" if peer else f"{'-':>10}"
        peer_t = f"{peer[1]:11,}" if peer else f"{'-':>11}"
        print(
            f"{r['stitches']:9,} {r['triangles']:11,} {r['core_s']:8.3f} "
            f"{r['triangles'] / r['core_s'] / 1e6:8.2f} {r['floor_s']:8.4f} {r['fresh_s']:8.4f} "
            f"{r['mesh_s']:8.3f} {r['mesh_first_s']:6.3f} {r['click_s']:8.3f} "
            f"{r['click_first_s']:6.3f} {peer_s} {peer_t}"
        )
    print()
    print("core: knitwear.knit alone; floor: copying its output bytes once (NumPy) into "
          "touched memory; fresh: into newly allocated memory; mesh: "
          "Blender mesh from the arrays; click: Knit operator to finished object; 1st: the "
          "first of a face count (builds the cached triangle template); GN peer: "
          f"Geometry Nodes loop instancing + sweep, ring {RING}, {SAMPLES} samples per loop.")


def main() -> None:
    args = parse_args()
    start_blender(args.zip)
    import bpy

    print(f"bench: Blender {bpy.app.version_string}, {os.cpu_count()} CPUs, "
          f"{args.repeats} repeats per figure")
    rows = []
    for n in args.stitches:
        row = bench(n, args.repeats, not args.no_peer)
        rows.append(row)
        print(f"bench: {row['stitches']:,} stitches done")
    print_table(rows)


if __name__ == "__main__":
    main()
