"""`knitwear.Knit`: a knit bound once to its surface, following it in new poses."""

from __future__ import annotations

import knitwear
import numpy as np
import pytest


def bent_sheet(bend: float = 0.0, shift: float = 0.0) -> knitwear.GridSurface:
    u, v = np.meshgrid(np.linspace(0, 1, 33), np.linspace(0, 1, 25))
    if bend == 0.0:
        pos = np.stack([0.1 * u, 0.08 * v, np.zeros_like(u)], axis=-1)
        nrm = np.broadcast_to(np.array([0.0, 0.0, 1.0]), pos.shape)
    else:
        r, a = 0.1 / bend, (u - 0.5) * bend
        pos = np.stack([r * np.sin(a), 0.08 * v, r * np.cos(a) - r], axis=-1)
        nrm = np.stack([np.sin(a), np.zeros_like(a), np.cos(a)], axis=-1)
    pos = pos + np.array([shift, 0.0, 0.0])
    return knitwear.GridSurface(
        np.ascontiguousarray(pos, dtype=np.float32), np.ascontiguousarray(nrm, dtype=np.float32)
    )


SETTINGS = {"courses": 8, "wales": 10, "ring_segments": 4, "samples_per_loop": 8, "seed": 5}


def test_build_at_rest_is_knit() -> None:
    pattern = knitwear.Pattern.preset("seed")
    bound = knitwear.Knit(bent_sheet(), pattern, **SETTINGS)
    once = knitwear.knit(bent_sheet(), pattern, **SETTINGS)
    built = bound.build(bent_sheet())
    for name in ("vertices", "triangles", "edges", "corner_edges", "colors"):
        np.testing.assert_array_equal(getattr(built, name), getattr(once, name))
    assert bound.vertex_count == len(once.vertices)
    assert bound.triangle_count == len(once.triangles) > 0
    assert bound.counts == (8, 10)
    assert bound.topology_key == once.stats["topology_key"]
    assert bound.yarn_radius == pytest.approx(once.yarn_radius)


def test_positions_follow_a_new_pose_bit_for_bit() -> None:
    bound = knitwear.Knit(bent_sheet(), knitwear.Pattern.preset("stockinette"), **SETTINGS)
    pose = bent_sheet(bend=1.3, shift=0.5)
    full = bound.build(pose)
    fresh = bound.positions(pose)
    assert fresh.dtype == np.float32 and fresh.shape == (bound.vertex_count, 3)
    np.testing.assert_array_equal(fresh, full.vertices)

    out = np.empty((bound.vertex_count, 3), np.float32)
    assert bound.positions(pose, out=out) is out
    np.testing.assert_array_equal(out, full.vertices)
    np.testing.assert_array_equal(full.triangles, bound.build(bent_sheet()).triangles)


def test_pinned_stitch_size_reproduces_the_bound_knit_from_any_pose() -> None:
    pattern = knitwear.Pattern.preset("rib_1x1")
    bound = knitwear.Knit(bent_sheet(), pattern, **SETTINGS)
    pose = bent_sheet(bend=2.0)
    alone = knitwear.Knit(
        pose, pattern, **SETTINGS, yarn_radius=bound.yarn_radius, stitch_size=bound.stitch_size
    )
    np.testing.assert_array_equal(alone.positions(pose), bound.positions(pose))


@pytest.mark.parametrize(
    "out",
    [
        np.empty((3, 3), np.float32),
        "not an array",
        np.empty((1, 3), np.float64),
    ],
)
def test_bad_out_buffers_are_refused(out: object) -> None:
    bound = knitwear.Knit(bent_sheet(), knitwear.Pattern.preset("stockinette"), **SETTINGS)
    with pytest.raises(knitwear.ParameterError):
        bound.positions(bent_sheet(), out=out)


def test_read_only_and_fortran_out_buffers_are_refused() -> None:
    bound = knitwear.Knit(bent_sheet(), knitwear.Pattern.preset("stockinette"), **SETTINGS)
    frozen = np.empty((bound.vertex_count, 3), np.float32)
    frozen.flags.writeable = False
    with pytest.raises(knitwear.ParameterError):
        bound.positions(bent_sheet(), out=frozen)
    fortran = np.asfortranarray(np.empty((bound.vertex_count, 3), np.float32))
    with pytest.raises(knitwear.ParameterError):
        bound.positions(bent_sheet(), out=fortran)


def test_a_surface_with_another_layout_is_a_surface_error() -> None:
    bound = knitwear.Knit(bent_sheet(), knitwear.Pattern.preset("stockinette"), **SETTINGS)
    pos = np.zeros((3, 3), np.float32)
    pos[1, 0] = pos[2, 1] = 1.0
    nrm = np.tile(np.array([0, 0, 1], np.float32), (3, 1))
    uvs = np.array([[[0, 0], [0.5, 0], [0, 0.5]]], np.float32)
    mesh = knitwear.MeshSurface(pos, nrm, np.array([[0, 1, 2]], np.int32), uvs)
    with pytest.raises(knitwear.SurfaceError):
        bound.build(mesh)
    with pytest.raises(knitwear.SurfaceError):
        bound.positions(mesh)


def sphere(radius: float = 0.1, n: int = 48) -> knitwear.GridSurface:
    """A UV sphere as a NURBS sphere samples: u round the equator (cyclic), v pole to pole."""
    u = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    v = np.linspace(0.0, np.pi, n)
    uu, vv = np.meshgrid(u, v)
    nrm = np.stack(
        [np.sin(vv) * np.cos(uu), np.sin(vv) * np.sin(uu), -np.cos(vv)], axis=-1
    ).astype(np.float32)
    return knitwear.GridSurface((radius * nrm).astype(np.float32), nrm, cyclic_u=True)


def test_a_sphere_rebuilt_with_its_pinned_sizes_is_not_refused() -> None:
    """Issue 18: a knitted NURBS sphere stopped following on the next frame ("the yarn is
    thicker than a stitch"): the rebuild checked the yarn against its pinned stitch size, the
    tightest stitches' (at the poles), where the first knit checked it against the mean."""
    s = sphere()
    first = knitwear.Knit(s, knitwear.Pattern.preset("stockinette"), gauge=(22.0, 30.0))
    # The poles' stitches are a fraction of a yarn wide: the loops are tuned for the
    # narrowest stitch a loop clears, 2.5 yarn diameters, not for them.
    diameter = 2 * first.yarn_radius
    assert first.stitch_size[0] == pytest.approx(2.5 * diameter, rel=1e-5)
    courses, wales = first.counts
    again = knitwear.Knit(
        s,
        knitwear.Pattern.preset("stockinette"),
        courses=courses,
        wales=wales,
        yarn_radius=first.yarn_radius,
        stitch_size=first.stitch_size,
    )
    assert np.array_equal(again.build(s).vertices, first.build(s).vertices)
    # A pinned size narrower than the yarn (an older knit's, tuned for the poles) is checked
    # against the mean stitch too, as its first knit was.
    narrow = (0.5 * diameter, first.stitch_size[1])
    knitwear.Knit(
        s,
        knitwear.Pattern.preset("stockinette"),
        courses=courses,
        wales=wales,
        yarn_radius=first.yarn_radius,
        stitch_size=narrow,
    )


def squashed_sheet(height: float) -> knitwear.GridSurface:
    """`bent_sheet()` with its rows squashed (or stretched) to ``height`` of theirs."""
    u, v = np.meshgrid(np.linspace(0, 1, 33), np.linspace(0, 1, 25))
    pos = np.stack([0.1 * u, 0.08 * height * v, np.zeros_like(u)], axis=-1)
    nrm = np.broadcast_to(np.array([0.0, 0.0, 1.0]), pos.shape)
    return knitwear.GridSurface(
        np.ascontiguousarray(pos, dtype=np.float32), np.ascontiguousarray(nrm, dtype=np.float32)
    )


def test_clearance_in_a_new_pose_is_the_builds_and_drops_as_the_rows_squash() -> None:
    """Issue 23: `Knit.clearance` measures the yarn in any pose without building the mesh,
    as `measure_clearance` measures the build there; rows squashed to 40% of their height
    push yarn through yarn (at the default gauge)."""
    bound = knitwear.Knit(bent_sheet(), knitwear.Pattern.preset("stockinette"), seed=5)
    figures = []
    for height in (1.0, 0.7, 0.4):
        surface = squashed_sheet(height)
        figure = bound.clearance(surface)
        assert figure == knitwear.measure_clearance(bound.build(surface))
        figures.append(figure)
    assert figures[0][0] > 0.9, figures
    assert figures[0][0] > figures[1][0] > figures[2][0], figures
    assert figures[2][0] < 0.5, figures
    pos = np.zeros((3, 3), np.float32)
    pos[1, 0] = pos[2, 1] = 1.0
    nrm = np.tile(np.array([0, 0, 1], np.float32), (3, 1))
    uvs = np.array([[[0, 0], [0.5, 0], [0, 0.5]]], np.float32)
    mesh = knitwear.MeshSurface(pos, nrm, np.array([[0, 1, 2]], np.int32), uvs)
    with pytest.raises(knitwear.SurfaceError, match="layout"):
        bound.clearance(mesh)
