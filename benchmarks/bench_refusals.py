"""How long the extension takes to refuse what it cannot knit (issue 18: refusal comes before
sampling, within 0.5 s): a 500 m NURBS surface at a knitting gauge, absurd counts on a NURBS
surface, a 1024 x 1024 chart, a camera of 65536^2 pixels culling hidden yarn. Prints the
median seconds of each and the error class; the Blender scene is reset between runs.

    .venv/bin/python benchmarks/bench_refusals.py [--repeats 5] [--zip dist/knitwear-0.1.0.zip]
"""

import argparse
import os
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from bench_setup import start_blender


def parse_args() -> argparse.Namespace:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--zip", type=Path, default=None)
    return ap.parse_args()


def main() -> None:
    args = parse_args()
    start_blender(args.zip)
    import bpy
    import knitwear
    import numpy as np
    from bl_ext.user_default.knitwear import api

    def patch(scale: float) -> bpy.types.Object:
        for old in list(bpy.data.objects):
            bpy.data.objects.remove(old)
        bpy.ops.surface.primitive_nurbs_surface_surface_add()
        obj = bpy.context.active_object
        obj.scale = (scale, scale, scale)
        bpy.context.view_layer.update()
        return obj

    def sheet() -> knitwear.GridSurface:
        u, v = np.meshgrid(np.linspace(0, 0.05, 8), np.linspace(0, 0.05, 8))
        p = np.stack([u, v, np.zeros_like(u)], axis=-1).astype(np.float32)
        n = np.zeros_like(p)
        n[..., 2] = 1
        return knitwear.GridSurface(p, n)

    chart = "\n".join(["k" * 1024] * 1024)
    camera = knitwear.Camera(np.eye(4, dtype=np.float32), np.array([0, 0, 1, 1], np.float32),
                             (65536, 65536))
    cases: dict[str, Callable[[], Any]] = {
        "500 m NURBS surface, default gauge": lambda: api.knit_object(patch(500.0)),
        "NURBS patch, 10^6 x 10^6 counts": lambda: api.knit_object(
            patch(1.0), size_mode="COUNTS", courses=10**6, wales=10**6),
        "1024 x 1024 chart": lambda: knitwear.Pattern.from_chart(chart),
        "65536^2 camera, cull hidden": lambda: knitwear.knit(
            sheet(), knitwear.Pattern.preset("stockinette"), courses=8, wales=8,
            camera=camera, cull_hidden=True),
    }
    print(f"bench: Blender {bpy.app.version_string}, {os.cpu_count()} CPUs, "
          f"medians over {args.repeats} runs")
    print(f"{'case':40} {'seconds':>8}  error")
    for name, run in cases.items():
        times, error = [], "none: it was not refused"
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            try:
                run()
            except knitwear.KnitError as e:
                error = f"{type(e).__name__}: {str(e)[:60]}"
            times.append(time.perf_counter() - t0)
        print(f"{name:40} {float(np.median(times)):8.3f}  {error}")


if __name__ == "__main__":
    main()
