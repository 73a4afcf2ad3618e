"""Issue 4's fixture suite at the Python API: every bad buffer a caller can pass (wrong dtype,
non-contiguous, read-only, empty, NaN or infinite) raises a `knitwear.KnitError` subclass
whose message names the argument and the problem, and the degradations of the core (stitches
skipped, offsets clamped) are counted in `stats`. Never a panic, a NaN or a crash.
"""

from __future__ import annotations

from collections.abc import Callable

import knitwear
import numpy as np
import pytest


def grid(rows: int = 12, cols: int = 12) -> tuple[np.ndarray, np.ndarray]:
    u, v = np.meshgrid(np.linspace(0, 1, cols), np.linspace(0, 1, rows))
    pos = np.stack([0.1 * u, 0.1 * v, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return pos, nrm


def mesh() -> dict[str, np.ndarray]:
    pos = np.array([[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0, 0.1, 0]], np.float32)
    return {
        "positions": pos,
        "normals": np.tile(np.array([0, 0, 1], np.float32), (4, 1)),
        "triangles": np.array([[0, 1, 2], [0, 2, 3]], np.int32),
        "uvs": np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], np.float32),
    }


def make_mesh(**parts: np.ndarray) -> knitwear.MeshSurface:
    m = mesh() | parts
    return knitwear.MeshSurface(m["positions"], m["normals"], m["triangles"], m["uvs"])


def read_only(a: np.ndarray) -> np.ndarray:
    a = a.copy()
    a.setflags(write=False)
    return a


def poked(a: np.ndarray, index: int, value: float) -> np.ndarray:
    out = a.copy()
    out.flat[index] = value
    return out


Mutation = Callable[[np.ndarray], object]

#: (name, mutation of a good float32 buffer, SurfaceError message pattern)
BAD_FLOATS: list[tuple[str, Mutation, str]] = [
    ("float64", lambda a: a.astype(np.float64), "float32"),
    ("float16", lambda a: a.astype(np.float16), "float32"),
    ("int32", lambda a: a.astype(np.int32), "float32"),
    ("python list", lambda a: a.tolist(), "float32"),
    ("fortran order", np.asfortranarray, "C-contiguous"),
    ("strided view", lambda a: np.repeat(a, 2, axis=0)[::2], "C-contiguous"),
    ("empty", lambda a: a[:0], "at least|no triangles|shape|has 0"),
    ("NaN", lambda a: poked(a, 4, np.nan), "NaN"),
    ("+inf", lambda a: poked(a, 2, np.inf), "inf"),
    ("-inf", lambda a: poked(a, 0, -np.inf), "inf"),
]


@pytest.mark.parametrize("name, mutate, match", BAD_FLOATS, ids=[c[0] for c in BAD_FLOATS])
@pytest.mark.parametrize("which", ["positions", "normals"])
def test_bad_grid_buffers_name_the_problem(
    which: str, name: str, mutate: Mutation, match: str
) -> None:
    pos, nrm = grid()
    args = {"positions": pos, "normals": nrm}
    args[which] = mutate(args[which])
    if name == "empty":
        # Both empty, so the shapes agree and the size itself is what is refused.
        args = {k: v[:0] for k, v in args.items()}
    with pytest.raises(knitwear.SurfaceError, match=match) as err:
        knitwear.GridSurface(args["positions"], args["normals"])
    message = str(err.value)
    print(f"grid {which} {name}: {message}")
    if name in ("NaN", "+inf", "-inf"):
        assert "row" in message and "column" in message, message


@pytest.mark.parametrize("name, mutate, match", BAD_FLOATS, ids=[c[0] for c in BAD_FLOATS])
@pytest.mark.parametrize("which", ["positions", "normals", "uvs"])
def test_bad_mesh_buffers_name_the_problem(
    which: str, name: str, mutate: Mutation, match: str
) -> None:
    parts = {which: mutate(mesh()[which])}
    if name == "empty":
        parts = {"positions": mesh()["positions"][:0], "normals": mesh()["normals"][:0]}
        parts |= {"triangles": mesh()["triangles"][:0], "uvs": mesh()["uvs"][:0]}
    with pytest.raises(knitwear.SurfaceError, match=match) as err:
        make_mesh(**parts)
    print(f"mesh {which} {name}: {err.value}")
    if name == "NaN":
        assert ("vertex" in str(err.value)) or ("triangle" in str(err.value))


@pytest.mark.parametrize(
    "tris, match",
    [
        (np.array([[0, 1, 2], [0, 2, 3]], np.float32), "int32"),
        (np.array([[0, 1, 2], [0, 2, 3]], np.int16), "int32"),
        (np.asfortranarray(np.array([[0, 1, 2], [0, 2, 3]], np.int32)), "C-contiguous"),
        (np.array([[0, 1, 2], [0, 2, 7]], np.int32), "vertex 7"),
        (np.array([[0, 1, 2], [0, 2, -1]], np.int64), "negative|-1"),
    ],
)
def test_bad_triangles_name_the_problem(tris: np.ndarray, match: str) -> None:
    with pytest.raises(knitwear.SurfaceError, match=match) as err:
        make_mesh(triangles=tris)
    print(f"triangles: {err.value}")


def test_read_only_buffers_are_read() -> None:
    m = {k: read_only(v) for k, v in mesh().items()}
    surface = knitwear.MeshSurface(m["positions"], m["normals"], m["triangles"], m["uvs"])
    pos, nrm = grid()
    g = knitwear.GridSurface(read_only(pos), read_only(nrm))
    image = read_only(np.ones((4, 4, 3), np.float32))
    for s in (surface, g):
        r = knitwear.knit(s, knitwear.Pattern.preset("garter"), courses=4, wales=4,
                          color_image=image)
        assert np.isfinite(r.vertices).all()


def test_bad_colour_images_name_the_problem() -> None:
    surface = knitwear.GridSurface(*grid())
    pattern = knitwear.Pattern.preset("garter")
    good = np.ones((4, 4, 3), np.float32)
    for bad, match in [
        (good.astype(np.float64), "float32"),
        (good[:, ::2], "C-contiguous"),
        (good[:0], "at least 1"),
        (np.ones((4, 4, 2), np.float32), "3 or 4"),
        (poked(good, 5, np.nan), "NaN"),
    ]:
        with pytest.raises(knitwear.ParameterError, match=match):
            knitwear.knit(surface, pattern, courses=4, wales=4, color_image=bad)


def test_positions_out_buffer_must_be_writable_float32_of_the_right_size() -> None:
    surface = knitwear.GridSurface(*grid())
    k = knitwear.Knit(surface, knitwear.Pattern.preset("garter"), courses=4, wales=4)
    v = k.build(surface).vertices
    for bad in (
        np.zeros_like(v, dtype=np.float64),
        np.zeros((len(v) + 1, 3), np.float32),
        read_only(np.zeros_like(v)),
        np.zeros((len(v), 6), np.float32)[:, ::2],
    ):
        with pytest.raises(knitwear.KnitError):
            k.positions(surface, out=bad)
    out = np.zeros_like(v)
    k.positions(surface, out=out)
    assert np.array_equal(out, v)


def test_absurd_requests() -> None:
    surface = knitwear.GridSurface(*grid())
    pattern = knitwear.Pattern.preset("stockinette")
    with pytest.raises(knitwear.BudgetError, match="1000000000 stitches"):
        knitwear.knit(surface, pattern, courses=10**6, wales=1000)
    with pytest.raises(knitwear.BudgetError, match="coarser gauge"):
        knitwear.knit(surface, pattern, gauge=(1e8, 1e8))
    for gauge in [(0.0, 28.0), (20.0, -28.0), (float("inf"), 28.0)]:
        with pytest.raises(knitwear.ParameterError, match="gauge must be positive"):
            knitwear.knit(surface, pattern, gauge=gauge)
    with pytest.raises(knitwear.ParameterError, match="thicker than a stitch"):
        knitwear.knit(surface, pattern, yarn_radius=0.05)
    with pytest.raises(knitwear.ParameterError, match="kappa"):
        knitwear.knit(surface, pattern, kappa=float("nan"))


def test_forced_internal_error_is_our_class() -> None:
    with pytest.raises(knitwear.InternalError, match="please report") as err:
        knitwear._core._force_internal_error()
    # Caught by `except KnitError` and `except Exception`: never a BaseException only.
    assert isinstance(err.value, knitwear.KnitError)
    assert isinstance(err.value, Exception)
    # The module still works after it.
    r = knitwear.knit(knitwear.GridSurface(*grid()), knitwear.Pattern.preset("garter"),
                      courses=2, wales=2)
    assert r.stats["stitches"] == 4


def test_degradations_are_counted_in_stats() -> None:
    # Half the UV square covered: stitches outside it are skipped, and say so.
    m = mesh()
    half = knitwear.MeshSurface(m["positions"], m["normals"], m["triangles"][:1], m["uvs"][:1])
    r = knitwear.knit(half, knitwear.Pattern.preset("stockinette"), courses=12, wales=12)
    s = r.stats
    assert s["stitches"] + s["stitches_skipped"] == 144 and s["stitches_skipped"] > 50
    assert s["stitches_clamped"] == 0

    # A 1 mm tube, two stitches round it, a yarn 1.2 mm thick: every stitch's offsets are
    # clamped to the tube's curvature, and the yarn stays out of the tube's core.
    a = np.linspace(0, 2 * np.pi, 48, endpoint=False)
    z = np.linspace(0, 0.04, 40)
    aa, zz = np.meshgrid(a, z)
    nrm = np.stack([np.cos(aa), np.sin(aa), np.zeros_like(aa)], axis=-1).astype(np.float32)
    pos = (0.001 * nrm + np.stack([0 * aa, 0 * aa, zz], axis=-1)).astype(np.float32)
    tube = knitwear.GridSurface(pos, nrm, cyclic_u=True)
    r = knitwear.knit(tube, knitwear.Pattern.preset("stockinette"), courses=16, wales=2,
                      yarn_radius=0.0006, measure_clearance=True)
    # Every stitch: the fabric's 32 and the 2 + 2 of its cast-on and bind-off.
    assert r.stats["stitches_clamped"] == 32 + 4
    assert np.isfinite(r.vertices).all()
    inner = np.linalg.norm(r.centerline_points[:, :2], axis=1).min()
    print(f"tube: clearance {r.stats['clearance_min']:.2f} diameters, yarn {inner * 1e3:.2f} "
          "mm from the axis")
    assert inner > 0.00035


def tube_mesh(n: int = 24, k: int = 8, shift: float = 0.0) -> knitwear.MeshSurface:
    """A 5 cm wide, 10 cm tall tube of `n` x `k` quads, unwrapped round u with its seam
    vertices shared (as Blender keeps them); `shift` slides the seam's right side along v."""
    a = 2 * np.pi * np.arange(n) / n
    rows = np.linspace(0.0, 0.1, k + 1)
    pos = np.array([(0.025 * np.cos(t), 0.025 * np.sin(t), z) for z in rows for t in a])
    nrm = np.array([(np.cos(t), np.sin(t), 0.0) for _ in rows for t in a])
    tris, uvs = [], []
    for i in range(k):
        for j in range(n):
            last = j + 1 == n
            q = (i * n + j, i * n + (j + 1) % n, (i + 1) * n + (j + 1) % n, (i + 1) * n + j)
            dv = shift if last else 0.0
            corner_uv = [
                (j / n, i / k),
                ((j + 1) / n, i / k + dv),
                ((j + 1) / n, (i + 1) / k + dv),
                (j / n, (i + 1) / k),
            ]
            for c in ((0, 1, 2), (0, 2, 3)):
                tris.append([q[x] for x in c])
                uvs.append([corner_uv[x] for x in c])
    return knitwear.MeshSurface(
        pos.astype(np.float32), nrm.astype(np.float32), np.array(tris), np.array(uvs, np.float32)
    )


def test_a_mesh_closed_across_its_uv_seam_is_knitted_in_the_round() -> None:
    tube = tube_mesh()
    assert tube.cyclic == (True, False)
    result = knitwear.knit(tube, knitwear.Pattern.preset("rib_2x2"), ring_segments=4)
    assert result.stats["stitches_skipped"] == 0
    assert result.yarn_closed.all()
    assert result.stats["in_the_round"] == (True, False)
    # Knitted in the round from the gauge, the stitches round the tube are whole repeats.
    assert result.stats["wales"] % 4 == 0
    # A seam whose sides meet at other heights is no pure shift of the UV map: open.
    assert tube_mesh(shift=0.01).cyclic == (False, False)
    assert make_mesh().cyclic == (False, False)
