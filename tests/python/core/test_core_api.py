"""The core's Python API without Blender: shapes, dtypes, errors on bad buffers, no panics."""

from __future__ import annotations

import time

import knitwear
import numpy as np
import pytest


def plane_grid(
    rows: int = 24, cols: int = 24, w: float = 0.1, h: float = 0.08
) -> tuple[np.ndarray, np.ndarray]:
    u, v = np.meshgrid(np.linspace(0, 1, cols), np.linspace(0, 1, rows))
    pos = np.stack([u * w, v * h, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return pos, nrm


def quad_mesh() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    pos = np.array([[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0, 0.1, 0]], np.float32)
    nrm = np.tile(np.array([0, 0, 1], np.float32), (4, 1))
    tris = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    uvs = np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], np.float32)
    return pos, nrm, tris, uvs


def test_knit_returns_blender_ready_buffers() -> None:
    surface = knitwear.GridSurface(*plane_grid())
    r = knitwear.knit(surface, knitwear.Pattern.preset("rib_2x2"), courses=10, wales=12)
    v, t, e = r.vertices, r.triangles, r.edges
    assert v.dtype == np.float32 and v.ndim == 2 and v.shape[1] == 3
    assert t.dtype == np.int32 and t.shape[1] == 3
    assert e.dtype == np.int32 and e.shape[1] == 2
    assert r.corner_edges.dtype == np.int32 and r.corner_edges.shape == (3 * len(t),)
    assert r.colors.dtype == np.float32 and r.colors.shape == (len(v), 4)
    for a in (v, t, e, r.colors, r.corner_edges, r.centerline_points):
        assert a.flags["C_CONTIGUOUS"]
    assert t.min() >= 0 and t.max() < len(v)
    assert np.isfinite(v).all()
    offsets = r.course_offsets
    # Ten courses, then the cast-on under the first and the bind-off over the last.
    assert offsets.shape == (13,) and offsets[0] == 0 and offsets[-1] == len(r.centerline_points)
    assert r.yarn_course.tolist() == list(range(10)) + [0, 9]
    assert r.stats["stitches"] == 120 and r.stats["triangles"] == len(t)
    # The yarn of course i is the slice between its offsets.
    yarn = r.centerline_points[offsets[3] : offsets[4]]
    assert len(yarn) > 12 * 6
    assert r.yarn_radius > 0


def test_mesh_surface_and_gauge() -> None:
    surface = knitwear.MeshSurface(*quad_mesh())
    assert surface.extent == pytest.approx((0.1, 0.1), rel=1e-4)
    r = knitwear.knit(surface, knitwear.Pattern.preset("stockinette"), gauge=(20, 28))
    # 10 cm at 20 stitches and 28 rows per 10 cm.
    assert (r.stats["wales"], r.stats["courses"]) == (20, 28)
    # Default yarn: a quarter of a stitch wide.
    assert 2 * r.yarn_radius == pytest.approx(0.25 * r.stats["stitch_width"], rel=1e-4)


def test_triangle_index_dtypes() -> None:
    pos, nrm, tris, uvs = quad_mesh()
    for dtype in (np.int32, np.uint32, np.int64):
        knitwear.MeshSurface(pos, nrm, tris.astype(dtype), uvs)
    with pytest.raises(knitwear.SurfaceError, match="int32"):
        knitwear.MeshSurface(pos, nrm, tris.astype(np.float32), uvs)
    with pytest.raises(knitwear.SurfaceError):
        knitwear.MeshSurface(pos, nrm, np.array([[0, 1, 9]], np.int32), uvs[:1])
    with pytest.raises(knitwear.SurfaceError):
        knitwear.MeshSurface(pos, nrm, np.array([[0, 1, -1]], np.int64), uvs[:1])


def with_value(a: np.ndarray, index: int, value: float) -> np.ndarray:
    out = a.copy()
    out.flat[index] = value
    return out


@pytest.mark.parametrize(
    "mutate, match",
    [
        (lambda p: p.astype(np.float64), "float32"),
        (lambda p: np.asfortranarray(p), "C-contiguous"),
        (lambda p: p[:, ::2], "C-contiguous"),
        (lambda p: p[..., :2].copy(), "shape"),
        (lambda p: p[:0], "2x2|at least"),
        (lambda p: with_value(p, 7, np.nan), "finite|NaN"),
        (lambda p: with_value(p, 5, np.inf), "finite|NaN|inf"),
        (lambda p: [[1.0, 2.0, 3.0]], "float32"),
    ],
)
def test_bad_grid_buffers_raise_surface_error(mutate, match: str) -> None:  # noqa: ANN001
    pos, nrm = plane_grid()
    bad = mutate(pos)
    with pytest.raises(knitwear.SurfaceError, match=match):
        knitwear.GridSurface(bad, nrm if getattr(bad, "shape", None) == nrm.shape else bad)


def test_read_only_buffers_are_accepted() -> None:
    pos, nrm = plane_grid()
    pos.setflags(write=False)
    nrm.setflags(write=False)
    surface = knitwear.GridSurface(pos, nrm)
    result = knitwear.knit(surface, knitwear.Pattern.preset("garter"), courses=4, wales=4)
    assert result.vertices.size


def test_degenerate_surface() -> None:
    pos = np.zeros((8, 8, 3), np.float32)
    nrm = np.zeros_like(pos)
    with pytest.raises(knitwear.SurfaceError):
        knitwear.knit(knitwear.GridSurface(pos, nrm), knitwear.Pattern.preset("garter"))


def test_every_error_is_a_knit_error_and_never_a_panic() -> None:
    surface = knitwear.GridSurface(*plane_grid())
    pattern = knitwear.Pattern.preset("seed")
    cases = [
        dict(courses=0),
        dict(wales=-3),
        dict(gauge=(0.0, 28.0)),
        dict(gauge=(float("nan"), 28.0)),
        dict(yarn_radius=-1.0),
        dict(yarn_radius=1.0),
        dict(ring_segments=2),
        dict(samples_per_loop=1),
        dict(fluffiness=99.0),
        dict(threads=0),
        dict(color_image=np.zeros((0, 4, 4), np.float32)),
    ]
    for kwargs in cases:
        with pytest.raises(knitwear.KnitError):
            knitwear.knit(surface, pattern, **kwargs)
    with pytest.raises(knitwear.InternalError):
        knitwear._core._force_internal_error()
    # The panic hook's exception is our class, catchable with `except Exception`.
    assert issubclass(knitwear.InternalError, Exception)


def test_absurd_stitch_counts_fail_fast_naming_the_size() -> None:
    surface = knitwear.GridSurface(*plane_grid())
    start = time.perf_counter()
    with pytest.raises(knitwear.BudgetError, match="GiB"):
        knitwear.knit(surface, knitwear.Pattern.preset("stockinette"), courses=31623, wales=31623)
    elapsed = time.perf_counter() - start
    print(f"10^9 stitches refused in {elapsed * 1000:.1f} ms")
    with pytest.raises(knitwear.BudgetError):
        knitwear.knit(surface, knitwear.Pattern.preset("stockinette"), budget_bytes=1000)


def test_patterns() -> None:
    names = knitwear.Pattern.presets()
    for required in ("stockinette", "reverse_stockinette", "garter", "rib_1x1", "rib_2x2",
                     "seed", "moss", "basketweave"):
        assert required in names
    p = knitwear.Pattern.from_chart("kkpp\nppkk\n")
    assert (p.width, p.height) == (4, 2)
    assert knitwear.Pattern.from_chart(p.chart()).chart() == p.chart()
    with pytest.raises(knitwear.PatternError, match=r"row 1, column 3.*'x'"):
        knitwear.Pattern.from_chart("kkpp\nkkxp")
    with pytest.raises(knitwear.PatternError, match="row"):
        knitwear.Pattern.from_chart("kkpp\nkk")
    with pytest.raises(knitwear.PatternError, match="presets are"):
        knitwear.Pattern.preset("fishermans_rib_deluxe")
    with pytest.raises(knitwear.PatternError):
        knitwear.ColorPattern([(1, 0, 0)], "012")


def test_colors_from_chart_and_image() -> None:
    surface = knitwear.GridSurface(*plane_grid())
    red, blue = (0.9, 0.05, 0.05), (0.05, 0.05, 0.9)
    colors = knitwear.ColorPattern([red, blue], "01\n10")
    r = knitwear.knit(surface, knitwear.Pattern.preset("stockinette"), courses=6, wales=6,
                      colors=colors, color_variation=0.0)
    rgb = r.colors[:, :3]
    assert np.isclose(rgb, red).all(axis=1).sum() > len(rgb) // 3
    assert np.isclose(rgb, blue).all(axis=1).sum() > len(rgb) // 3
    # An image: left half green, right half yellow.
    img = np.zeros((8, 8, 4), np.float32)
    img[:, :4] = (0.0, 0.8, 0.0, 1.0)
    img[:, 4:] = (0.8, 0.8, 0.0, 1.0)
    r = knitwear.knit(surface, knitwear.Pattern.preset("stockinette"), courses=6, wales=8,
                      color_image=img, color_variation=0.0)
    left = r.vertices[:, 0] < 0.03
    right = r.vertices[:, 0] > 0.07
    assert (r.colors[left, 0] < 0.2).mean() > 0.9
    assert (r.colors[right, 0] > 0.6).mean() > 0.9


def test_determinism_and_seed() -> None:
    surface = knitwear.GridSurface(*plane_grid())
    pattern = knitwear.Pattern.preset("moss")
    runs = [knitwear.knit(surface, pattern, seed=3, threads=t) for t in (1, 2, 8)]
    for r in runs[1:]:
        assert runs[0].vertices.tobytes() == r.vertices.tobytes()
        assert runs[0].colors.tobytes() == r.colors.tobytes()
    other = knitwear.knit(surface, pattern, seed=4, threads=2)
    assert other.vertices.tobytes() != runs[0].vertices.tobytes()


def test_clearance_is_exposed() -> None:
    surface = knitwear.GridSurface(*plane_grid())
    r = knitwear.knit(surface, knitwear.Pattern.preset("rib_1x1"), measure_clearance=True)
    # Inside the interlock a 1x1 rib keeps about 0.97 on a sheet; 0.5 is the plain floor.
    assert r.stats["clearance_min"] >= 0.5
    assert knitwear.measure_clearance(r) == pytest.approx(
        (r.stats["clearance_min"], r.stats["clearance_p01"])
    )


def test_interlock_is_exposed_and_whole() -> None:
    """Every course interlocks with the one below (docs/design.md section 3): all the crossings
    between a course and the loops it is pulled through are the right way round."""
    surface = knitwear.GridSurface(*plane_grid())
    for name in ("stockinette", "rib_1x1", "seed", "cable_c4"):
        r = knitwear.knit(surface, knitwear.Pattern.preset(name), measure_clearance=True)
        decided, agree = r.stats["interlock"]
        assert decided > 0 and agree == decided, (name, decided, agree)
        # Finished with a cast-on and a bind-off: every loop is held, every stitch pulled
        # through one.
        assert r.stats["free_loops"] == (0, 0), name
    plain = knitwear.knit(surface, knitwear.Pattern.preset("stockinette"))
    assert plain.stats["interlock"] is None and plain.stats["free_loops"] is None


def test_live_loops_leave_the_edges_unfinished() -> None:
    """`live_loops=True` knits the fabric alone: the same yarn, without the cast-on and the
    bind-off, so the last course's loops and the first course's feet hang free."""
    surface = knitwear.GridSurface(*plane_grid())
    pattern = knitwear.Pattern.preset("stockinette")
    finished = knitwear.knit(surface, pattern, measure_clearance=True)
    live = knitwear.knit(surface, pattern, measure_clearance=True, live_loops=True)
    wales = live.stats["wales"]
    assert finished.stats["yarn_pieces"] == live.stats["yarn_pieces"] + 2
    assert live.stats["free_loops"] == (wales, wales)
    n = len(live.centerline_points)
    np.testing.assert_array_equal(finished.centerline_points[:n], live.centerline_points)


def test_cover_is_exposed_and_grows_with_the_yarn() -> None:
    surface = knitwear.GridSurface(*plane_grid())
    stockinette = knitwear.Pattern.preset("stockinette")
    inner = (0.02, 0.02, 0.08, 0.06)
    thin = knitwear.knit(surface, stockinette, yarn_radius=0.0004)
    thick = knitwear.knit(surface, stockinette, yarn_radius=0.0006)
    c_thin = knitwear.measure_cover(thin, inner, 400)
    c_thick = knitwear.measure_cover(thick, inner, 400)
    assert 0.3 < c_thin < c_thick < 1.0, (c_thin, c_thick)
    # Nothing of the knit lies out beyond the sheet.
    assert knitwear.measure_cover(thick, (1.0, 1.0, 2.0, 2.0), 50) == 0.0
    with pytest.raises(knitwear.ParameterError, match="bounds"):
        knitwear.measure_cover(thick, (0.1, 0.0, 0.0, 0.1))
    with pytest.raises(knitwear.ParameterError, match="resolution"):
        knitwear.measure_cover(thick, inner, 0)


def test_the_stitch_spread_measures_the_maps_stretch() -> None:
    """`stats["stitch_spread"]`: the 5th and 95th percentiles of the stitches' widths and
    heights over their means, and the share more than 15% off; measured where the stitch size
    is not pinned."""
    pattern = knitwear.Pattern.preset("stockinette")
    flat = knitwear.GridSurface(*plane_grid())
    even = knitwear.knit(flat, pattern, courses=12, wales=12).stats["stitch_spread"]
    assert even["stretched"] == 0.0
    assert all(abs(x - 1.0) < 1e-3 for x in (*even["width"], *even["height"]))
    # u squared along x: stitches at one side far wider than at the other.
    u, v = np.meshgrid(np.linspace(0, 1, 33), np.linspace(0, 1, 9))
    pos = np.stack([0.1 * (0.2 * u + 0.8 * u**2), 0.1 * v, 0 * u], -1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    squeezed = knitwear.GridSurface(pos, nrm)
    spread = knitwear.knit(squeezed, pattern, courses=12, wales=12).stats["stitch_spread"]
    assert spread["width"][0] < 0.5 < 1.5 < spread["width"][1]
    assert abs(spread["height"][0] - 1) < 1e-3 and spread["stretched"] > 0.5
    pinned = knitwear.knit(squeezed, pattern, courses=12, wales=12, stitch_size=(0.008, 0.008))
    assert pinned.stats["stitch_spread"] is None


def test_stitches_cut_by_an_islands_edge_are_lost_fabric_not_empty_space() -> None:
    """Two UV islands with empty UV space between them: the stitches there are skipped, and
    only those an island's edge cuts through count as lost fabric."""
    # The islands end at u = 0.415 and 0.585: through the middle of a stitch of 21 wales.
    pos = np.array(
        [[0, 0, 0], [0.0415, 0, 0], [0.0415, 0.1, 0], [0, 0.1, 0],
         [0.0585, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0.0585, 0.1, 0]], np.float32,
    )
    nrm = np.tile(np.array([0, 0, 1], np.float32), (8, 1))
    tris = np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]], np.int32)
    uvs = pos[tris][..., :2] / 0.1
    surface = knitwear.MeshSurface(pos, nrm, tris, uvs.astype(np.float32))
    pattern = knitwear.Pattern.preset("stockinette")
    s = knitwear.knit(surface, pattern, courses=20, wales=21).stats
    assert s["stitches"] + s["stitches_skipped"] == 420
    # In every course: the stitches wholly in the gap (wales 9 to 11) were never fabric; the
    # two the islands' edges cut through (wales 8 and 12) were.
    assert s["stitches_lost"] == 2 * 20 and s["stitches_skipped"] == 5 * 20, s
