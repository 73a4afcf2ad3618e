"""Plush (warp-knit pile) from Python without Blender: shapes, dtypes, errors, cheap camera
updates equal to full builds, determinism."""

from __future__ import annotations

import math

import knitwear
import numpy as np
import pytest


def plane_grid(w: float = 0.1, h: float = 0.08) -> knitwear.GridSurface:
    u, v = np.meshgrid(np.linspace(0, 1, 16), np.linspace(0, 1, 16))
    pos = np.stack([u * w, v * h, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return knitwear.GridSurface(pos, nrm)


# Behind the default lean (30 degrees towards -v), 60 degrees up: sees most piles side on.
SIDE_EYE = (0.05, 0.30, 0.15)
SETTINGS = {"courses": 16, "wales": 20, "seed": 3}


def test_plush_returns_blender_ready_buffers() -> None:
    r = knitwear.plush(plane_grid(), eye=SIDE_EYE, slices=6, piles_per_stitch=4, **SETTINGS)
    piles = 16 * 20 * 4
    quads = piles * 6
    assert r.vertices.shape == (4 * quads, 3) and r.vertices.dtype == np.float32
    assert r.triangles.shape == (2 * quads, 3) and r.triangles.dtype == np.int32
    assert r.edges.shape == (5 * quads, 2) and r.edges.dtype == np.int32
    assert r.corner_edges.shape == (6 * quads,) and r.corner_edges.dtype == np.int32
    assert r.colors.shape == (4 * quads, 4) and r.colors.dtype == np.float32
    assert r.uvs.shape == (4 * quads, 2) and r.uvs.dtype == np.float32
    assert r.mask.shape == (4 * quads,) and r.mask.dtype == np.float32
    assert r.horizontal.shape == (piles,) and r.horizontal.dtype == np.uint8
    for a in (r.vertices, r.triangles, r.edges, r.corner_edges, r.colors, r.uvs, r.mask):
        assert a.flags["C_CONTIGUOUS"]
    assert r.triangles.min() == 0 and r.triangles.max() == len(r.vertices) - 1
    assert np.isfinite(r.vertices).all()
    s = r.stats
    assert s["piles"] == piles and s["piles_skipped"] == 0
    assert s["horizontal"] + s["vertical"] == piles
    assert s["horizontal"] == int(r.horizontal.sum()) and s["vertical"] > 0
    assert s["triangles"] == len(r.triangles) and s["vertices"] == len(r.vertices)
    # The mask follows the slice kind: 0 (round) on horizontal piles, 1 on vertical ones.
    per_pile = r.mask.reshape(piles, -1)
    assert ((per_pile == 0).all(axis=1) == (r.horizontal == 1)).all()
    # Corner edges name the triangle's own edges.
    e = np.sort(r.edges[r.corner_edges], axis=1)
    sides = np.sort(np.stack([r.triangles, np.roll(r.triangles, -1, axis=1)], axis=-1), axis=-1)
    np.testing.assert_array_equal(e, sides.reshape(-1, 2))
    # Root darker than tip; opaque.
    rgb = r.colors.reshape(piles, 6, 4, 4)
    assert (rgb[:, 0, :, 0] < rgb[:, -1, :, 0]).all()
    assert (r.colors[:, 3] == 1).all()
    field = r.field
    assert field.piles == piles and field.slices == 6
    assert field.roots.shape == (piles, 3) and field.directions.shape == (piles, 3)
    assert field.root_uvs.shape == (piles, 2) and field.normals.shape == (piles, 3)
    assert field.noise.shape == (32, 40, 3)  # one texel per pile: 2x2 piles per stitch
    assert s["pile_radius"] == pytest.approx(field.pile_radius)


def test_defaults_follow_the_stitch_size() -> None:
    r = knitwear.plush(plane_grid(), courses=16, wales=20)
    s = r.stats
    assert s["stitch_width"] == pytest.approx(0.1 / 20, rel=1e-5)
    assert s["pile_length"] == pytest.approx(2.5 * s["stitch_width"], rel=1e-5)
    assert s["pile_radius"] == pytest.approx(0.6 * min(0.1 / 20, 0.08 / 16), rel=1e-5)
    # No camera: each pile seen along its normal, so all horizontal at the default lean.
    assert s["vertical"] == 0
    # The gauge (48 wales, 64 courses per 10 cm) sets the counts when they are not given.
    g = knitwear.plush(plane_grid()).stats
    assert (g["wales"], g["courses"]) == (48, 51)


def test_camera_update_equals_a_full_build() -> None:
    r = knitwear.plush(plane_grid(), eye=(0.3, -0.2, 0.4), **SETTINGS)
    for kw in ({"eye": SIDE_EYE}, {"view_dir": (0.0, 1.0, -0.2)}, {}):
        full = knitwear.plush(plane_grid(), **kw, **SETTINGS)
        view = r.field.view(**kw)
        np.testing.assert_array_equal(view.vertices, full.vertices)
        np.testing.assert_array_equal(view.mask, full.mask)
        np.testing.assert_array_equal(view.horizontal, full.horizontal)
        assert view.stats["horizontal"] == full.stats["horizontal"]
        built = r.field.build(**kw)
        for name in ("vertices", "triangles", "edges", "corner_edges", "colors", "uvs", "mask"):
            np.testing.assert_array_equal(getattr(built, name), getattr(full, name))
        assert built.stats["topology_key"] == r.stats["topology_key"]
    # The topology never depends on the view.
    np.testing.assert_array_equal(r.triangles, full.triangles)


def test_determinism_and_seed() -> None:
    runs = [knitwear.plush(plane_grid(), eye=SIDE_EYE, threads=t, **SETTINGS) for t in (1, 2, 8)]
    for r in runs[1:]:
        assert r.vertices.tobytes() == runs[0].vertices.tobytes()
        assert r.colors.tobytes() == runs[0].colors.tobytes()
        assert r.horizontal.tobytes() == runs[0].horizontal.tobytes()
    other = knitwear.plush(plane_grid(), eye=SIDE_EYE, **{**SETTINGS, "seed": 4})
    assert other.vertices.tobytes() != runs[0].vertices.tobytes()


def test_fractal_noise() -> None:
    theta_max = 0.5
    base = knitwear.fractal_noise((64, 48), theta_max=theta_max, scales=(1,), seed=2)
    frac = knitwear.fractal_noise((64, 48), theta_max=theta_max, seed=2)
    assert base.shape == frac.shape == (48, 64, 3) and frac.dtype == np.float32
    np.testing.assert_allclose(np.linalg.norm(frac, axis=-1), 1.0, atol=1e-5)
    assert (frac[..., 2] >= math.cos(theta_max) - 1e-6).all()

    def neighbour_angle(n: np.ndarray) -> float:
        dots = np.concatenate([(n * np.roll(n, 1, axis=a)).sum(-1).ravel() for a in (0, 1)])
        return float(np.arccos(np.clip(dots, -1, 1)).mean())

    assert neighbour_angle(frac) < 0.5 * neighbour_angle(base)
    rgb = knitwear.fractal_noise((64, 48), theta_max=theta_max, seed=2, rgb=True)
    np.testing.assert_allclose(rgb, (frac + 1) / 2, atol=1e-6)
    assert knitwear.fractal_noise(8).shape == (8, 8, 3)
    r = knitwear.plush(plane_grid(), theta_max=theta_max, **SETTINGS)
    np.testing.assert_allclose(r.field.noise_rgb, (r.field.noise + 1) / 2, atol=1e-6)


def test_colors_and_press() -> None:
    red = (0.8, 0.1, 0.1)
    solid = knitwear.plush(plane_grid(), colors=red, slices=1, **SETTINGS)
    assert np.allclose(solid.colors[:, 0], 0.8 * (0.45 + 0.7 * 0.5))
    per_stitch = np.zeros((16, 20, 3), np.float32)
    per_stitch[:, 10:] = (0.0, 0.0, 1.0)
    r = knitwear.plush(plane_grid(), colors=per_stitch, **SETTINGS)
    right = r.field.root_uvs[:, 0] > 0.5
    rgb = r.colors.reshape(len(right), -1, 4)
    assert (rgb[right, :, 2] > 0).all() and (rgb[~right, :, 2] == 0).all()
    stripes = knitwear.ColorPattern.stripes([red, (0.1, 0.8, 0.1)], rows_each=2)
    assert knitwear.plush(plane_grid(), colors=stripes, **SETTINGS).colors.shape[1] == 4
    img = np.full((4, 4, 3), 0.5, np.float32)
    assert knitwear.plush(plane_grid(), color_image=img, **SETTINGS).colors.max() > 0
    # A press over the left half bends the pile there towards the fabric.
    press = np.zeros((8, 8), np.float32)
    press[:, :4] = 1.0
    p = knitwear.plush(plane_grid(), press=press, press_direction=0.0, **SETTINGS)
    left = p.field.root_uvs[:, 0] < 0.4
    z = p.field.directions[:, 2]
    assert z[left].mean() < 0.5 * z[~left & (p.field.root_uvs[:, 0] > 0.6)].mean()


@pytest.mark.parametrize(
    "kwargs",
    [
        {"slices": 0},
        {"slices": 1000},
        {"piles_per_stitch": 0},
        {"courses": 0},
        {"wales": -2},
        {"gauge": (0.0, 10.0)},
        {"pile_length": -1.0},
        {"pile_radius": float("nan")},
        {"theta_max": 1.0},
        {"theta_max": float("nan")},
        {"lean": (float("nan"), 0.0)},
        {"lean": (0.1,)},
        {"lean": (0.0, 0.0, -1.0)},
        {"noise_scales": (1, 0)},
        {"noise_scales": ()},
        {"noise_size": (0, 4)},
        {"eye": (0.0, float("nan"), 1.0)},
        {"eye": (0.0, 1.0)},
        {"view_dir": (0.0, 0.0, 0.0)},
        {"eye": (0, 0, 1), "view_dir": (0, 0, -1)},
        {"colors": (1.0, 0.0)},
        {"colors": np.zeros((3, 3, 3), np.float32)},
        {"colors": np.zeros((16, 20, 3), np.float64)},
        {"colors": (float("nan"), 0.0, 0.0)},
        {"press": np.full((4, 4), 2.0, np.float32)},
        {"press": np.zeros((4, 4, 1), np.float32)},
        {"press_strength": 3.0},
        {"press_direction": float("inf")},
        {"threads": 0},
    ],
)
def test_bad_settings_raise_parameter_errors(kwargs: dict) -> None:
    settings = {**SETTINGS, **kwargs}
    with pytest.raises(knitwear.ParameterError):
        knitwear.plush(plane_grid(), **settings)


def test_other_errors_are_knit_errors() -> None:
    with pytest.raises(knitwear.SurfaceError):
        knitwear.plush("not a surface")  # type: ignore[arg-type]
    with pytest.raises(knitwear.BudgetError, match="budget"):
        knitwear.plush(plane_grid(), courses=100_000, wales=100_000)
    with pytest.raises(knitwear.BudgetError):
        knitwear.plush(plane_grid(), budget_bytes=1000, **SETTINGS)
    r = knitwear.plush(plane_grid(), **SETTINGS)
    with pytest.raises(knitwear.ParameterError):
        r.field.view(eye=(float("inf"), 0, 0))
    with pytest.raises(knitwear.BudgetError):
        r.field.build(budget_bytes=10)
    for bad in ((0, 4), -1, "big"):
        with pytest.raises(knitwear.ParameterError):
            knitwear.fractal_noise(bad)  # type: ignore[arg-type]
    with pytest.raises(knitwear.ParameterError):
        knitwear.fractal_noise(8, theta_max=0.9)
    assert issubclass(knitwear.ParameterError, knitwear.KnitError)


def test_mesh_surface_skips_piles_outside_the_uv_islands() -> None:
    pos = np.array([[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0]], np.float32)
    nrm = np.tile(np.array([0, 0, 1], np.float32), (3, 1))
    tris = np.array([[0, 1, 2]], np.int32)
    uvs = np.array([[[0, 0], [1, 0], [1, 1]]], np.float32)
    r = knitwear.plush(knitwear.MeshSurface(pos, nrm, tris, uvs), courses=10, wales=10)
    s = r.stats
    assert s["piles"] + s["piles_skipped"] == 100 and 30 < s["piles"] < 70
    assert len(r.horizontal) == s["piles"]
    assert (r.field.root_uvs[:, 0] >= r.field.root_uvs[:, 1]).all()
