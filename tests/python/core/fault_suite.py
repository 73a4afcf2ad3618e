"""The fault suite's cases and runner (issue 18, item 6), shared by `test_faults.py` and
`benchmarks/fault_sweep.py`.

Cases are generated with hypothesis (derandomized, no example database, so every run tries the
same inputs) plus a scripted list of the inputs issue 18 found, and run by `fault_case.py` in
child processes under an address-space limit and a wall-clock limit per case. Cases are batched
many to a child; a child that dies or stalls has the case it was running blamed (confirmed on
its own in a fresh child) and the rest of its batch go on in a new child. Risky cases (absurd
sizes, deep nesting, special files) always run alone.

Kinds of outcome: the accepted ``ok`` and ``knit_error`` (plus ``internal``, a KnitError that
reports a caught panic: accepted, listed), and the faults ``crash`` (killed by a signal or an
abort), ``hang`` (over the time limit), ``other_exception`` (not a KnitError), ``nonfinite``
(NaN or inf in a returned float buffer) and ``wrong`` (a broken documented promise).
"""

from __future__ import annotations

import json
import math
import os
import selectors
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from collections.abc import Callable, Iterable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st
from hypothesis.configuration import set_hypothesis_home_dir
from hypothesis.strategies import SearchStrategy

# Hypothesis keeps no example database here (`database=None`) and its caches out of the tree.
if not os.environ.get("HYPOTHESIS_STORAGE_DIRECTORY"):
    set_hypothesis_home_dir(Path(tempfile.gettempdir()) / "knitwear-hypothesis")

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
HELPER = HERE / "fault_case.py"
DATA = ROOT / "tests" / "data" / "knitspeak"

FAULTS = ("crash", "hang", "other_exception", "nonfinite", "wrong")
ACCEPTED = ("ok", "knit_error", "internal")

# --- Values -----------------------------------------------------------------------------------

NAN = float("nan")
INF = float("inf")
F32_MAX = 3.4028234663852886e38
ODD_FLOATS = [NAN, INF, -INF, -0.0, 0.0, 5e-324, 1e-45, 1.1754943508222875e-38, 1e-12, -1.0]
ODD_FLOATS += [-1e-9, F32_MAX, 3.5e38, 1e300]
# No int here is valid and merely slow: each is refused, or is absurd enough to be refused.
ODD_INTS = [-(2**70), -(2**64), -(2**63), -(2**31), -2, -1, 0, 2**31 - 1, 2**31, 2**32]
ODD_INTS += [2**53 + 1, 2**63 - 1, 2**63, 2**64 - 1, 2**64, 2**70]

GRID: dict[str, Any] = {"$grid": {}}
STOCKINETTE: dict[str, Any] = {"$pattern": "stockinette"}
SMALL: dict[str, Any] = {"courses": 8, "wales": 8}


def tup(xs: Iterable[Any]) -> dict[str, Any]:
    return {"$t": list(xs)}


def floats_for(valid: list[float]) -> SearchStrategy[float]:
    return st.one_of(st.sampled_from(ODD_FLOATS), st.sampled_from(valid))


def ints_for(valid: list[int]) -> SearchStrategy[int]:
    return st.one_of(st.sampled_from(ODD_INTS), st.sampled_from(valid))


def tuple_of(elem: SearchStrategy[Any], n: int) -> SearchStrategy[dict[str, Any]]:
    """Mostly the right length; sometimes 0 to 5 elements."""
    right = st.tuples(*[elem] * n).map(tup)
    return st.one_of(right, right, right, st.lists(elem, max_size=5).map(tup))


def optional(s: SearchStrategy[Any]) -> SearchStrategy[Any]:
    return st.one_of(st.none(), s)


def array(
    shape: tuple[int, ...], values: SearchStrategy[float], dtype: str = "float32"
) -> SearchStrategy[dict[str, Any]]:
    n = math.prod(shape)
    return st.lists(values, min_size=n, max_size=n).map(
        lambda xs: {"$nd": {"dtype": dtype, "shape": list(shape), "data": xs}}
    )


COLOR_VALUES = st.one_of(st.sampled_from(ODD_FLOATS), st.floats(0, 1, width=32))
SHAPES_IMAGE = [(4, 4, 3), (4, 4, 4), (3, 5, 3), (1, 1, 3), (0, 0, 3), (4, 4), (4, 4, 1)]
SHAPES_IMAGE += [(4, 4, 5), (2, 2, 2, 3)]


@st.composite
def image(draw: st.DrawFn) -> dict[str, Any]:
    shape = draw(st.sampled_from(SHAPES_IMAGE))
    dtype = draw(st.sampled_from(["float32", "float32", "float32", "float64", "uint8"]))
    fill = draw(st.sampled_from(["data", "data", "fill"]))
    if fill == "fill":
        return {"$nd": {"dtype": dtype, "shape": list(shape), "fill": draw(COLOR_VALUES)}}
    a = draw(array(shape, COLOR_VALUES, dtype))
    if draw(st.integers(0, 5)) == 0:
        a["$nd"]["fortran"] = True
    if draw(st.integers(0, 5)) == 0:
        a["$nd"]["readonly"] = True
    return a


PALETTE_ENTRY = st.lists(COLOR_VALUES, min_size=0, max_size=5)
CHART_CHARS = st.sampled_from(list("0123456789abcz\n \t") + ["\ud800", "\u00e9", "Z", "-"])


@st.composite
def color_pattern(draw: st.DrawFn) -> dict[str, Any]:
    """A ColorPattern built inside the case (its constructor's errors are the case's)."""
    palette = draw(
        st.one_of(
            st.lists(PALETTE_ENTRY, max_size=4),
            st.lists(st.lists(COLOR_VALUES, min_size=3, max_size=3), min_size=1, max_size=40),
        )
    )
    how = draw(st.sampled_from(["new", "new", "stripes", "preset"]))
    if how == "new":
        chart = draw(st.text(CHART_CHARS, max_size=40))
        return {"$call": "ColorPattern", "args": [palette, chart]}
    if how == "stripes":
        return {"$call": "ColorPattern.stripes", "args": [palette, draw(ints_for([0, 1, 3]))]}
    name = draw(st.sampled_from(["fair_isle_band", "", "nope", "\ud800", "fair_isle_band\x00"]))
    return {"$call": "ColorPattern.preset", "args": [name, palette]}


EYES = [[0.025, 0.025, 0.1], [0.025, -0.05, 0.05], [0.025, 0.025, 1e6], [0.025, 0.025, 0.0]]
EYES += [[NAN, 0.0, 0.1], [0.025, 0.025, 1e-30], [INF, 0.0, 0.0]]
RESOLUTIONS = st.one_of(
    st.tuples(ints_for([1, 64, 65536, 65537]), ints_for([1, 48, 65536])).map(tup),
    st.tuples(st.sampled_from([64, 320]), st.sampled_from([48, 240])).map(tup),
    st.lists(st.sampled_from([64, 48, -1]), max_size=3).map(tup),
)
MATRIX_KINDS = ["zeros", "identity", "rank2", "nan", "inf", "huge", "random", "projective0"]


def matrix(kind: str, seed: int) -> list[list[float]]:
    rng = np.random.default_rng(seed)
    m = {
        "zeros": np.zeros((4, 4)),
        "identity": np.eye(4),
        "rank2": np.outer(rng.normal(size=4), rng.normal(size=4))
        + np.outer(rng.normal(size=4), rng.normal(size=4)),
        "nan": np.where(rng.random((4, 4)) < 0.3, NAN, np.eye(4)),
        "inf": np.where(rng.random((4, 4)) < 0.3, INF, np.eye(4)),
        "huge": np.eye(4) * 1e30,
        "random": rng.normal(size=(4, 4)),
        "projective0": np.vstack([np.eye(4)[:3], np.zeros((1, 4))]),
    }[kind]
    return m.tolist()


@st.composite
def camera(draw: st.DrawFn) -> dict[str, Any]:
    resolution = draw(RESOLUTIONS)
    if draw(st.booleans()):
        eye = draw(st.sampled_from(EYES))
        w = draw(st.sampled_from([1.0, 1.0, 0.0, 2.0, -1.0, NAN]))
        return {"$camera": {"eye": eye, "eyes": [*eye, w], "resolution": resolution}}
    kind = draw(st.sampled_from(MATRIX_KINDS))
    views = draw(st.sampled_from([None, 0, 1, 2, 3]))
    m = matrix(kind, draw(st.integers(0, 3)))
    data: Any = m if views is None else [m] * views
    shape = draw(st.sampled_from([None, None, None, [3, 3], [16], [2, 2, 4]]))
    if shape is not None and math.prod(shape) != np.size(data):
        data, shape = np.eye(4)[:3, :3].tolist(), [3, 3]
    mats = {"dtype": "float64", "data": data}
    if shape is not None:
        mats["shape"] = shape
    eye_w = draw(st.sampled_from([1.0, 0.0, 2.0, -1.0, NAN]))
    eye = [0.025, 0.025, 0.1, eye_w]
    eyes: Any = eye if views is None else [eye] * draw(st.sampled_from([views, views, 1, 5]))
    if draw(st.integers(0, 6)) == 0:
        eyes = draw(st.sampled_from([[], [0.0, 0.0, 1.0], [0.0] * 5, [[0.0] * 4] * 2]))
    made: dict[str, Any] = {"$call": "Camera", "args": [{"$nd": mats}, eyes, resolution]}
    if views and draw(st.integers(0, 2)) == 0:
        # The surface in each view's pose (a deforming source); a count that does not match.
        count = draw(st.sampled_from([views, views, 1, views + 1]))
        made["kwargs"] = {"poses": [GRID] * count}
    return made


@st.composite
def stitch_levels(draw: st.DrawFn) -> Any:
    shape = draw(st.sampled_from([(8, 8), (8, 8), (8, 7), (0,), (64,), (8, 8, 1)]))
    values = st.sampled_from([0, 1, 2, 3, 4, 5, 255, -1, 256])
    dtype = draw(st.sampled_from(["uint8", "uint8", "int64", "float32"]))
    return draw(array(shape, values, dtype))


def knit_keywords(texture: bool) -> dict[str, SearchStrategy[Any]]:
    """Each keyword of `Knit` (and `knit_texture`), drawn odd: out of range, NaN, huge."""
    kw: dict[str, SearchStrategy[Any]] = {
        "courses": ints_for([1, 2, 3, 17, 40, 1_000_000]),
        "wales": ints_for([1, 2, 3, 17, 40, 1_000_000]),
        "gauge": tuple_of(floats_for([20.0, 1e-3, 1e6]), 2),
        "yarn_radius": optional(floats_for([0.0005, 1.0, 1e-9])),
        "stitch_size": tuple_of(floats_for([0.005, 100.0, 1e-7]), 2),
        "fluffiness": floats_for([0.0, 0.5, 4.0, 4.0001]),
        "ring_segments": ints_for([2, 3, 12, 64, 65]),
        "plies": ints_for([0, 1, 3, 8, 9]),
        "live_loops": st.booleans(),
        "samples_per_loop": ints_for([5, 6, 32, 256, 257]),
        "tension": floats_for([0.5, 0.99, 0.991, 1.0]),
        "kappa": floats_for([0.01, 0.02, 0.0201]),
        "seed": st.one_of(ints_for([1, 12345]), st.integers()),
        "colors": optional(color_pattern()),
        "color_image": optional(image()),
        "color_variation": floats_for([0.0, 1.0, 1.01]),
        "threads": optional(ints_for([1, 2, 64, 1025])),
        "budget_bytes": optional(ints_for([1, 1000, 10**6, 10**12])),
        "measure_clearance": st.booleans(),
    }
    if texture:
        kw["width"] = ints_for([1, 16, 64, 1024])
        kw["height"] = ints_for([1, 16, 64, 1024])
        return kw
    quality = st.one_of(
        st.tuples(ints_for([3, 4, 6]), ints_for([4, 8, 16]), st.booleans()).map(tup),
        st.lists(st.sampled_from([3, 8, True, -1]), max_size=4).map(tup),
    )
    kw |= {
        "camera": optional(camera()),
        "stitch_levels": optional(stitch_levels()),
        "detail_px": tuple_of(floats_for([12.0, 5.0, 1.0]), 3),
        "mid_quality": quality,
        "far_quality": quality,
        "frustum_margin": floats_for([0.0, 100.0, 101.0]),
        "cull_back_faces": st.booleans(),
        "cull_hidden": st.booleans(),
        "hidden_supersampling": ints_for([0, 1, 16, 17]),
        "seen_triangles": optional(st.binary(max_size=64).map(lambda b: {"$b": b.hex()})),
    }
    return kw


KNIT_KW = knit_keywords(texture=False)
TEXTURE_KW = knit_keywords(texture=True)


@st.composite
def setting_case(draw: st.DrawFn) -> dict[str, Any]:
    """`knit`, `Knit` or `knit_texture` on a small sheet with one to three odd settings."""
    name = draw(st.sampled_from(["knit", "Knit", "knit_texture"]))
    table = TEXTURE_KW if name == "knit_texture" else KNIT_KW
    kwargs: dict[str, Any] = dict(SMALL)
    if name == "knit_texture":
        kwargs |= {"width": 64, "height": 64}
    for key in draw(st.lists(st.sampled_from(sorted(table)), min_size=1, max_size=3, unique=True)):
        kwargs[key] = draw(table[key])
    return {"call": name, "args": [GRID, STOCKINETTE], "kwargs": kwargs}


@st.composite
def camera_case(draw: st.DrawFn) -> dict[str, Any]:
    """A knit seen by an odd camera, with or without hidden-yarn culling and detail levels."""
    kwargs: dict[str, Any] = dict(SMALL)
    kwargs["camera"] = draw(camera())
    if draw(st.booleans()):
        kwargs["cull_hidden"] = True
        kwargs["hidden_supersampling"] = draw(st.sampled_from([1, 4, 16]))
    if draw(st.booleans()):
        kwargs["detail_px"] = draw(tuple_of(floats_for([12.0, 5.0, 1.0]), 3))
    if draw(st.booleans()):
        kwargs["cull_back_faces"] = True
    return {
        "call": draw(st.sampled_from(["knit", "Knit"])),
        "args": [GRID, STOCKINETTE],
        "kwargs": kwargs,
    }


# --- Surfaces ---------------------------------------------------------------------------------

SCALES = [1e-30, 1e-9, 1e-4, 0.05, 0.1, 1e3, 1e6, 1e20, F32_MAX]
OFFSETS = [0.0, 0.0, 0.0, 1e4, 1e6, 1e30]
POISON = [NAN, INF, -INF, 0.0, 1e38, -1e38, 1e-40]


def plane(rows: int, cols: int, sx: float, sy: float, offset: float) -> np.ndarray:
    u, v = np.meshgrid(np.linspace(0, 1, cols), np.linspace(0, 1, rows))
    return np.stack([u * sx + offset, v * sy + offset, np.zeros_like(u) + offset], axis=-1)


def mutate(draw: st.DrawFn, a: np.ndarray) -> np.ndarray:
    """Poison a few entries, collapse everything or a row, or leave it."""
    a = a.copy()
    how = draw(st.sampled_from(["none", "none", "poison", "poison", "collapse", "row", "zero"]))
    if how == "poison" and a.size:
        for _ in range(draw(st.integers(1, 3))):
            a.flat[draw(st.integers(0, a.size - 1))] = draw(st.sampled_from(POISON))
    elif how == "collapse":
        a[...] = a.reshape(-1)[:1] if a.size else 0
    elif how == "row" and a.ndim >= 2 and a.shape[0]:
        a[0] = a[0][:1] if a.shape[1:] and a.shape[1] else 0
    elif how == "zero":
        a[...] = 0
    return a


def encode(a: np.ndarray, dtype: str) -> dict[str, Any]:
    return {"$nd": {"dtype": dtype, "shape": list(a.shape), "data": a.reshape(-1).tolist()}}


SURFACE_DTYPES = ["float32"] * 6 + ["float64", "int32", "float16", "bool"]


@st.composite
def grid_case(draw: st.DrawFn) -> dict[str, Any]:
    """A GridSurface of odd size, scale, position, shape or dtype, then knitted."""
    rows, cols = draw(st.integers(0, 10)), draw(st.integers(0, 10))
    sx = draw(st.sampled_from(SCALES))
    sy = draw(st.sampled_from([sx, sx, sx, *SCALES]))
    pos = plane(rows, cols, sx, sy, draw(st.sampled_from(OFFSETS)))
    nrm = np.zeros_like(pos)
    if nrm.size:
        nrm[..., 2] = 1.0
    pos, nrm = mutate(draw, pos), mutate(draw, nrm)
    shape = draw(st.sampled_from(["ok"] * 6 + ["channels2", "channels4", "flat", "extra"]))
    if shape == "channels2":
        pos = pos[..., :2]
    elif shape == "channels4":
        pos = np.concatenate([pos, pos[..., :1]], axis=-1)
    elif shape == "flat":
        pos = pos.reshape(-1, 3)
    elif shape == "extra":
        pos = pos[None]
    if draw(st.integers(0, 4)) == 0:
        nrm = nrm[: max(rows - 1, 0)]
    dt = draw(st.sampled_from(SURFACE_DTYPES))
    args = [encode(pos, dt), encode(nrm, draw(st.sampled_from([dt, "float32"])))]
    args += [draw(st.booleans()), draw(st.booleans())]
    return then_knit(draw, {"call": "GridSurface", "args": args})


def then_knit(draw: st.DrawFn, case: dict[str, Any]) -> dict[str, Any]:
    """Knit the surface the case built: at 8 x 8 stitches, or at the default gauge (which must
    refuse a huge surface at once), or as a texture."""
    how = draw(st.sampled_from(["small", "small", "small", "gauge", "texture", "plush", "none"]))
    if how == "small":
        case["then"] = [{"call": "knit", "args": [STOCKINETTE], "kwargs": SMALL}]
    elif how == "gauge":
        case["then"] = [{"call": "knit", "args": [STOCKINETTE], "kwargs": {}}]
    elif how == "texture":
        kw = {**SMALL, "width": 32, "height": 32}
        case["then"] = [{"call": "knit_texture", "args": [STOCKINETTE], "kwargs": kw}]
    elif how == "plush":
        case["then"] = [{"call": "plush", "args": [], "kwargs": SMALL}]
    return case


@st.composite
def mesh_case(draw: st.DrawFn) -> dict[str, Any]:
    """A MeshSurface: odd indices, index dtypes, UV layouts, degenerate or poisoned values."""
    n = draw(st.sampled_from([2, 2, 3, 4]))
    s = draw(st.sampled_from(SCALES))
    pos = plane(n, n, s, s, draw(st.sampled_from(OFFSETS))).reshape(-1, 3)
    tris = []
    for i in range(n - 1):
        for j in range(n - 1):
            a, b, c, d = i * n + j, i * n + j + 1, (i + 1) * n + j + 1, (i + 1) * n + j
            tris += [[a, b, c], [a, c, d]]
    t = np.array(tris, dtype=np.int64)
    uv2 = plane(n, n, 1.0, 1.0, 0.0)[..., :2].reshape(-1, 2)
    uvs = uv2[t]  # (T, 3, 2), per corner
    nrm = np.tile(np.array([0.0, 0.0, 1.0]), (len(pos), 1))
    pos, nrm, uvs = mutate(draw, pos), mutate(draw, nrm), mutate(draw, uvs)
    tri_how = draw(st.sampled_from(["ok"] * 5 + ["oob", "negative", "huge", "empty", "quads"]))
    if tri_how == "oob":
        t[0, 2] = len(pos)
    elif tri_how == "negative":
        t[-1, 0] = -1
    elif tri_how == "huge":
        t[0, 0] = 2**40
    elif tri_how == "empty":
        t, uvs = t[:0], uvs[:0]
    elif tri_how == "quads":
        t = np.concatenate([t, t[:, :1]], axis=1)
    uv_how = draw(st.sampled_from(["ok"] * 5 + ["flat", "per_vertex", "short", "same"]))
    if uv_how == "flat":
        uvs = uvs.reshape(-1, 2)
    elif uv_how == "per_vertex":
        uvs = uv2
    elif uv_how == "short":
        uvs = uvs[:-1]
    elif uv_how == "same":
        uvs = np.zeros_like(uvs) + 0.5
    tri_dtype = draw(st.sampled_from(["int32", "int32", "int64", "uint32", "int16", "float32"]))
    if tri_how == "huge":
        tri_dtype = "int64"
    args = [
        encode(pos, draw(st.sampled_from(SURFACE_DTYPES))),
        encode(nrm, "float32"),
        encode(t, tri_dtype),
        encode(uvs, draw(st.sampled_from(["float32"] * 4 + ["float64"]))),
    ]
    return then_knit(draw, {"call": "MeshSurface", "args": args})


# --- Patterns ---------------------------------------------------------------------------------


def seed_texts() -> list[str]:
    texts = [p.read_text(encoding="utf-8") for p in sorted(DATA.glob("*.ks"))]
    texts += ["kp\npk", "kkkk\npppp", "XX..\n..XX\nX = 2/2 RC", "k\n", "oooo\n////", "."]
    return texts


SEEDS = seed_texts()
NASTY = ["[", "]", "(", ")", "*", ";", ",", ".", "\n", "Row ", "Rows 1-", " times", "rep from *"]
NASTY += ["99999999999999999999", "18446744073709551616", "4294967296", "-1", "0", "k", "p"]
NASTY += ["2/2 RC", "7/7 LC", "1/1 LPC", "\x00", "\ud800", "\udfff", "\u202e", "\U0001f9f6"]
NASTY += ["\t", "\r\n", "\u00e9", "\uff4b", "K1", "ssk", "yo", "MB", "k2tog", "sl1", ":", "RS"]
NASTY += ["WS", "=", "X = ", "\ufeff", "k0", "p-1", "k1000000", "\u0301", " " * 50]


@st.composite
def mutated_text(draw: st.DrawFn) -> str:
    text = draw(st.sampled_from(SEEDS))
    for _ in range(draw(st.integers(0, 6))):
        pos = draw(st.integers(0, len(text)))
        op = draw(st.sampled_from(["insert", "insert", "delete", "replace", "dup_line", "swap"]))
        piece = draw(st.one_of(st.sampled_from(NASTY), st.text(max_size=6)))
        if op == "insert":
            text = text[:pos] + piece + text[pos:]
        elif op == "delete":
            text = text[:pos] + text[pos + draw(st.integers(1, 8)) :]
        elif op == "replace":
            text = text[:pos] + piece + text[pos + len(piece) :]
        else:
            lines = text.split("\n")
            i, j = draw(st.integers(0, len(lines) - 1)), draw(st.integers(0, len(lines) - 1))
            if op == "dup_line":
                lines.insert(i, lines[j])
            else:
                lines[i], lines[j] = lines[j], lines[i]
            text = "\n".join(lines)
    return text


@st.composite
def built_text(draw: st.DrawFn) -> str:
    """Texts built to stress the parser: deep nesting, huge counts and row numbers, wide rows
    and big charts (within what a child answers in well under a second when refused)."""
    kind = draw(st.sampled_from(["nest", "count", "rows", "wide", "chart", "legend"]))
    if kind == "nest":
        d = draw(st.sampled_from([1, 2, 15, 16, 17, 64, 1000]))
        o, c = draw(st.sampled_from([("[", "]"), ("(", ")"), ("[", ")")]))
        reps = draw(st.sampled_from(["", " 2 times", " 0 times", " 18446744073709551616 times"]))
        return "Row 1: " + (o + "k1, ") * d + "p1" + (c + reps) * d
    if kind == "count":
        n = draw(st.sampled_from(ODD_INTS + [10**6, 2**32 + 1]))
        forms = [f"Row 1: k{n}", f"Row 1: (k1, p1) {n} times", f"Row 1: k1\nRow 2: p{n}"]
        return draw(st.sampled_from(forms))
    if kind == "rows":
        a = draw(st.sampled_from([0, 1, 2, 1024, 1025, 10**8, 2**64]))
        b = draw(st.sampled_from([1, 3, 1024, 1025, 10**8, 2**64]))
        return draw(st.sampled_from([f"Rows {a}-{b}: k1", f"Row {a}: k1", f"Rows {a} and {b}: k1"]))
    if kind == "wide":
        n = draw(st.sampled_from([255, 256, 257, 5000]))
        return "Row 1: " + ", ".join(["k1", "p1"] * (n // 2))
    if kind == "chart":
        w = draw(st.sampled_from([1, 16, 256, 257]))
        h = draw(st.sampled_from([1, 16, 256, 257]))
        cell = draw(st.sampled_from(["kp", "k", "p.", "X."]))
        return "\n".join((cell * w)[:w] for _ in range(h))
    symbols = draw(st.lists(st.sampled_from(list("XYZ?*")), min_size=1, max_size=3, unique=True))
    meanings = st.sampled_from([*NASTY, "2/2 RC", "k", "p"])
    legend = "\n".join(f"{s} = {draw(meanings)}" for s in symbols)
    return "".join(symbols) + "k\n" + "k" * (len(symbols) + 1) + "\n" + legend


PATTERN_CALLS = ["Pattern.from_knitspeak", "Pattern.from_chart", "Pattern.from_text"]
PATTERN_CALLS += ["Pattern.looks_like_knitspeak"]


@st.composite
def pattern_case(draw: st.DrawFn) -> dict[str, Any]:
    """A pattern from mutated, built or random text, read back through its chart."""
    text = draw(st.one_of(mutated_text(), mutated_text(), built_text(), st.text(max_size=80)))
    return {"call": draw(st.sampled_from(PATTERN_CALLS)), "args": [text]}


@st.composite
def preset_case(draw: st.DrawFn) -> dict[str, Any]:
    name = draw(st.one_of(st.sampled_from(["stockinette", "cable_c4", ""]), st.text(max_size=12)))
    return {"call": "Pattern.preset", "args": [name]}


@st.composite
def file_case(draw: st.DrawFn) -> dict[str, Any]:
    """`Pattern.from_file` on a new file of odd bytes, named by str, bytes or a PathLike."""
    content = draw(
        st.one_of(
            st.binary(max_size=64),
            mutated_text().map(lambda t: t.encode("utf-8", "surrogatepass")),
            st.sampled_from([b"\xef\xbb\xbfRow 1: k1", "\ufeffRow 1: k1".encode("utf-16-le")]),
        )
    )
    spec = {"kind": "file", "hex": content.hex(), "as_bytes": draw(st.booleans())}
    if draw(st.integers(0, 3)) == 0:
        spec["name"] = draw(st.sampled_from(["p\udcff.txt", "a b.ks", "x" * 255, "\u00e9.ks"]))
    return {"call": "Pattern.from_file", "args": [{"$path": spec}]}


# --- Plush, noise, measurement ----------------------------------------------------------------


def seq(elem: SearchStrategy[Any], right: int) -> SearchStrategy[list[Any]]:
    fixed = st.lists(elem, min_size=right, max_size=right)
    return st.one_of(fixed, fixed, st.lists(elem, max_size=5))


PLUSH_KW: dict[str, SearchStrategy[Any]] = {
    "courses": ints_for([1, 3, 40, 1_000_000]),
    "wales": ints_for([1, 3, 40, 1_000_000]),
    "gauge": tuple_of(floats_for([48.0, 1e-3, 1e6]), 2),
    "piles_per_stitch": ints_for([1, 64, 65]),
    "pile_length": optional(floats_for([0.01, 1e30])),
    "pile_radius": optional(floats_for([0.003, 1e30])),
    "slices": ints_for([1, 64, 65]),
    "lean": optional(seq(floats_for([0.5, -1.5, 1.56, 7.0]), 2)),
    "theta_max": optional(floats_for([0.3, 0.78, 0.79])),
    "noise_scales": optional(st.lists(ints_for([1, 2, 4, 64]), max_size=6)),
    "noise_size": optional(tuple_of(ints_for([1, 16, 4096]), 2)),
    "seed": st.one_of(ints_for([7]), st.integers()),
    "eye": optional(seq(floats_for([0.02, 0.3]), 3)),
    "view_dir": optional(seq(floats_for([0.0, 1.0, -1.0]), 3)),
    "colors": optional(st.one_of(color_pattern(), seq(COLOR_VALUES, 3), image())),
    "color_image": optional(image()),
    "press": optional(image()),
    "press_strength": optional(floats_for([0.5, 1.0, 1.01])),
    "press_direction": optional(floats_for([0.0, 3.14, 100.0])),
    "threads": optional(ints_for([1, 2, 1025])),
    "budget_bytes": optional(ints_for([1, 10**6])),
}


@st.composite
def plush_case(draw: st.DrawFn) -> dict[str, Any]:
    kwargs: dict[str, Any] = dict(SMALL)
    for key in draw(
        st.lists(st.sampled_from(sorted(PLUSH_KW)), min_size=1, max_size=3, unique=True)
    ):
        kwargs[key] = draw(PLUSH_KW[key])
    return {"call": "plush", "args": [GRID], "kwargs": kwargs}


@st.composite
def noise_case(draw: st.DrawFn) -> dict[str, Any]:
    size = draw(
        st.one_of(
            ints_for([1, 2, 64]), tuple_of(ints_for([1, 3, 64]), 2), st.sampled_from([True, 2.5])
        )
    )
    kwargs: dict[str, Any] = {}
    if draw(st.booleans()):
        kwargs["theta_max"] = draw(floats_for([0.0, 0.35, 0.79]))
    if draw(st.booleans()):
        kwargs["scales"] = draw(st.lists(ints_for([1, 2, 8, 64]), max_size=5))
    if draw(st.booleans()):
        kwargs["seed"] = draw(st.one_of(ints_for([3]), st.integers()))
    kwargs["rgb"] = draw(st.booleans())
    if draw(st.booleans()):
        kwargs["threads"] = draw(ints_for([1, 2]))
    return {"call": "fractal_noise", "args": [size], "kwargs": kwargs}


@st.composite
def measure_case(draw: st.DrawFn) -> dict[str, Any]:
    """`measure_cover` with odd bounds and resolutions on a small knit."""
    bounds = draw(tuple_of(floats_for([0.0, 0.05, -0.05, 1e-9]), 4))
    resolution = draw(ints_for([0, 1, 10, 800, 100_000]))
    knit = {"call": "knit", "args": [GRID, STOCKINETTE], "kwargs": SMALL}
    return knit | {"then": [{"call": "measure_cover", "args": [bounds, resolution]}]}


# --- The issue's own cases (scripted) ---------------------------------------------------------


def checker(n: int) -> str:
    return "\n".join("".join("kp"[(r // 2 + c // 2) % 2] for c in range(n)) for r in range(n))


def knit_with(**kwargs: Any) -> dict[str, Any]:
    """`knit` of stockinette on the 5 cm sheet at 8 x 8 stitches, with `kwargs` on top."""
    return {"call": "knit", "args": [GRID, STOCKINETTE], "kwargs": {**SMALL, **kwargs}}


def from_file(path: Any) -> dict[str, Any]:
    return {"call": "Pattern.from_file", "args": [path]}


def camera_call(matrices: dict[str, Any], eye: list[float], res: list[int]) -> dict[str, Any]:
    return {"call": "Camera", "args": [{"$nd": matrices}, eye, tup(res)]}


def scripted_cases() -> list[dict[str, Any]]:
    """Issue 18's inputs, each as it was reported; all run alone."""
    deep = "Row 1: " + "[" * 20000 + "k1" + "]" * 20000
    eye4 = {"data": np.eye(4).tolist()}
    look = {"eye": EYES[0], "resolution": tup([64, 48])}
    cases: list[dict[str, Any]] = [
        {"call": "Pattern.from_chart", "args": [checker(1024)]},
        {"call": "Pattern.from_text", "args": [checker(1024)]},
        {"call": "Pattern.from_knitspeak", "args": [deep]},
        {"call": "Pattern.from_text", "args": [deep]},
        {"call": "Pattern.from_knitspeak", "args": ["Rows 1-100000000: k1"]},
        {"call": "Pattern.from_knitspeak", "args": ["Row 1: 7/7 RC"]},
        {"call": "Pattern.from_knitspeak", "args": ["Row 1: k1\ud800"]},
        {"call": "Pattern.from_chart", "args": ["\udc80k\npk"]},
        {"call": "Pattern.from_chart", "args": ["\n".join(["k"] * 100_000)]},
        {"call": "Pattern.from_chart", "args": ["k" * 100_000]},
        from_file("/dev/zero"),
        from_file("/dev/urandom"),
        from_file("/dev/null"),
        from_file("/"),
        from_file("/nonexistent/pattern.ks"),
        from_file(""),
        from_file("bad\x00name.ks"),
        from_file({"$b": b"/nonexistent/pattern.ks".hex()}),
        from_file({"$b": (DATA / "seed.ks").as_posix().encode().hex()}),
        from_file({"$path": {"kind": "pathlike", "path": "/etc"}}),
        from_file({"$path": {"kind": "folder"}}),
        from_file({"$path": {"kind": "fifo"}}),
        from_file({"$path": {"kind": "file", "text": "k" * 1023 + "\n", "repeat": 5000}}),
        knit_with(seed=-1),
        knit_with(seed=2**64),
        knit_with(budget_bytes=2**70),
        knit_with(courses=2**64),
        knit_with(gauge=tup([20.0, 28.0, 1.0])),
        knit_with(stitch_size=tup([100.0, 100.0])),
        knit_with(hidden_supersampling=-1),
        knit_with(threads=2**20),
        {"call": "knit", "args": [{"$grid": {"sx": 500.0, "sy": 500.0}}, STOCKINETTE]},
        {"call": "knit", "args": [{"$grid": {"z0": 1e6}}, STOCKINETTE], "kwargs": SMALL},
        {"call": "knit_texture", "args": [GRID, STOCKINETTE], "kwargs": {**SMALL, "width": -1}},
        {
            "call": "knit_texture",
            "args": [GRID, STOCKINETTE],
            # The largest image, 4 GiB, under a 1 GiB budget: refused before anything large
            # is taken (within the default budget it is legitimately minutes of work here).
            "kwargs": {**SMALL, "width": 16384, "height": 16384, "budget_bytes": 1 << 30},
        },
        {
            "call": "knit_texture",
            "args": [GRID, STOCKINETTE],
            "kwargs": {**SMALL, "width": 16384, "height": 4},
        },
        {"call": "ColorPattern.stripes", "args": [[[1.0, 0.0, 0.0]], -2]},
        camera_call({"shape": [4, 4], "fill": 0.0}, [0.0, 0.0, 1.0, 1.0], [64, 48]),
        camera_call(eye4, [0.0, 0.0, 1.0, 2.0], [64, 48]),
        camera_call(eye4, [0.0, 0.0, 1.0, -1.0], [64, 48]),
        camera_call(eye4, [0.0, 0.0, 1.0, 1.0], [-1, 48]),
        {
            "call": "Camera",
            "args": [
                {"$nd": {"shape": [10_000, 4, 4], "fill": 0.5}},
                {"$nd": {"shape": [10_000, 4], "fill": 1.0}},
                tup([64, 48]),
            ],
        },
        knit_with(cull_hidden=True, camera={"$camera": {**look, "resolution": tup([65536] * 2)}}),
        knit_with(camera={"$camera": {**look, "matrices": {"shape": [4, 4], "fill": 0.0}}}),
        {"call": "plush", "args": [GRID], "kwargs": {**SMALL, "pile_length": 1e30}},
        {"call": "plush", "args": [GRID], "kwargs": {**SMALL, "lean": [0.1, 0.2, 0.3]}},
        {"call": "fractal_noise", "args": [2**70]},
        {"call": "fractal_noise", "args": [tup([100_000, 100_000])]},
    ]
    for c in cases:
        c["isolate"] = True
    return cases


# --- Generation -------------------------------------------------------------------------------

FAMILIES: dict[str, SearchStrategy[dict[str, Any]]] = {
    "setting": setting_case(),
    "camera": camera_case(),
    "grid": grid_case(),
    "mesh": mesh_case(),
    "pattern": pattern_case(),
    "preset": preset_case(),
    "file": file_case(),
    "plush": plush_case(),
    "noise": noise_case(),
    "measure": measure_case(),
}


# Examples per family in the test: about 480 generated cases plus the list, in about a
# minute on two cores (most are refused in milliseconds; a child's first knit tunes for ~3 s).
COUNTS = {
    "setting": 120,
    "camera": 40,
    "grid": 60,
    "mesh": 40,
    "pattern": 100,
    "preset": 10,
    "file": 25,
    "plush": 50,
    "noise": 25,
    "measure": 15,
}


def generate(strategy: SearchStrategy[dict[str, Any]], n: int) -> list[dict[str, Any]]:
    """`n` examples of `strategy`, the same ones on every run (no database, derandomized);
    duplicates dropped."""
    out: list[dict[str, Any]] = []

    @settings(
        max_examples=n,
        derandomize=True,
        database=None,
        deadline=None,
        phases=[Phase.generate],
        suppress_health_check=list(HealthCheck),
    )
    @given(strategy)
    def collect(case: dict[str, Any]) -> None:
        out.append(case)

    collect()
    seen: set[str] = set()
    unique = []
    for c in out:
        key = json.dumps(c, sort_keys=True)
        if key not in seen:
            seen.add(key)
            unique.append(c)
    return unique


def build_cases(
    counts: dict[str, int], scripted: bool = True, knit_patterns: bool = False
) -> list[dict[str, Any]]:
    """`counts[family]` generated cases of each family, then the scripted ones. With
    `knit_patterns`, every pattern that parses is also knitted at 8 x 8 stitches (slow: each
    new pattern is tuned, seconds to minutes)."""
    cases: list[dict[str, Any]] = []
    for family, n in counts.items():
        for i, c in enumerate(generate(FAMILIES[family], n)):
            if knit_patterns and c["call"] in PATTERN_CALLS[:3] + ["Pattern.from_file"]:
                c["then"] = [{"call": "knit", "args": [GRID], "kwargs": SMALL, "value_at": 1}]
            cases.append({"id": f"{family}-{i:03d}", **c})
    if scripted:
        for i, c in enumerate(scripted_cases()):
            cases.append({"id": f"issue18-{i:02d}", **c})
    return cases


# --- Running ----------------------------------------------------------------------------------


@dataclass
class Outcome:
    id: str
    kind: str
    detail: str
    seconds: float
    case: dict[str, Any] = field(repr=False)


def risky(case: dict[str, Any]) -> bool:
    """Cases that run alone: scripted ones, big texts, absurd integers anywhere."""
    if case.get("isolate"):
        return True
    text = json.dumps(case)
    if len(text) > 20_000:
        return True

    def big(v: Any) -> bool:
        if isinstance(v, bool):
            return False
        if isinstance(v, int):
            return abs(v) >= 2**16
        if isinstance(v, list):
            return any(big(x) for x in v)
        if isinstance(v, dict):
            return any(big(x) for k, x in v.items() if k != "$nd")
        return False

    return big(case.get("kwargs", {})) or big(case.get("args", []))


def describe_exit(rc: int | None, stderr: str) -> str:
    if rc is not None and rc < 0:
        try:
            name = signal.Signals(-rc).name
        except ValueError:
            name = f"signal {-rc}"
    else:
        name = f"exit {rc}"
    lines = [ln.strip() for ln in stderr.splitlines() if ln.strip()]
    keys = ("memory allocation", "panicked", "Fatal Python error", "overflow", "Killed", "Error")
    key = [ln for ln in lines if any(k in ln for k in keys)]
    tail = " | ".join((key or [ln for ln in lines if "Extension modules" not in ln])[-3:])
    return f"{name}: {tail[:300]}" if tail else name


def run_child(
    cases: list[dict[str, Any]],
    timeout: float,
    memory: int,
    env: dict[str, str],
) -> tuple[dict[int, Outcome], int | None, str]:
    """Runs `cases` in one child. Returns the outcomes it reported, the index of the case
    that was running when it died or stalled (None if it finished), and how it ended."""
    payload = "".join(json.dumps(c) + "\n" for c in cases).encode()
    with tempfile.TemporaryFile() as err, tempfile.TemporaryFile() as inp:
        inp.write(payload)
        inp.seek(0)
        proc = subprocess.Popen(
            [sys.executable, str(HELPER)],
            stdin=inp,
            stdout=subprocess.PIPE,
            stderr=err,
            env={**env, "KNITWEAR_FAULT_AS_BYTES": str(memory)},
        )
        assert proc.stdout is not None
        fd = proc.stdout.fileno()
        sel = selectors.DefaultSelector()
        sel.register(fd, selectors.EVENT_READ)
        done: dict[int, Outcome] = {}
        running: int | None = None
        started = time.monotonic()
        deadline = started + timeout
        buf = b""
        stalled = False
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                stalled = True
                proc.kill()
                break
            if not sel.select(left):
                continue
            chunk = os.read(fd, 1 << 16)
            if not chunk:
                break
            buf += chunk
            *lines, buf = buf.split(b"\n")
            for line in lines:
                now = time.monotonic()
                if line.startswith(b"S "):
                    running, started, deadline = int(line[2:]), now, now + timeout
                elif line.startswith(b"R "):
                    r = json.loads(line[2:])
                    i = running if running is not None else len(done)
                    done[i] = Outcome(r["id"], r["outcome"], r["detail"], now - started, cases[i])
                    running, started, deadline = None, now, now + timeout
        sel.close()
        proc.stdout.close()
        rc = proc.wait()
        err.seek(0)
        stderr = err.read().decode("utf-8", "replace")
    if stalled:
        blamed = running if running is not None else len(done)
        return done, blamed, f"no answer in {timeout:.0f} s"
    if len(done) < len(cases):
        blamed = running if running is not None else len(done)
        return done, blamed, describe_exit(rc, stderr)
    return done, None, ""


def child_env() -> dict[str, str]:
    env = dict(os.environ)
    site = ROOT / "build" / "site"
    if site.is_dir() and str(site) not in env.get("PYTHONPATH", "").split(os.pathsep):
        env["PYTHONPATH"] = os.pathsep.join(p for p in (str(site), env.get("PYTHONPATH")) if p)
    env["PYTHONFAULTHANDLER"] = "1"
    env.setdefault("PYTHONHASHSEED", "0")
    return env


def run_batch(
    cases: list[dict[str, Any]], timeout: float, memory: int, env: dict[str, str]
) -> list[Outcome]:
    """Every case of `cases`, restarting the child past a case that killed or stalled it (and
    re-running that case alone to confirm it, when it was not alone)."""
    out: list[Outcome] = []
    rest = list(cases)
    while rest:
        done, blamed, how = run_child(rest, timeout, memory, env)
        out += [done[i] for i in sorted(done)]
        if blamed is None:
            break
        case = rest[blamed]
        kind = "hang" if how.startswith("no answer") else "crash"
        seconds = timeout if kind == "hang" else 0.0
        if len(rest) > 1:
            again, blamed_alone, how_alone = run_child([case], timeout, memory, env)
            if blamed_alone is None:
                kind, how = "crash" if kind == "crash" else "hang", f"{how} (only in a batch)"
            else:
                how = how_alone
                kind = "hang" if how.startswith("no answer") else "crash"
        out.append(Outcome(case["id"], kind, how, seconds, case))
        rest = rest[blamed + 1 :]
    return out


def run_cases(
    cases: list[dict[str, Any]],
    *,
    timeout: float = 20.0,
    workers: int = 2,
    batch: int = 25,
    memory: int = 6 << 30,
    progress: Callable[[Outcome], None] | None = None,
) -> list[Outcome]:
    """Runs every case in child processes, `workers` at a time: risky ones alone, the rest
    `batch` to a child (grouped by family, so a child's tuning cache is reused)."""
    env = child_env()
    alone = [[c] for c in cases if risky(c)]
    safe = [c for c in cases if not risky(c)]
    batches = [safe[i : i + batch] for i in range(0, len(safe), batch)] + alone
    results: list[Outcome] = []
    with ThreadPoolExecutor(max_workers=workers) as pool:
        for got in pool.map(lambda b: run_batch(b, timeout, memory, env), batches):
            results += got
            if progress:
                for o in got:
                    progress(o)
    return results


# --- Reporting --------------------------------------------------------------------------------


def counts(outcomes: list[Outcome]) -> Counter[str]:
    c: Counter[str] = Counter(o.kind for o in outcomes)
    for k in FAULTS + ACCEPTED:
        c.setdefault(k, 0)
    return c


def summary(outcomes: list[Outcome]) -> str:
    c = counts(outcomes)
    refusals = [o for o in outcomes if o.kind == "knit_error"]
    slowest = max(refusals, key=lambda o: o.seconds, default=None)
    slow = f", slowest refusal {slowest.seconds:.2f} s ({slowest.id})" if slowest else ""
    return (
        f"{len(outcomes)} cases: crashes {c['crash']}, hangs {c['hang']}, "
        f"non-KnitError exceptions {c['other_exception']}, NaN/inf outputs {c['nonfinite']}, "
        f"wrong outputs {c['wrong']} | clear errors {c['knit_error']}, "
        f"internal errors {c['internal']}, ok {c['ok']}{slow}"
    )


def brief(v: Any, width: int = 60) -> str:
    """A value of a case as Python-like text, arrays and long texts abbreviated."""
    if isinstance(v, str):
        r = repr(v)
        return r if len(r) <= width else f"{r[: width - 20]}...<{len(v)} chars>"
    if isinstance(v, list):
        text = "[" + ", ".join(brief(x, width) for x in v) + "]"
        return text if len(text) <= 2 * width else text[: 2 * width] + "...]"
    if not isinstance(v, dict):
        return repr(v)
    if "$t" in v:
        return (
            "("
            + ", ".join(brief(x, width) for x in v["$t"])
            + ("," if len(v["$t"]) == 1 else "")
            + ")"
        )
    if "$b" in v:
        return repr(bytes.fromhex(v["$b"]))
    if "$nd" in v:
        a = v["$nd"]
        shape = a.get("shape") or list(np.shape(a.get("data")))
        how = f"fill={a['fill']!r}" if "fill" in a else "..."
        return f"array({a.get('dtype', 'float32')}{shape}, {how})"
    if "$grid" in v:
        return "sheet(" + ", ".join(f"{k}={x!r}" for k, x in v["$grid"].items()) + ")"
    if "$pattern" in v:
        return f"Pattern.preset({v['$pattern']!r})"
    if "$call" in v:
        return call_text(v["$call"], v.get("args", []), v.get("kwargs", {}), width)
    if "$camera" in v:
        return (
            "look_at_camera(" + ", ".join(f"{k}={brief(x)}" for k, x in v["$camera"].items()) + ")"
        )
    if "$path" in v:
        return "path(" + ", ".join(f"{k}={brief(x, 30)}" for k, x in v["$path"].items()) + ")"
    return "{" + ", ".join(f"{k!r}: {brief(x, width)}" for k, x in v.items()) + "}"


def call_text(name: str, args: list[Any], kwargs: dict[str, Any], width: int = 60) -> str:
    parts = [brief(a, width) for a in args] + [f"{k}={brief(x, width)}" for k, x in kwargs.items()]
    return f"{name}({', '.join(parts)})"


def short(case: dict[str, Any]) -> str:
    """The case as the call it makes, then its follow-up calls on the result."""
    text = call_text(case["call"], case.get("args", []), case.get("kwargs", {}))
    for then in case.get("then", []):
        args = list(then.get("args", []))
        args.insert(then.get("value_at", 0), "_")
        text += " -> " + call_text(then["call"], args, then.get("kwargs", {}))
    return text


def table(outcomes: list[Outcome], kinds: Iterable[str] = FAULTS + ("internal",)) -> str:
    rows = [o for o in outcomes if o.kind in kinds]
    rows.sort(key=lambda o: (o.kind, o.id))
    lines = [f"{'kind':<16}{'case':<13}{'s':>6}  detail / input"]
    for o in rows:
        lines.append(f"{o.kind:<16}{o.id:<13}{o.seconds:6.1f}  {o.detail[:200]}")
        lines.append(f"{'':<35}{short(o.case)}")
    return "\n".join(lines)


def write_cases(outcomes: list[Outcome], path: Path, kinds: Iterable[str] = FAULTS) -> int:
    """The failing cases, one JSON line each: ``fault_case.py @path`` replays them all."""
    rows = [o.case for o in outcomes if o.kind in kinds]
    path.write_text("".join(json.dumps(c) + "\n" for c in rows), encoding="utf-8")
    return len(rows)
