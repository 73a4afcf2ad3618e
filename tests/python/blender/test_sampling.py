"""What the core is given: grid orientation, cyclic flags, density, fallbacks. A spy wraps
the core's surface constructors and records their arguments."""

from types import ModuleType
from typing import Any

import bpy
import numpy as np
import pytest
from blender_scenes import SMALL, data_counts, nurbs_patch, nurbs_sphere, snapshot


class Spy:
    def __init__(self, core: ModuleType, monkeypatch: pytest.MonkeyPatch) -> None:
        self.calls: list[tuple[str, tuple[Any, ...], dict[str, Any]]] = []
        for name in ("GridSurface", "MeshSurface", "Knit"):
            real = getattr(core, name)
            monkeypatch.setattr(core, name, self._wrap(name, real))

    def _wrap(self, name: str, real: Any) -> Any:
        def record(*args: Any, **kwargs: Any) -> Any:
            self.calls.append((name, args, kwargs))
            return real(*args, **kwargs)

        return record

    def last(self, name: str) -> tuple[tuple[Any, ...], dict[str, Any]]:
        found = [(a, k) for n, a, k in self.calls if n == name]
        assert found, f"{name} was not called; calls: {[c[0] for c in self.calls]}"
        return found[-1]


@pytest.fixture
def spy(core: ModuleType, monkeypatch: pytest.MonkeyPatch) -> Spy:
    return Spy(core, monkeypatch)


def _points(spline: bpy.types.Spline) -> np.ndarray:
    co = np.empty(len(spline.points) * 4, dtype=np.float32)
    spline.points.foreach_get("co", co)
    return co.reshape(spline.point_count_v, spline.point_count_u, 4)[..., :3]


def test_grid_rows_run_along_v_columns_along_u(api: ModuleType, spy: Spy) -> None:
    """Known answer: core positions[i, j] = s(u_j, v_i). The patch's u direction is the
    direction of its control points' fast index."""
    source = nurbs_patch()
    api.knit_result(source, **SMALL, direction="U")
    (grid, _normals), kwargs = spy.last("GridSurface")
    assert grid.dtype == np.float32 and grid.flags.c_contiguous
    rows, cols, _ = grid.shape
    pts = _points(source.data.splines[0])
    u_dir = pts[0, -1] - pts[0, 0]
    v_dir = pts[-1, 0] - pts[0, 0]
    along_row = grid[0, -1] - grid[0, 0]
    along_col = grid[-1, 0] - grid[0, 0]
    unit = np.linalg.norm
    assert np.dot(along_row, u_dir) / (unit(along_row) * unit(u_dir)) > 0.99
    assert np.dot(along_col, v_dir) / (unit(along_col) * unit(v_dir)) > 0.99
    # Dense enough: at least SAMPLES_PER_STITCH samples per stitch each way.
    assert cols >= 4 * SMALL["wales"] and rows >= 4 * SMALL["courses"]
    assert kwargs == {"cyclic_u": False, "cyclic_v": False}
    # The source keeps its own resolution.
    assert source.data.splines[0].resolution_u == 4


def test_sphere_is_knitted_in_the_round(api: ModuleType, spy: Spy) -> None:
    source = nurbs_sphere()
    spline = source.data.splines[0]
    assert (spline.use_cyclic_u, spline.use_cyclic_v) == (False, True)
    api.knit_result(source, **SMALL)  # direction AUTO
    (grid, normals), kwargs = spy.last("GridSurface")
    # Courses go round the closed direction, which becomes the core's (cyclic) u.
    assert kwargs == {"cyclic_u": True, "cyclic_v": False}
    # Rows run from pole to pole: the first and last rows are the poles (points).
    assert np.ptp(grid[0], axis=0).max() < 1e-4
    assert np.ptp(grid[-1], axis=0).max() < 1e-4
    # Normals point out of the sphere.
    centre = grid.reshape(-1, 3).mean(axis=0)
    assert np.mean(np.sum((grid - centre) * normals, axis=-1) > 0) > 0.95


def test_explicit_direction_v_swaps_the_grid(api: ModuleType, spy: Spy) -> None:
    source = nurbs_sphere()
    api.knit_result(source, **SMALL, direction="U")
    (grid, _), kwargs = spy.last("GridSurface")
    assert kwargs == {"cyclic_u": False, "cyclic_v": True}
    assert np.ptp(grid[:, 0], axis=0).max() < 1e-4  # first column is a pole


def test_topology_changing_modifier_falls_back_to_the_uv_map(
    api: ModuleType, spy: Spy
) -> None:
    source = nurbs_patch()
    source.modifiers.new("Subdivision", "SUBSURF")
    before = snapshot(source)
    counts = data_counts()
    result = api.knit_result(source, **SMALL)
    (mesh_positions, _normals, triangles, uvs), _ = spy.last("MeshSurface")
    assert "GridSurface" not in [name for name, _, _ in spy.calls]
    assert uvs.shape == (len(triangles), 3, 2) and uvs.dtype == np.float32
    assert len(result.triangles) > 0
    assert snapshot(source) == before
    assert data_counts() == counts


def test_deforming_modifier_is_seen(api: ModuleType, spy: Spy) -> None:
    source = nurbs_patch()
    api.knit_result(source, **SMALL)
    (flat, _), _ = spy.last("GridSurface")
    modifier = source.modifiers.new("Cast", "CAST")
    modifier.factor = 1.0
    api.knit_result(source, **SMALL)
    (cast, _), _ = spy.last("GridSurface")
    assert cast.shape == flat.shape
    assert np.abs(cast - flat).max() > 0.02


def test_gauge_reaches_the_core_per_scene_unit(api: ModuleType, spy: Spy) -> None:
    source = nurbs_patch()
    source.scale = (0.05, 0.05, 0.05)
    bpy.context.scene.unit_settings.scale_length = 0.5
    bpy.context.view_layer.update()
    api.knit_result(source, size_mode="GAUGE", gauge_stitches=20.0, gauge_rows=28.0,
                    ring_segments=4, samples_per_loop=8)
    _, kwargs = spy.last("Knit")
    # The core counts stitches per 0.1 units: 20 per 10 cm is 10 per 0.1 units of 0.5 m.
    assert kwargs["gauge"] == pytest.approx((10.0, 14.0))
    assert kwargs["threads"] == bpy.context.scene.render.threads
    assert "courses" not in kwargs and "wales" not in kwargs
