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

import inspect
import textwrap
from typing import Any

from . import settings_text
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

    Returns a `KnitResult`: the mesh (``vertices``, ``triangles``, ``colors``, ``normals``...)
    and the yarn (``centerline_points`` split by ``course_offsets``) as NumPy arrays in the
    surface's object space, scene units (metres by default), and ``stats`` (docs/stats.md).
    Raises `KnitError` (`SurfaceError`, `PatternError`, `ParameterError`, `BudgetError`,
    `CancelledError`) for anything a caller can get wrong; nothing is kept then.

    Besides the settings below, ``gauge=(stitches, rows)`` per 10 cm, ``stitch_size``
    (width, height) to pin, ``colors`` (a `ColorPattern`) or ``color_image`` (float32
    (H, W, 3|4) over (u,v)), ``threads``, ``budget_bytes`` (4 GiB), ``measure_clearance``
    (clearance and interlock into ``stats``), and for camera-driven detail ``camera`` (a
    `Camera`), ``detail_px=(full, mid, texture)`` pixels, ``mid_quality``, ``far_quality``,
    ``stitch_levels`` and ``seen_triangles`` (docs/settings.md, docs/detail.md).

    Settings, each declared once in the core (`settings()` lists them):

    """
    return Knit(surface, pattern, **settings).build(surface)


def _document_knit() -> None:
    """Give `knit` `Knit`'s whole keyword signature and each setting's meaning, default and
    range, read from the core's table, so `help(knitwear.knit)` is the reference."""
    params = list(inspect.signature(Knit).parameters.values())
    knit.__signature__ = inspect.Signature(params, return_annotation=KnitResult)  # type: ignore[attr-defined]
    table = settings_text.help_text(settings())
    knit.__doc__ = (knit.__doc__ or "").rstrip(" ") + textwrap.indent(table, "    ") + "\n"


_document_knit()


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
