"""How fast a running core call stops when asked: `knitwear.cancel()` from another thread
(the add-on's Esc). The goal is under 0.5 s for every kind of long call.

    PYTHONPATH=build/site .venv/bin/python benchmarks/bench_cancel.py

For each long call it prints how long the call runs when left alone, and the seconds from
`cancel()` to the `CancelledError` (the median of --repeats cancels at different moments).
No assertions: figures only.
"""

from __future__ import annotations

import argparse
import statistics
import threading
import time
from collections.abc import Callable

import knitwear
import numpy as np


def sheet(size: float = 0.5, n: int = 64) -> knitwear.GridSurface:
    u, v = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    pos = np.stack([u * size, v * size, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return knitwear.GridSurface(pos, nrm)


def fresh_chart(seed: int) -> knitwear.Pattern:
    rng = np.random.default_rng(seed)
    return knitwear.Pattern.from_chart(
        "\n".join("".join(rng.choice(["k", "p"], 12)) for _ in range(12))
    )


def filling_camera() -> knitwear.Camera:
    m = np.eye(4, dtype=np.float32)
    m[0, 0] = m[1, 1] = 4.0
    m[0, 3] = m[1, 3] = -1.0
    m[2, 2] = 0.1
    return knitwear.Camera(m, np.array([0, 0, 1, 0], np.float32), (3840, 2160))


def stop_seconds(call: Callable[[], object], after: float) -> float | None:
    """Seconds from cancel() (sent `after` s into the call) to the call's end; None if the
    call finished before the cancel."""
    sent: list[float] = []

    def fire() -> None:
        sent.append(time.perf_counter())
        knitwear.cancel()

    timer = threading.Timer(after, fire)
    timer.start()
    try:
        call()
    except knitwear.CancelledError:
        return time.perf_counter() - sent[0]
    finally:
        timer.cancel()
    return None


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    surface = sheet()
    stock = knitwear.Pattern.preset("stockinette")
    knitwear.knit(sheet(0.05, 8), stock, courses=4, wales=4)  # stockinette tuned once
    seeds = iter(range(1000, 2000))
    calls: dict[str, Callable[[], object]] = {
        "first knit (12x12 chart tuned)": lambda: knitwear.knit(
            sheet(0.05, 12), fresh_chart(next(seeds)), courses=12, wales=12
        ),
        "build 250x250 stitches": lambda: knitwear.knit(surface, stock, courses=250, wales=250),
        "hidden-yarn pass 4K x4": lambda: knitwear.Knit(
            surface,
            stock,
            courses=120,
            wales=120,
            camera=filling_camera(),
            cull_hidden=True,
            hidden_supersampling=4,
        ),
        "knitwear texture 4096^2": lambda: knitwear.knit_texture(
            surface, stock, courses=200, wales=200, width=4096, height=4096
        ),
        "plush 400x400": lambda: knitwear.plush(surface, courses=400, wales=400, slices=8),
    }
    print(f"{'call':34} {'alone s':>8} {'stop s (median, max)':>22}")
    for name, call in calls.items():
        t = time.perf_counter()
        call()
        alone = time.perf_counter() - t
        stops = [
            s
            for k in range(args.repeats)
            if (s := stop_seconds(call, alone * (0.2 + 0.6 * k / max(1, args.repeats - 1))))
            is not None
        ]
        shown = f"{statistics.median(stops):.3f}, {max(stops):.3f}" if stops else "finished first"
        print(f"{name:34} {alone:8.2f} {shown:>22}")


if __name__ == "__main__":
    main()
