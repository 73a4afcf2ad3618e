"""Camera-driven detail through the Python API: `knitwear.Camera`, the detail keywords of
`Knit`, the per-level stats and pinned levels."""

import math
from typing import Any

import knitwear
import numpy as np
import pytest

RES = (1920, 1080)


def strip() -> knitwear.GridSurface:
    """A flat 10 x 60 cm strip in z = 0."""
    u, v = np.meshgrid(np.linspace(0, 1, 8), np.linspace(0, 1, 32))
    pos = np.stack([0.1 * u, 0.6 * v, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return knitwear.GridSurface(pos, nrm)


def perspective(fov_y: float, aspect: float, near: float, far: float) -> np.ndarray:
    f = 1.0 / math.tan(fov_y / 2)
    return np.array(
        [
            [f / aspect, 0, 0, 0],
            [0, f, 0, 0],
            [0, 0, (far + near) / (near - far), 2 * far * near / (near - far)],
            [0, 0, -1, 0],
        ]
    )


def look_at(eye: np.ndarray, target: np.ndarray, up: np.ndarray) -> np.ndarray:
    f = (target - eye) / np.linalg.norm(target - eye)
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    m = np.eye(4)
    m[0, :3], m[1, :3], m[2, :3] = s, u, -f
    m[:3, 3] = -m[:3, :3] @ eye
    return m


def receding_camera() -> knitwear.Camera:
    eye = np.array([0.05, -0.08, 0.06])
    m = perspective(math.radians(50), RES[0] / RES[1], 0.01, 100) @ look_at(
        eye, np.array([0.05, 0.25, 0.0]), np.array([0.0, 0.0, 1.0])
    )
    return knitwear.Camera(m, [*eye, 1.0], RES)


def test_without_a_camera_the_knit_is_unchanged_and_all_full() -> None:
    a = knitwear.knit(strip(), knitwear.Pattern.preset("seed"), seed=2)
    b = knitwear.Knit(strip(), knitwear.Pattern.preset("seed"), seed=2)
    assert b.stitch_levels is None
    s = a.stats
    assert s["levels"] == {"full": s["stitches"], "mid": 0, "far": 0, "texture": 0, "culled": 0}
    assert s["triangles_full_detail"] == s["triangles"]
    np.testing.assert_array_equal(a.vertices, b.build(strip()).vertices)


def test_a_camera_sets_levels_and_saves_triangles() -> None:
    cam = receding_camera()
    assert cam.views == 1 and cam.resolution == RES
    # Thresholds twice the defaults, so this strip at 1080p gets every built level.
    knit = knitwear.Knit(
        strip(), knitwear.Pattern.preset("stockinette"), camera=cam, detail_px=(24, 10, 2)
    )
    result = knit.build(strip())
    s = result.stats
    assert sum(s["levels"].values()) == s["stitches"]
    assert s["levels"]["full"] > 0 and s["levels"]["mid"] > 0 and s["levels"]["far"] > 0
    assert s["triangles"] < s["triangles_full_detail"]
    levels = knit.stitch_levels
    assert levels.shape == knit.counts and levels.dtype == np.uint8
    assert (levels == 0).sum() == s["levels"]["full"]
    # Coarser thresholds push stitches to the texture.
    coarse = knitwear.knit(
        strip(), knitwear.Pattern.preset("stockinette"), camera=cam, detail_px=(60, 30, 12)
    )
    assert coarse.stats["levels"]["texture"] > 0
    # Several views: the frames of an animated camera, as a stack.
    two = knitwear.Camera(np.stack([np.eye(4)] * 2), np.array([[0, 0, 1, 0]] * 2), (64, 64))
    assert two.views == 2


def test_pinned_levels_rebuild_the_same_mesh() -> None:
    pattern = knitwear.Pattern.preset("rib_2x2")
    first = knitwear.Knit(strip(), pattern, camera=receding_camera(), seed=4)
    again = knitwear.Knit(strip(), pattern, stitch_levels=first.stitch_levels, seed=4)
    assert again.topology_key == first.topology_key
    a, b = first.build(strip()), again.build(strip())
    np.testing.assert_array_equal(a.vertices, b.vertices)
    np.testing.assert_array_equal(a.triangles, b.triangles)
    np.testing.assert_array_equal(again.positions(strip()), a.vertices)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"detail_px": (4, 8, 2)}, "full >= mid >= texture"),
        ({"mid_quality": (3, 6, True)}, "6..=256 samples"),
        ({"frustum_margin": float("nan")}, "frustum_margin"),
        ({"stitch_levels": np.zeros((2, 2), np.uint8)}, "not both"),
    ],
)
def test_bad_detail_settings_raise_parameter_errors(kwargs: dict, match: str) -> None:
    with pytest.raises(knitwear.ParameterError, match=match):
        knitwear.Knit(strip(), knitwear.Pattern.preset("garter"), camera=receding_camera(),
                      **kwargs)


def test_bad_cameras_and_pinned_levels_raise() -> None:
    with pytest.raises(knitwear.ParameterError, match="matrices"):
        knitwear.Camera(np.eye(3), [0, 0, 0, 1], RES)
    with pytest.raises(knitwear.ParameterError, match="NaN"):
        knitwear.Knit(
            strip(),
            knitwear.Pattern.preset("garter"),
            camera=knitwear.Camera(np.full((4, 4), np.nan), [0, 0, 0, 1], RES),
        )
    with pytest.raises(knitwear.ParameterError, match="pinned stitch levels"):
        knitwear.Knit(strip(), knitwear.Pattern.preset("garter"), stitch_levels=[0, 1, 2])
    with pytest.raises(knitwear.ParameterError, match="0 \\(full\\) to 4"):
        knitwear.Knit(strip(), knitwear.Pattern.preset("garter"), stitch_levels=[7])


def slid_strip(dy: float) -> knitwear.GridSurface:
    """`strip` moved ``dy`` along y: the same (u,v) layout in another pose."""
    u, v = np.meshgrid(np.linspace(0, 1, 8), np.linspace(0, 1, 32))
    pos = np.stack([0.1 * u, 0.6 * v + dy, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return knitwear.GridSurface(pos, nrm)


def overhead_camera(frames: int, poses: list | None = None) -> knitwear.Camera:
    """Still, 12 cm over the strip's near end (y = 5 cm), ``frames`` times over."""
    eye = np.array([0.05, 0.05, 0.12])
    m = perspective(math.radians(40), RES[0] / RES[1], 0.01, 100) @ look_at(
        eye, np.array([0.05, 0.05, 0.0]), np.array([0.0, 1.0, 0.0])
    )
    return knitwear.Camera([m] * frames, [[*eye, 1.0]] * frames, RES, poses=poses)


def test_a_posed_camera_builds_each_part_for_the_frame_that_sees_it() -> None:
    """A source that slides (or deforms) under a still camera: each view sees the surface in
    its frame's pose, so the far end, which only the last frame brings under the camera, is
    built; without the poses it was culled as the first frame's pose left it, and the
    knit, following its source, showed nothing there."""
    pattern = knitwear.Pattern.preset("stockinette")
    still = knitwear.Knit(strip(), pattern, camera=overhead_camera(3))
    lv_still = still.stitch_levels
    courses = lv_still.shape[0]
    # The still knit culls its far end: out of the frame.
    assert (lv_still[-courses // 4 :] == 4).all()
    assert (lv_still[: courses // 10] != 4).all()
    # The strip slides 50 cm towards -y over three frames: its far end passes under the camera.
    poses = [slid_strip(0.0), slid_strip(-0.25), slid_strip(-0.5)]
    cam = overhead_camera(3, poses)
    assert cam.posed and "with poses" in repr(cam)
    moving = knitwear.Knit(strip(), pattern, camera=cam)
    lv = moving.stitch_levels
    assert (lv[-courses // 10 :] != 4).all(), "the far end, seen at the last frame, is built"
    assert (lv[: courses // 10] != 4).all()
    assert (lv == 4).sum() < (lv_still == 4).sum()
    # A stitch between the frames' footprints is culled still: no view sees it.
    assert (lv == 4).any()
    # Poses that do not move give the unposed camera's levels, bit for bit.
    same = knitwear.Knit(strip(), pattern, camera=overhead_camera(3, [strip()] * 3))
    np.testing.assert_array_equal(same.stitch_levels, lv_still)


def test_a_posed_camera_culls_the_yarn_each_frame_hides_in_its_own_pose() -> None:
    """Hidden yarn is culled for a source that slides under the camera too (it was refused):
    each view finds what it sees on the strip in its own pose, so under the camera in the
    last frame, where the far end has come, most of the yarn is kept, but not the yarn that
    yarn hides there."""
    pattern = knitwear.Pattern.preset("stockinette")
    poses = [slid_strip(0.0), slid_strip(-0.25), slid_strip(-0.5)]
    culled = knitwear.Knit(strip(), pattern, camera=overhead_camera(3, poses), cull_hidden=True)
    whole = knitwear.Knit(strip(), pattern, camera=overhead_camera(3, poses))
    np.testing.assert_array_equal(culled.stitch_levels, whole.stitch_levels)

    def under_the_camera(knit: knitwear.Knit) -> int:
        """Triangles within 5 cm of the camera's foot, in the last frame's pose."""
        built = knit.build(poses[-1])
        y = built.vertices[built.triangles].mean(axis=1)[:, 1]
        return int(((y > 0.0) & (y < 0.1)).sum())

    kept, all_there = under_the_camera(culled), under_the_camera(whole)
    assert 0.5 * all_there < kept < 0.95 * all_there, (kept, all_there)


def test_bad_poses_raise() -> None:
    pattern = knitwear.Pattern.preset("garter")
    with pytest.raises(knitwear.ParameterError, match="one pose per view"):
        overhead_camera(2, [strip()])
    with pytest.raises(knitwear.ParameterError, match="sequence of surfaces"):
        overhead_camera(1, 3)  # type: ignore[arg-type]
    with pytest.raises(knitwear.SurfaceError, match="GridSurface or knitwear.MeshSurface"):
        overhead_camera(1, ["a surface"])  # type: ignore[list-item]
    ring = np.stack(
        np.meshgrid(np.linspace(0, 1, 8), np.linspace(0, 1, 32)) + [np.zeros((32, 8))], axis=-1
    ).astype(np.float32)
    up = np.zeros_like(ring)
    up[..., 2] = 1.0
    cyclic = knitwear.GridSurface(ring, up, cyclic_u=True)
    with pytest.raises(knitwear.ParameterError, match="another \\(u,v\\) layout"):
        knitwear.Knit(strip(), pattern, camera=overhead_camera(1, [cyclic]))


def test_hidden_yarn_is_culled_with_the_whole_knits_normals_and_can_be_pinned() -> None:
    pattern = knitwear.Pattern.preset("stockinette")
    cam = receding_camera()
    whole = knitwear.knit(strip(), pattern, camera=cam, seed=3)
    assert whole.stats["triangles_hidden"] == 0
    knit = knitwear.Knit(strip(), pattern, camera=cam, seed=3, cull_hidden=True)
    result = knit.build(strip())
    s = result.stats
    assert s["triangles"] + s["triangles_hidden"] == whole.stats["triangles"]
    # At 16 samples a pixel of a 1080p frame much of the yarn shows; the loops behind the
    # fabric and the backs of the strands do not.
    assert s["triangles_hidden"] > 0.3 * whole.stats["triangles"]
    assert len(result.triangles) == s["triangles"] and len(result.vertices) == knit.vertex_count
    assert result.normals.shape == result.vertices.shape
    np.testing.assert_allclose(np.linalg.norm(result.normals, axis=1), 1.0, atol=1e-5)
    seen = knit.seen_triangles
    assert isinstance(seen, bytes) and len(seen) == -(-whole.stats["triangles"] // 8)
    bits = np.unpackbits(np.frombuffer(seen, np.uint8), bitorder="little")
    assert bits.sum() == s["triangles"]
    # The culled triangles are the whole knit's seen ones, corner for corner.
    kept = np.flatnonzero(bits[: whole.stats["triangles"]])
    np.testing.assert_array_equal(
        result.vertices[result.triangles], whole.vertices[whole.triangles[kept]]
    )
    # Pinned, without the camera: the same mesh, in another pose too.
    again = knitwear.Knit(
        strip(), pattern, seed=3, stitch_levels=knit.stitch_levels, seen_triangles=seen
    )
    assert again.topology_key == knit.topology_key
    np.testing.assert_array_equal(again.build(strip()).vertices, result.vertices)
    np.testing.assert_array_equal(again.normals(strip()), result.normals)
    out = np.empty_like(result.normals)
    assert again.normals(strip(), out=out) is out
    np.testing.assert_array_equal(out, result.normals)
    with pytest.raises(knitwear.ParameterError, match="needs a camera"):
        knitwear.Knit(strip(), pattern, cull_hidden=True)
    with pytest.raises(knitwear.ParameterError, match="another knit"):
        knitwear.Knit(strip(), pattern, camera=cam, seen_triangles=seen[:-1])
    # One pass gives both, into the caller's buffers.
    pos, nrm = np.empty_like(result.vertices), np.empty_like(result.normals)
    tan = np.empty_like(result.tangents)
    assert again.positions(strip(), out=pos, normals_out=nrm, tangents_out=tan) is pos
    np.testing.assert_array_equal(pos, result.vertices)
    np.testing.assert_array_equal(nrm, result.normals)
    # The kept vertices' fibre directions are the whole knit's too.
    np.testing.assert_array_equal(tan, result.tangents)
    np.testing.assert_array_equal(
        result.tangents[result.triangles], whole.tangents[whole.triangles[kept]]
    )
    with pytest.raises(knitwear.ParameterError, match="normals_out must have shape"):
        again.positions(strip(), normals_out=np.empty((3, 3), np.float32))
    with pytest.raises(knitwear.ParameterError, match="not borrowed elsewhere"):
        again.positions(strip(), out=pos, normals_out=pos)


def miss_of_the_centreline(
    result: knitwear.KnitResult, normals: np.ndarray, nearest: bool = False
) -> Any:
    """Per vertex ``p`` with normal ``n``: how far the centreline passes from the segment
    from ``p - 0.3 r n`` to ``p - 2 r n`` (``r`` the yarn radius), the nearest sample's
    distance (with ``nearest``, and that sample's index). The tube's normal points straight
    out from the vertex's own ring centre, a centreline sample between 0.5 and
    1 + fluffiness radii back along it: 0 to rounding."""
    points = result.centerline_points.astype(np.float64)
    r = result.yarn_radius
    out = np.empty(len(normals))
    which = np.empty(len(normals), np.int64)
    for start in range(0, len(out), 512):
        p = result.vertices[start : start + 512].astype(np.float64)
        n = normals[start : start + 512].astype(np.float64)
        a, b = p - 0.3 * r * n, p - 2.0 * r * n
        ab = b - a  # (k, 3)
        ac = points[None, :, :] - a[:, None, :]  # (k, S, 3)
        t = np.clip(np.einsum("kj,ksj->ks", ab, ac) / np.einsum("kj,kj->k", ab, ab)[:, None], 0, 1)
        d = np.linalg.norm(ac - t[..., None] * ab[:, None, :], axis=2)
        out[start : start + 512] = d.min(axis=1)
        which[start : start + 512] = d.argmin(axis=1)
    return (out, which) if nearest else out


def test_any_knit_gives_the_swept_tubes_normals() -> None:
    """Every knit gives its shading normals (what the add-on writes as custom normals, and
    an animated knit each frame): the swept tube's, out from the yarn's centreline through
    each vertex, in any pose, with its positions in one pass."""
    def sheet(bend: float) -> knitwear.GridSurface:
        """A 3 x 3 cm sheet, arched by ``bend`` metres."""
        u, v = np.meshgrid(np.linspace(0, 1, 9), np.linspace(0, 1, 9))
        z = bend * np.sin(np.pi * u)
        pos = np.stack([0.03 * u, 0.03 * v, z], axis=-1).astype(np.float32)
        nrm = np.zeros_like(pos)
        nrm[..., 2] = 1.0
        return knitwear.GridSurface(pos, nrm)

    pattern = knitwear.Pattern.preset("seed")
    knit = knitwear.Knit(sheet(0.0), pattern, seed=2, plies=2)
    for surface in (sheet(0.0), sheet(0.01)):
        result = knit.build(surface)
        normals = knit.normals(surface)
        np.testing.assert_array_equal(normals, result.normals)
        np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-5)
        # Straight out from the yarn: back along each normal lies a centreline sample.
        miss = miss_of_the_centreline(result, normals)
        assert miss.max() < 1e-3 * result.yarn_radius, miss.max() / result.yarn_radius
        # (Any other direction misses: turned by a tenth of a radian, the segment passes
        # the sample a tenth of a radius or more away.)
        turned = np.roll(normals, 1, axis=1) * 0.1 + normals
        turned /= np.linalg.norm(turned, axis=1, keepdims=True)
        assert np.median(miss_of_the_centreline(result, turned)) > 0.02 * result.yarn_radius
        pos, nrm = np.empty_like(result.vertices), np.empty_like(normals)
        knit.positions(surface, out=pos, normals_out=nrm)
        np.testing.assert_array_equal(pos, result.vertices)
        np.testing.assert_array_equal(nrm, normals)


def centreline_directions(result: knitwear.KnitResult) -> np.ndarray:
    """Per centreline sample, the unit direction the yarn runs there (central differences
    within its piece, one-sided at an open piece's ends, wrapping round a closed one)."""
    points = result.centerline_points.astype(np.float64)
    out = np.empty_like(points)
    offsets = result.course_offsets
    for k, closed in enumerate(result.yarn_closed):
        piece = points[offsets[k] : offsets[k + 1]]
        if closed:
            d = np.roll(piece, -1, axis=0) - np.roll(piece, 1, axis=0)
        else:
            d = np.gradient(piece, axis=0)
        out[offsets[k] : offsets[k + 1]] = d
    return out / np.linalg.norm(out, axis=1, keepdims=True)


def test_any_knit_gives_its_fibres_directions_along_the_yarn() -> None:
    """Every knit gives its fibres' directions (the yarn material's anisotropic tangent):
    unit, across the shading normal, forward along the yarn at the nearest centreline
    sample and slanted round it with the twist; in any pose, in the same pass as its
    positions, and the same in a knit that culls its hidden yarn."""

    def sheet(bend: float) -> knitwear.GridSurface:
        u, v = np.meshgrid(np.linspace(0, 1, 9), np.linspace(0, 1, 9))
        pos = np.stack([0.03 * u, 0.03 * v, bend * np.sin(np.pi * u)], axis=-1)
        nrm = np.zeros_like(pos)
        nrm[..., 2] = 1.0
        return knitwear.GridSurface(pos.astype(np.float32), nrm.astype(np.float32))

    knit = knitwear.Knit(sheet(0.0), knitwear.Pattern.preset("stockinette"), seed=2, plies=2)
    for surface in (sheet(0.0), sheet(0.01)):
        result = knit.build(surface)
        t, n = result.tangents.astype(np.float64), result.normals.astype(np.float64)
        assert t.shape == result.vertices.shape
        np.testing.assert_allclose(np.linalg.norm(t, axis=1), 1.0, atol=1e-5)
        assert np.abs(np.einsum("ij,ij->i", t, n)).max() < 1e-5
        # The vertex's own ring centre: the centreline sample back along its normal.
        _, centre = miss_of_the_centreline(result, result.normals, nearest=True)
        along = np.einsum("ij,ij->i", t, centreline_directions(result)[centre])
        slant = np.degrees(np.arccos(np.clip(along, -1, 1)))
        # Forward along the yarn, slanted as the plies' helix at the vertex's distance from
        # the centreline: 4 turns a loop, about 38 degrees at the surface.
        # (Measured: 1st, 50th, 99th percentiles 18, 33, 62 degrees; the widest are where
        # the yarn curves fast and the nearest sample's direction is not the ring's.)
        assert 25 < np.median(slant) < 45, np.percentile(slant, [1, 50, 99])
        assert np.percentile(slant, 99) < 70, np.percentile(slant, [1, 50, 99])
        pos, nrm, tan = (np.empty_like(result.vertices) for _ in range(3))
        knit.positions(surface, out=pos, normals_out=nrm, tangents_out=tan)
        np.testing.assert_array_equal(pos, result.vertices)
        np.testing.assert_array_equal(nrm, result.normals)
        np.testing.assert_array_equal(tan, result.tangents)
    with pytest.raises(knitwear.ParameterError, match="tangents_out must have shape"):
        knit.positions(sheet(0.0), tangents_out=np.empty((3, 3), np.float32))
    with pytest.raises(knitwear.ParameterError, match="not borrowed elsewhere"):
        knit.positions(sheet(0.0), normals_out=nrm, tangents_out=nrm)


def test_the_hidden_yarn_pass_is_skipped_under_cull_hidden_min_triangles() -> None:
    """Under `cull_hidden_min_triangles` full-quality triangles the pass does not run (it
    would cost more than building what it hides) and the knit is the whole one; pinned seen
    triangles still apply, whatever the count."""
    pattern = knitwear.Pattern.preset("stockinette")
    cam = receding_camera()
    whole = knitwear.knit(strip(), pattern, camera=cam, seed=3)
    assert whole.stats["hidden_pass"] is None
    culled = knitwear.Knit(strip(), pattern, camera=cam, seed=3, cull_hidden=True)
    assert culled.build(strip()).stats["hidden_pass"] is True
    full = whole.stats["triangles"]  # at most this many are at full quality
    skipped = knitwear.Knit(
        strip(), pattern, camera=cam, seed=3, cull_hidden=True,
        cull_hidden_min_triangles=full + 1,
    )
    result = skipped.build(strip())
    assert result.stats["hidden_pass"] is False and result.stats["triangles_hidden"] == 0
    assert skipped.seen_triangles is None
    np.testing.assert_array_equal(result.normals, whole.normals)
    np.testing.assert_array_equal(result.vertices, whole.vertices)
    np.testing.assert_array_equal(result.triangles, whole.triangles)
    pinned = knitwear.Knit(
        strip(), pattern, seed=3, stitch_levels=culled.stitch_levels,
        seen_triangles=culled.seen_triangles, cull_hidden_min_triangles=full + 1,
    )
    again = pinned.build(strip())
    assert again.stats["hidden_pass"] is True
    np.testing.assert_array_equal(again.vertices, culled.build(strip()).vertices)
    with pytest.raises(knitwear.ParameterError, match="cull_hidden_min_triangles"):
        knitwear.Knit(strip(), pattern, camera=cam, cull_hidden=True,
                      cull_hidden_min_triangles=-1)
