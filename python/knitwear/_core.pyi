"""Type stubs of the compiled core (``knitwear._core``). Lengths are in scene units."""

import os
from typing import Any, Self, Sequence, final

import numpy as np
import numpy.typing as npt

__version__: str
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
    "_force_internal_error",
    "cancel",
    "check_budget",
    "fractal_noise",
    "knit_texture",
    "measure_clearance",
    "measure_cover",
    "plush",
    "set_tuning_store",
    "settings",
    "tuning_store",
]

class KnitError(Exception):
    """Base class of every error a user can cause (bad surface, pattern, setting, budget)."""

class SurfaceError(KnitError):
    """The surface cannot be knitted: NaN/inf coordinates, wrong buffer shapes, no area."""

class PatternError(KnitError):
    """A stitch or colour pattern that does not parse (names the row and column)."""

class ParameterError(KnitError):
    """A setting out of range (zero gauge, negative radius, too few ring segments)."""

class BudgetError(KnitError):
    """The output would exceed the memory budget; nothing was allocated."""

class CancelledError(KnitError):
    """The call was stopped by `cancel()` before it finished; nothing it made was kept."""

class InternalError(KnitError):
    """A bug in knitwear (a caught panic). Please report it."""

@final
class GridSurface:
    """Positions and normals sampled on a regular (u,v) grid, e.g. a NURBS surface.

    ``positions[i, j]`` is s(u_j, v_i) with u_j = j/(C-1), v_i = i/(R-1): float32 (R, C, 3).
    With ``cyclic_u`` the last column wraps to the first (u_j = j/C); a duplicated seam column
    (equal to the first) is detected and dropped. Likewise for ``cyclic_v`` and rows.
    """

    def __new__(
        cls,
        positions: npt.NDArray[np.float32],
        normals: npt.NDArray[np.float32],
        cyclic_u: bool = False,
        cyclic_v: bool = False,
    ) -> Self: ...
    @property
    def extent(self) -> tuple[float, float]:
        """Mean length along u (a course) and along v (a wale), scene units."""

@final
class MeshSurface:
    """A triangle mesh with per-corner UVs; (u,v) is the UV map."""

    def __new__(
        cls,
        positions: npt.NDArray[np.float32],
        normals: npt.NDArray[np.float32],
        triangles: npt.NDArray[Any],
        uvs: npt.NDArray[np.float32],
    ) -> Self: ...
    @property
    def extent(self) -> tuple[float, float]:
        """Mean length along u (a course) and along v (a wale), scene units."""
    @property
    def domain(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """The UV map's bounding box ((u_min, v_min), (u_max, v_max)): what a knit and a
        knit texture cover."""
    @property
    def cyclic(self) -> tuple[bool, bool]:
        """Whether the UV map closes round along u and along v: a seam along the two sides
        of its bounding box whose edges are one in 3D (a tube). A closed direction is
        knitted in the round."""

@final
class Pattern:
    """A stitch pattern: a chart of stitches (knit, purl, cables, decreases, yarn-overs,
    slips, bobbles), repeated over the surface."""

    @staticmethod
    def preset(name: str) -> Pattern:
        """A built-in pattern by name; an unknown name is a PatternError listing
        `Pattern.presets()`."""
    @staticmethod
    def from_chart(text: str) -> Pattern:
        """A chart, top row first, as seen on the right side, with an optional legend
        ("X = 2/2 RC"); errors name the row, the column and the symbol."""
    @staticmethod
    def from_knitspeak(text: str) -> Pattern:
        """Knitspeak rows ("Row 1 (RS): P2, *2/2 RC, p2; rep from *."); an unknown stitch or
        an unbalanced row is a PatternError naming the row, the instruction and the token."""
    @staticmethod
    def from_text(text: str) -> Pattern:
        """Knitspeak or a chart, told apart by content."""
    @staticmethod
    def from_file(path: str | bytes | os.PathLike[str] | os.PathLike[bytes]) -> Pattern:
        """A UTF-8 file of Knitspeak or a chart; an unreadable file is a PatternError."""
    @staticmethod
    def looks_like_knitspeak(text: str) -> bool:
        """Whether `text` reads as Knitspeak rather than a chart (what `from_text` decides by)."""
    @staticmethod
    def presets() -> list[str]:
        """The names of the built-in patterns."""
    @property
    def name(self) -> str:
        """The preset's name, or what the pattern was read from."""
    @property
    def width(self) -> int:
        """Stitches in one repeat of the pattern."""
    @property
    def height(self) -> int:
        """Rows in one repeat of the pattern."""
    def chart(self) -> str:
        """The chart, top row first; k/p only for knit and purl patterns, else with a legend.
        `Pattern.from_chart` reads it back to the same stitches."""
    def stitch_counts(self) -> list[tuple[int, int]]:
        """Per row, bottom first: (loops of the row below worked, stitches made)."""

@final
class ColorPattern:
    """A palette (linear RGB, 0..1) and a chart of palette indices (digits 0-9, then a-z),
    one line per row, top line = top row, repeated over the surface."""

    def __new__(
        cls, palette: Sequence[Sequence[float]], chart: str | None = None) -> Self: ...
    @staticmethod
    def stripes(palette: Sequence[Sequence[float]], rows_each: int = 2) -> ColorPattern:
        """Stripes of the palette's colours in turn, `rows_each` rows each."""
    @staticmethod
    def preset(name: str, palette: Sequence[Sequence[float]]) -> ColorPattern:
        """A named colour chart ("fair_isle_band": 0 background, 1 pattern)."""
    @staticmethod
    def presets() -> list[str]:
        """The names of the built-in colour charts."""

@final
class KnitResult:
    """A knit's mesh and yarn, as NumPy arrays in the surface's object space (scene units)."""

    vertices: npt.NDArray[np.float32]
    """(V, 3) vertex positions, scene units, in the surface's object space"""
    triangles: npt.NDArray[np.int32]
    """(T, 3) vertex indices of each triangle"""
    edges: npt.NDArray[np.int32]
    """(E, 2), every edge of the triangles exactly once"""
    corner_edges: npt.NDArray[np.int32]
    """(3T,), edge from corner k to the next in its face"""
    colors: npt.NDArray[np.float32]
    """(V, 4) linear RGBA per vertex"""
    centerline_points: npt.NDArray[np.float32]
    """(P, 3) samples of the yarn's centreline, scene units, piece after piece"""
    course_offsets: npt.NDArray[np.int64]
    """(Y+1,), yarn piece i = points[o[i]:o[i+1]]"""
    yarn_course: npt.NDArray[np.int32]
    """(Y,), the course (row) each yarn piece belongs to"""
    yarn_closed: npt.NDArray[np.bool_]
    """(Y,), whether each piece closes on itself"""
    yarn_radius: float
    """The yarn's radius, scene units"""
    normals: npt.NDArray[np.float32]
    """(V, 3) unit shading normals: the swept tube's"""
    tangents: npt.NDArray[np.float32]
    """(V, 3) unit fibre directions: along the yarn, slanted with the plies' twist, across
    `normals` (a material's anisotropic tangent)"""
    stats: dict[str, Any]
    """Figures about the build: docs/stats.md lists every key"""

@final
class Knit:
    """A knit bound to its surface's (u,v) layout: counts, yarn radius, stitch size and
    buffer layout fixed once, so `build` and `positions` give one topology for the surface
    in any pose. Same keyword settings as `knit`."""

    def __new__(
        cls,
        surface: GridSurface | MeshSurface,
        pattern: Pattern,
        *,
        courses: int | None = None,
        wales: int | None = None,
        gauge: tuple[float, float] | None = None,
        yarn_radius: float | None = None,
        stitch_size: tuple[float, float] | None = None,
        fluffiness: float = 0.5,
        ring_segments: int = 6,
        plies: int = 1,
        live_loops: bool = False,
        samples_per_loop: int = 16,
        tension: float = 0.0,
        kappa: float = 0.0,
        seed: int = 0,
        colors: ColorPattern | None = None,
        color_image: npt.NDArray[np.float32] | None = None,
        color_variation: float = 0.15,
        threads: int | None = None,
        budget_bytes: int | None = None,
        measure_clearance: bool = False,
        camera: Camera | None = None,
        stitch_levels: npt.ArrayLike | None = None,
        detail_px: tuple[float, float, float] | None = None,
        mid_quality: tuple[int, int, bool] | None = None,
        far_quality: tuple[int, int, bool] | None = None,
        frustum_margin: float = 0.1,
        cull_back_faces: bool = False,
        cull_hidden: bool = False,
        hidden_supersampling: int = 4,
        cull_hidden_min_triangles: int = 0,
        seen_triangles: bytes | None = None,
    ) -> Self: ...
    def build(self, surface: GridSurface | MeshSurface) -> KnitResult:
        """The whole result for `surface` (the one knitted, or it deformed)."""
    def crossing_order(self, surface: GridSurface | MeshSurface) -> tuple[int, int, int]:
        """(decided, agree, undecided) crossings of the yarn on `surface`: at `agree` of the
        `decided` ones the yarn in front is the one the stitch pattern says."""
    def clearance(self, surface: GridSurface | MeshSurface) -> tuple[float, float]:
        """(min, 1st percentile) centreline clearance in yarn diameters of the knit's yarn on
        `surface` (the knitted one, or it deformed): what `build(surface)` measures with
        `measure_clearance`, without building the mesh. At 1 neighbouring yarns touch."""
    def positions(
        self,
        surface: GridSurface | MeshSurface,
        out: npt.NDArray[np.float32] | None = None,
        normals_out: npt.NDArray[np.float32] | None = None,
        tangents_out: npt.NDArray[np.float32] | None = None,
    ) -> npt.NDArray[np.float32]:
        """(V, 3) float32 positions for `surface` in a new pose, bit-identical to
        `build(surface).vertices`; written into `out` when given. With `normals_out` and
        `tangents_out`, the shading normals (see `normals`) and the fibre directions (see
        `KnitResult.tangents`) are written there in the same pass."""
    def normals(
        self,
        surface: GridSurface | MeshSurface,
        out: npt.NDArray[np.float32] | None = None,
    ) -> npt.NDArray[np.float32]:
        """(V, 3) float32 unit shading normals for `surface` in a new pose (the swept
        tube's, out from the yarn's centreline), bit-identical to `build(surface).normals`."""
    @property
    def vertex_count(self) -> int:
        """Vertices of every build and of `positions` (fixed when the knit is bound)."""
    @property
    def triangle_count(self) -> int:
        """Triangles of every build (fixed when the knit is bound): a caller can make room
        for the mesh while the core builds it."""
    @property
    def yarn_radius(self) -> float:
        """The yarn radius bound at knit time, scene units (pin it with `yarn_radius=` to
        rebuild)."""
    @property
    def counts(self) -> tuple[int, int]:
        """(courses, wales)."""
    @property
    def stitch_size(self) -> tuple[float, float]:
        """(width, height) of a stitch the loop shapes are tuned for, scene units."""
    @property
    def topology_key(self) -> int:
        """A key of the mesh topology: equal keys mean identical triangles and edges."""
    @property
    def seen_triangles(self) -> bytes | None:
        """With ``cull_hidden``: one bit per triangle before culling (triangle i at bit i % 8
        of byte i // 8), whether it is kept; pass back as ``seen_triangles``."""
    @property
    def stitch_levels(self) -> npt.NDArray[np.uint8] | None:
        """With a camera, (courses, wales): 0 full, 1 mid, 2 far, 3 texture, 4 culled (or no
        surface under the stitch). None without a camera."""

@final
class Camera:
    """Camera views of a surface for camera-driven detail. ``matrices``: (4, 4) or (F, 4, 4)
    clip-from-object (``projection @ view @ world_from_object``, OpenGL clip conventions,
    row-major); ``eyes``: (4,) or (F, 4), the eye in the surface's object space, ``(x, y, z,
    1)`` for a perspective camera, ``(dx, dy, dz, 0)`` towards an orthographic one;
    ``resolution``: (width, height) pixels. Several views (an animated camera's frames) model
    each stitch for the view that sees it largest. ``poses``: the surface as each view sees
    it, one per view (a deforming source sampled at each view's frame, with the knit's UV
    layout), so that a part that moves into the frame or up to the camera during the
    animation is built for the frame that sees it best; without them every view sees the
    knit's own surface. With ``cull_hidden`` each view keeps the yarn it sees in its own
    pose (the knit is built once per pose to find it)."""

    def __new__(
        cls,
        matrices: npt.ArrayLike,
        eyes: npt.ArrayLike,
        resolution: tuple[int, int],
        poses: Sequence[GridSurface | MeshSurface] | None = None,
    ) -> Self: ...
    @property
    def views(self) -> int:
        """How many views (an animation's frames) the camera holds."""
    @property
    def posed(self) -> bool:
        """Whether each view sees a pose of its own (``poses`` given)."""
    @property
    def resolution(self) -> tuple[int, int]:
        """(width, height) in pixels."""

def knit_texture(
    surface: GridSurface | MeshSurface,
    pattern: Pattern,
    *,
    width: int = 1024,
    height: int = 1024,
    courses: int | None = None,
    wales: int | None = None,
    gauge: tuple[float, float] | None = None,
    yarn_radius: float | None = None,
    stitch_size: tuple[float, float] | None = None,
    fluffiness: float = 0.5,
    ring_segments: int = 6,
    plies: int = 1,
    live_loops: bool = False,
    samples_per_loop: int = 16,
    tension: float = 0.0,
    kappa: float = 0.0,
    seed: int = 0,
    colors: ColorPattern | None = None,
    color_image: npt.NDArray[np.float32] | None = None,
    color_variation: float = 0.15,
    threads: int | None = None,
    budget_bytes: int | None = None,
    measure_clearance: bool = False,
) -> npt.NDArray[np.float32]:
    """The knitwear texture: (height, width, 4) float32 linear RGBA of the knit drawn over
    the surface's (u,v) domain (a grid's [0, 1]^2, a mesh's `domain`), row 0 at the smallest
    v, transparent where no yarn is. Same stitches, perturbation and colours as `Knit` with
    the same settings."""

def set_tuning_store(path: str | os.PathLike[str] | None) -> None:
    """Keeps tunings in `path` (None: on no disk), for this process, overriding the
    KNITWEAR_TUNING_STORE environment variable."""

def tuning_store() -> str | None:
    """The folder tunings are kept in, or None."""

def settings(kind: str = "knit") -> list[dict[str, Any]]:
    """Every setting of a knit or a plush (``kind``) as declared once in the core: name,
    core_keyword, part_of, property, label, type, default, addon_default, addon_why, min,
    max, unit, doc."""
    ...

def measure_clearance(result: KnitResult) -> tuple[float, float]:
    """(min, 1st percentile) centreline clearance in yarn diameters."""

def measure_cover(
    result: KnitResult,
    bounds: tuple[float, float, float, float],
    resolution: int = 800,
) -> float:
    """Fraction of the rectangle (x_min, y_min, x_max, y_max) of object space hidden by the
    yarn's tubes (no fluff) seen orthographically along z."""

# Plush (warp-knit pile). Lengths in scene units, angles in radians; positions, `eye` and
# `view_dir` in the surface's object space. The fabric frame: x along the course (u), y along
# the wale (v), z the surface normal.

@final
class PlushView:
    """The view-dependent buffers of a plush for one view (topology, UVs and colours are
    the `PlushResult`'s and never change with the view)."""

    vertices: npt.NDArray[np.float32]
    """(V, 3) vertex positions for this view, scene units"""
    mask: npt.NDArray[np.float32]
    """(V,) 0 round mask (horizontal slice), 1 rectangle"""
    horizontal: npt.NDArray[np.uint8]
    """(P,) 1 where the pile has horizontal slices"""
    stats: dict[str, Any]
    """`horizontal`, `vertical` (piles of each kind) and `seconds`"""

@final
class PlushField:
    """Pile roots, frames, directions and colours sampled once; re-viewed cheaply."""

    def view(
        self,
        *,
        eye: Sequence[float] | None = None,
        view_dir: Sequence[float] | None = None,
        threads: int | None = None,
    ) -> PlushView:
        """Slice choice and positions for a new view: no surface sampling, no noise."""
    def build(
        self,
        *,
        eye: Sequence[float] | None = None,
        view_dir: Sequence[float] | None = None,
        threads: int | None = None,
        budget_bytes: int | None = None,
    ) -> PlushResult:
        """Every buffer for a view, as `plush()` returns them."""
    @property
    def piles(self) -> int:
        """Piles built."""
    @property
    def slices(self) -> int:
        """Quads per pile."""
    @property
    def pile_length(self) -> float:
        """Pile length, scene units."""
    @property
    def pile_radius(self) -> float:
        """Half width of a slice, scene units."""
    @property
    def stats(self) -> dict[str, Any]:
        """Figures about the sampling: docs/stats.md (Plush) lists the keys."""
    @property
    def roots(self) -> npt.NDArray[np.float32]:
        """(P, 3) pile roots."""
    @property
    def directions(self) -> npt.NDArray[np.float32]:
        """(P, 3) unit pile directions."""
    @property
    def normals(self) -> npt.NDArray[np.float32]:
        """(P, 3) unit surface normals at the roots."""
    @property
    def blends(self) -> npt.NDArray[np.float32]:
        """(P,) each pile's place in [0, 1) across the band where slices change kind."""
    @property
    def root_uvs(self) -> npt.NDArray[np.float32]:
        """(P, 2) (u,v) of the roots."""
    @property
    def noise(self) -> npt.NDArray[np.float32]:
        """(H, W, 3) fractal noise unit vectors in the noise frame (z = nominal direction)."""
    @property
    def noise_rgb(self) -> npt.NDArray[np.float32]:
        """(H, W, 3) the noise as the paper's image, (v + 1) / 2 in [0, 1]."""

@final
class PlushResult:
    """A plush's mesh, as NumPy arrays in the surface's object space (scene units)."""

    vertices: npt.NDArray[np.float32]
    """(V, 3), V = 4 * slices * piles"""
    triangles: npt.NDArray[np.int32]
    """(T, 3), two per slice quad"""
    edges: npt.NDArray[np.int32]
    """(E, 2), five per quad, every edge once"""
    corner_edges: npt.NDArray[np.int32]
    """(3T,), edge from corner k to the next in its face"""
    colors: npt.NDArray[np.float32]
    """(V, 4) linear RGBA, darker at the root"""
    uvs: npt.NDArray[np.float32]
    """(V, 2), each quad (0,0), (1,0), (1,1), (0,1)"""
    mask: npt.NDArray[np.float32]
    """(V,) 0 round mask (horizontal slice), 1 rectangle"""
    horizontal: npt.NDArray[np.uint8]
    """(P,) 1 where the pile has horizontal slices"""
    stats: dict[str, Any]
    """Figures about the build: docs/stats.md lists every key"""
    field: PlushField
    """The sampled piles, to view again or rebuild without resampling"""

def plush(
    surface: GridSurface | MeshSurface,
    *,
    courses: int | None = None,
    wales: int | None = None,
    gauge: tuple[float, float] | None = None,
    piles_per_stitch: int = 1,
    pile_length: float | None = None,
    pile_radius: float | None = None,
    slices: int = 8,
    lean: Sequence[float] | None = None,
    theta_max: float | None = None,
    noise_scales: Sequence[int] | None = None,
    noise_size: tuple[int, int] | None = None,
    seed: int = 0,
    eye: Sequence[float] | None = None,
    view_dir: Sequence[float] | None = None,
    colors: ColorPattern | Sequence[float] | npt.NDArray[np.float32] | None = None,
    color_image: npt.NDArray[np.float32] | None = None,
    press: npt.NDArray[np.float32] | None = None,
    press_strength: float | None = None,
    press_direction: float | None = None,
    threads: int | None = None,
    budget_bytes: int | None = None,
) -> PlushResult:
    """Warp-knit plush over `surface`: fractal-noise pile directions, and per pile
    horizontal or vertical slices for the view (docs/plush.md; every setting: docs/settings.md)."""

def fractal_noise(
    size: int | tuple[int, int],
    *,
    theta_max: float | None = None,
    scales: Sequence[int] | None = None,
    seed: int = 0,
    rgb: bool = False,
    threads: int | None = None,
) -> npt.NDArray[np.float32]:
    """(height, width, 3) float32 fractal noise unit vectors (or with rgb=True the image
    (v + 1) / 2); size is an int or (width, height); scales=(1,) gives the base noise."""

def cancel() -> None:
    """Stops every knitwear call now running, from any thread (the add-on's Esc): each raises
    `CancelledError` within a fraction of a second. Ctrl-C in the calling thread stops a
    call the same way and raises `KeyboardInterrupt`."""

def check_budget(
    pattern: Pattern,
    courses: int,
    wales: int,
    *,
    ring_segments: int = 6,
    samples_per_loop: int = 16,
    budget_bytes: int | None = None,
) -> int:
    """Whether a knit of ``courses x wales`` stitches of ``pattern`` fits the memory budget,
    as `Knit` checks it first: the output's upper bound in bytes, or `BudgetError`. Cheap (no
    surface): refuses an absurd count before a surface is sampled densely for it."""

def _force_internal_error() -> None:
    """Raises InternalError from a deliberate panic in the core (a test hook: no Rust panic
    crosses into Python)."""
    ...
