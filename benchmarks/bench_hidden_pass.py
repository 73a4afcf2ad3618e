"""The hidden-yarn pass alone (issue 20): a 12 x 10 cm sheet at the default gauge (672
stitches, all at full detail) seen whole by a 1080p camera at 15 cm, in the core, for
`hidden_supersampling` 1 to 3.

    PYTHONPATH=build/site .venv/bin/python benchmarks/bench_hidden_pass.py [--repeats 5]

Prints, per pattern and supersampling, the median over --repeats knits of
`stats["hidden_pass_seconds"]` on every thread and on one, the triangles built and the share
the pass drops. The issue's target: 50 ms for one 1080p view at 2 x 2 samples a pixel.
Then the pass for an animation of --frames sampled frames (issue 23): the same view in every
frame, first on the sheet as knitted, then with the sheet in a pose of its own per frame
(lifted a millimetre a frame), which builds the knit once per pose. No assertions: figures
only.
"""

from __future__ import annotations

import argparse
import statistics

import knitwear
import numpy as np

RESOLUTION = (1920, 1080)


def sheet(lift: float = 0.0) -> knitwear.GridSurface:
    """The corpus's test sheet: 12 x 10 cm in the z = ``lift`` plane."""
    u, v = np.meshgrid(np.linspace(0, 1, 24), np.linspace(0, 1, 24))
    pos = np.stack([u * 0.12, v * 0.10, np.full_like(u, lift)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return knitwear.GridSurface(pos, nrm)


def camera(frames: int = 1, poses: list[knitwear.GridSurface] | None = None) -> knitwear.Camera:
    """A perspective camera 15 cm from the sheet's middle, a 34-degree vertical field of
    view, looking down at it from in front (OpenGL clip conventions, row-major)."""
    eye, target = np.array([0.06, -0.05, 0.12]), np.array([0.06, 0.05, 0.0])
    forward = (target - eye) / np.linalg.norm(target - eye)
    side = np.cross(forward, [0.0, 1.0, 0.0])
    side /= np.linalg.norm(side)
    up = np.cross(side, forward)
    view = np.eye(4)
    view[0, :3], view[1, :3], view[2, :3] = side, up, -forward
    view[:3, 3] = -view[:3, :3] @ eye
    near, far, aspect = 0.01, 10.0, RESOLUTION[0] / RESOLUTION[1]
    focal = 1.0 / np.tan(0.3)
    projection = np.zeros((4, 4))
    projection[0, 0], projection[1, 1] = focal / aspect, focal
    projection[2, 2] = (far + near) / (near - far)
    projection[2, 3] = 2.0 * far * near / (near - far)
    projection[3, 2] = -1.0
    clip = (projection @ view).astype(np.float32)
    return knitwear.Camera(
        np.stack([clip] * frames),
        np.array([[*eye, 1.0]] * frames, np.float32),
        RESOLUTION,
        poses=poses,
    )


def measured(
    surface: knitwear.GridSurface,
    pattern: knitwear.Pattern,
    view: knitwear.Camera,
    repeats: int,
    **settings: int,
) -> str:
    """``repeats`` knits with the pass: the median pass time, the triangles built and the
    share dropped, as a row's figures."""
    seconds, result = [], None
    for _ in range(repeats):
        result = knitwear.knit(
            surface, pattern, camera=view, cull_hidden=True, cull_hidden_min_triangles=0,
            **settings,
        )
        seconds.append(result.stats["hidden_pass_seconds"])
    assert result is not None
    hidden = result.stats["triangles_hidden"]
    built = len(result.triangles) + hidden
    return f"{statistics.median(seconds):8.3f} {built:>10,} {hidden / built:6.1%}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=5, help="knits per figure (median)")
    parser.add_argument("--patterns", nargs="*", default=["stockinette", "cable_c6"])
    parser.add_argument("--frames", type=int, default=25, help="sampled frames, animated")
    args = parser.parse_args()
    surface, view = sheet(), camera()
    print(f"{'pattern':12} {'samples':>7} {'threads':>7} {'pass s':>8} {'triangles':>10} dropped")
    for name in args.patterns:
        pattern = knitwear.Pattern.preset(name)
        # The first knit of a pattern tunes its loop shapes: not what is measured here.
        knitwear.knit(surface, pattern)
        for supersampling in (1, 2, 3):
            for threads in (0, 1):
                figures = measured(
                    surface, pattern, view, args.repeats, hidden_supersampling=supersampling,
                    **({"threads": threads} if threads else {}),
                )
                print(f"{name:12} {supersampling:>5}^2 {threads or 'all':>7} {figures}", flush=True)
    animated(surface, args.frames, args.repeats)


def animated(surface: knitwear.GridSurface, frames: int, repeats: int) -> None:
    """The pass for ``frames`` views of stockinette at 2 x 2 samples, without and with a pose
    per view."""
    pattern = knitwear.Pattern.preset("stockinette")
    poses = [sheet(0.001 * f) for f in range(frames)]
    print(f"\n{frames} frames, 2^2 samples: {'poses':>6} {'pass s':>8} {'triangles':>10} dropped")
    for posed in (False, True):
        view = camera(frames, poses if posed else None)
        figures = measured(surface, pattern, view, repeats, hidden_supersampling=2)
        print(f"{'':26}{'yes' if posed else 'no':>6} {figures}", flush=True)


if __name__ == "__main__":
    main()
