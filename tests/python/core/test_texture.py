"""The knitwear texture from Python without Blender: shape and dtype, the yarn colour where
the yarn is, the same perturbation as the 3D knit, determinism, errors as KnitError."""

from __future__ import annotations

import knitwear
import numpy as np
import pytest


def plane_grid(w: float = 0.1, h: float = 0.1) -> knitwear.GridSurface:
    u, v = np.meshgrid(np.linspace(0, 1, 16), np.linspace(0, 1, 16))
    pos = np.stack([u * w, v * h, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return knitwear.GridSurface(pos, nrm)


def plane_mesh(uv_lo: float, uv_hi: float) -> knitwear.MeshSurface:
    pos = np.array([[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0, 0.1, 0]], np.float32)
    nrm = np.tile(np.array([0, 0, 1], np.float32), (4, 1))
    tris = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    corner = np.array([[uv_lo, uv_lo], [uv_hi, uv_lo], [uv_hi, uv_hi], [uv_lo, uv_hi]], np.float32)
    return knitwear.MeshSurface(pos, nrm, tris, np.ascontiguousarray(corner[tris]))


STOCKINETTE = knitwear.Pattern.preset("stockinette")
SETTINGS = {"courses": 12, "wales": 12, "color_variation": 0.0}


def test_texture_is_an_rgba_float_image_of_the_yarn_colour() -> None:
    colors = knitwear.ColorPattern.stripes([(0.2, 0.5, 0.1)], 1)
    img = knitwear.knit_texture(
        plane_grid(), STOCKINETTE, width=128, height=96, colors=colors, **SETTINGS
    )
    assert img.shape == (96, 128, 4) and img.dtype == np.float32
    assert img.flags["C_CONTIGUOUS"]
    yarn = img[img[..., 3] > 0]
    assert 0.3 < len(yarn) / (96 * 128) < 0.98
    # Shaded, but every covered pixel is a shade of the yarn colour.
    shade = yarn[:, 1] / 0.5
    np.testing.assert_allclose(yarn[:, :3], shade[:, None] * [0.2, 0.5, 0.1], atol=1e-5)
    assert shade.max() > 0.97
    assert np.all(img[img[..., 3] == 0] == 0)


def test_texture_follows_the_knit_settings() -> None:
    base = knitwear.knit_texture(plane_grid(), STOCKINETTE, width=96, height=96, **SETTINGS)
    again = knitwear.knit_texture(
        plane_grid(), STOCKINETTE, width=96, height=96, threads=1, **SETTINGS
    )
    np.testing.assert_array_equal(base, again)
    perturbed = knitwear.knit_texture(
        plane_grid(), STOCKINETTE, width=96, height=96, kappa=0.02, seed=4, **SETTINGS
    )
    assert np.mean(base != perturbed) > 0.05
    # Purl bumps in front instead of knit Vs: the other side of the same fabric.
    purl = knitwear.knit_texture(
        plane_grid(),
        knitwear.Pattern.preset("reverse_stockinette"),
        width=96,
        height=96,
        **SETTINGS,
    )
    assert np.mean(base != purl) > 0.05


def test_mesh_texture_covers_the_uv_domain() -> None:
    mesh = plane_mesh(0.25, 0.75)
    assert mesh.domain == ((0.25, 0.25), (0.75, 0.75))
    small = knitwear.knit_texture(mesh, STOCKINETTE, width=64, height=64, **SETTINGS)
    full = knitwear.knit_texture(plane_mesh(0.0, 1.0), STOCKINETTE, width=64, height=64, **SETTINGS)
    # The image spans the domain, wherever the UV island lies in [0, 1].
    np.testing.assert_allclose(small, full, atol=1e-4)


@pytest.mark.parametrize(
    ("kwargs", "error"),
    [
        ({"width": 0}, knitwear.ParameterError),
        ({"height": 16385}, knitwear.ParameterError),
        ({"width": 4096, "height": 4096, "budget_bytes": 1 << 20}, knitwear.BudgetError),
        ({"fluffiness": -1.0}, knitwear.ParameterError),
    ],
)
def test_texture_errors_are_knit_errors(kwargs: dict, error: type) -> None:
    with pytest.raises(error):
        knitwear.knit_texture(plane_grid(), STOCKINETTE, **{**SETTINGS, **kwargs})
    with pytest.raises(knitwear.KnitError):
        knitwear.knit_texture(plane_grid(), STOCKINETTE, **{**SETTINGS, **kwargs})


def test_texture_refuses_what_is_not_a_surface() -> None:
    with pytest.raises(knitwear.SurfaceError):
        knitwear.knit_texture(np.zeros((4, 4, 3), np.float32), STOCKINETTE)  # type: ignore[arg-type]
