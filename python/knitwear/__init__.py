"""knitwear: knitted yarn geometry on free-form surfaces (Rust core).

NumPy in, NumPy out, no Blender needed::

    import numpy as np
    import knitwear

    u, v = np.meshgrid(np.linspace(0, 1, 32), np.linspace(0, 1, 32))
    pos = np.stack([u * 0.2, v * 0.2, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1
    result = knitwear.knit(knitwear.GridSurface(pos, nrm), knitwear.Pattern.preset("rib_2x2"))
    result.vertices, result.triangles, result.colors  # (V,3) f32, (T,3) i32, (V,4) f32

Lengths are in scene units (metres by default); the gauge is stitches and rows per 10 cm.
Every error a user can cause is a :class:`KnitError`. Ctrl-C stops a long call (it raises
`KeyboardInterrupt`), and :func:`cancel` stops every running call from another thread.
"""

from typing import Any

from ._core import (
    BudgetError,
    Camera,
    CancelledError,
    ColorPattern,
    GridSurface,
    InternalError,
    Knit,
    KnitError,
    KnitResult,
    MeshSurface,
    ParameterError,
    Pattern,
    PatternError,
    PlushField,
    PlushResult,
    PlushView,
    SurfaceError,
    __version__,
    cancel,
    check_budget,
    fractal_noise,
    knit_texture,
    measure_clearance,
    measure_cover,
    plush,
    set_tuning_store,
    settings,
    tuning_store,
)


def knit(surface: GridSurface | MeshSurface, pattern: Pattern, **settings: Any) -> KnitResult:
    """Knit ``pattern`` over ``surface``: ``Knit(surface, pattern, **settings).build(surface)``.

    The keyword settings are `Knit`'s: every one `settings()` lists (declared once in the
    core, with its default, range and unit; the README's table is made from it), and
    ``gauge``, ``stitch_size``, ``colors``, ``color_image``, ``threads``, ``budget_bytes``,
    ``measure_clearance``, and for camera-driven detail ``camera`` (a `Camera`),
    ``detail_px``, ``mid_quality``, ``far_quality``, ``stitch_levels`` and
    ``seen_triangles``. ``stats["seconds"]`` is the build's.
    """
    return Knit(surface, pattern, **settings).build(surface)


__all__ = [
    "BudgetError",
    "Camera",
    "CancelledError",
    "ColorPattern",
    "GridSurface",
    "InternalError",
    "Knit",
    "KnitError",
    "KnitResult",
    "MeshSurface",
    "ParameterError",
    "Pattern",
    "PatternError",
    "PlushField",
    "PlushResult",
    "PlushView",
    "SurfaceError",
    "__version__",
    "cancel",
    "check_budget",
    "fractal_noise",
    "knit",
    "knit_texture",
    "measure_clearance",
    "measure_cover",
    "settings",
    "plush",
    "set_tuning_store",
    "tuning_store",
]
