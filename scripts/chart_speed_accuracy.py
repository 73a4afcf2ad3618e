"""The speed-accuracy chart (issue 7): sweep every quality knob of a knit over one fixed scene
and camera, measure time and error, and chart error against time with the defaults marked.

    .venv/bin/python scripts/chart_speed_accuracy.py [--zip dist/knitwear-0.1.0.zip]
        [--out docs/charts] [--quick] [--repeats 1] [--replot]

Runs headless Blender (the `bpy` module) with the built extension installed, as the benchmarks
do (`benchmarks/bench_setup.py`). The scene: a 20 x 120 cm knitted strip (40 wales x 336
courses, 13,440 stitches) lying flat and receding from a low camera (35 mm lens, 960 x 540),
so it fills the lower part of the frame and runs into the distance. The source wears the
knitwear texture in every render, as auto detail leaves it.

Knobs swept (each from the defaults, one at a time): samples per loop (6..24) and ring segments
(3..8) at uniform full detail, fluff off, another seed, and auto detail with its three pixel
thresholds scaled together (x0, every stitch in view full, .. x2), culling the hidden yarn
(the add-on's default, one visibility sample per rendered pixel), with the hidden yarn kept,
and with the texture level off. For each point:

- time: seconds in the core (`Knit` + `build`, `KnitOutcome.core_seconds`) and click-to-mesh
  (`api.knit`: sampling, core, Blender mesh, and the knitwear texture where stitches are
  left to it);
- tessellation error in pixels: per stitch, the larger of the chord error of its centreline
  (against the same spline sampled 96 times per stitch) and the ring's flat-facet error
  `r (1 - cos(pi / m))`, at the stitch's samples and segments for its level, times the stitch's
  pixels per scene unit; a texture-level stitch counts its flattened relief, three yarn radii;
  the 99th percentile over the stitches in view;
- image error: SSIM and PSNR of an EEVEE render (luminance) against the render at the highest
  quality swept (uniform full detail, 24 samples per loop, 8 ring segments), and against
  uniform full detail at the defaults (the issue's target). Renders are anti-aliased by 4 x 4
  supersampling (`SUPERSAMPLE`: rendered at 3840 x 2160, one sample, box-filtered in linear
  light to 960 x 540), so sub-pixel fibres average out as in a many-sample render;
- the noise floor: full detail with another seed, which is as far from full detail as two
  equally good knits are; each setting's 1 - SSIM is also printed as a fraction of the
  floor's.

Writes docs/charts/speed_accuracy_ssim.png (image error against click-to-mesh time),
speed_accuracy_target.png (SSIM against full detail against triangles: the issue's target),
speed_accuracy_tessellation.png (tessellation error against triangles),
speed_accuracy_renders.png (the reference, auto detail, and their difference) and
speed_accuracy.json (the figures), and prints a table. `--replot` redraws the three scatter
charts from the JSON in seconds, without Blender. Timings are medians of `--repeats` knits.
`pile slices per pile` is a knob of the plush (`knitwear.plush`), not of a knit; it is not
swept here.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import tempfile
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image, ImageDraw, ImageFont

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from bench_setup import median_seconds, start_blender  # noqa: E402

Record = dict[str, Any]

#: The scene: a strip of COURSES x WALES stitches, WIDTH x LENGTH metres.
WIDTH, LENGTH = 0.2, 1.2
COURSES, WALES = 336, 40
RES = (960, 540)
#: Anti-aliasing: each image pixel is the linear-light mean of SUPERSAMPLE x SUPERSAMPLE
#: rendered pixels (one EEVEE sample each), so sub-pixel fibres average out as they do in a
#: many-sample render; the detail thresholds are given in image pixels.
SUPERSAMPLE = 4
#: Dense samples per stitch of the spline the tessellation error is measured against.
DENSE = 96
#: The defaults (the operator's): what the charts mark.
DEFAULTS = {"samples_per_loop": 16, "ring_segments": 6, "fluffiness": 0.5,
            "detail_full_px": 12.0, "detail_mid_px": 5.0, "detail_texture_px": 1.0}
REFERENCE = {"detail_mode": "FULL", "samples_per_loop": 24, "ring_segments": 8}
FLOOR = "full detail, another seed"


# ---------------------------------------------------------------------------------------------
# Scene


def build_scene(quick: bool) -> tuple[Any, Any]:
    """The strip (a UV-mapped plane) and the scene camera; lights and EEVEE settings."""
    import bpy
    from mathutils import Vector

    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, LENGTH / 2, 0.0))
    strip = bpy.context.active_object
    strip.name = "Strip"
    strip.scale = (WIDTH, LENGTH, 1.0)
    cam_data = bpy.data.cameras.new("Camera")
    cam_data.lens = 35.0
    cam = bpy.data.objects.new("Camera", cam_data)
    scene.collection.objects.link(cam)
    cam.location = (0.03, -0.03, 0.05)
    cam.rotation_euler = (Vector((0.0, 0.32, 0.0)) - cam.location).to_track_quat(
        "-Z", "Y").to_euler()
    scene.camera = cam
    sun_data = bpy.data.lights.new("Sun", "SUN")
    sun_data.energy = 3.0
    sun = bpy.data.objects.new("Sun", sun_data)
    sun.rotation_euler = (math.radians(40), math.radians(10), math.radians(30))
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("World")
    world.color = (0.05, 0.05, 0.06)
    scene.world = world
    r = scene.render
    r.resolution_x, r.resolution_y = (RES[0] // 2, RES[1] // 2) if quick else RES
    r.resolution_percentage = 100 * SUPERSAMPLE
    try:
        r.engine = "BLENDER_EEVEE"  # Blender 5
    except TypeError:
        r.engine = "BLENDER_EEVEE_NEXT"  # Blender 4.2 to 4.5
    # Software GL redraws every triangle per sample; one sample at 4 x 4 the pixels is the
    # cheaper way to 16 samples per image pixel (about 50 s a full-detail render here).
    scene.eevee.taa_render_samples = 1
    scene.view_settings.view_transform = "Standard"
    r.image_settings.file_format = "PNG"
    bpy.context.view_layer.update()
    return strip, cam


def render(path: Path) -> np.ndarray:
    """Renders the scene, box-filters it down by SUPERSAMPLE in linear light and writes the
    result to ``path``; returns its luminance, (H, W) float in [0, 1]."""
    import bpy

    bpy.context.scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    rgb = np.asarray(Image.open(path).convert("RGB"), dtype=np.float64) / 255.0
    lin = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
    k = SUPERSAMPLE
    h, w = lin.shape[0] // k, lin.shape[1] // k
    lin = lin[:h * k, :w * k].reshape(h, k, w, k, 3).mean(axis=(1, 3))
    srgb = np.where(lin <= 0.0031308, lin * 12.92, 1.055 * lin ** (1 / 2.4) - 0.055)
    Image.fromarray(np.clip(srgb * 255 + 0.5, 0, 255).astype(np.uint8)).save(path)
    return srgb @ np.array([0.2126, 0.7152, 0.0722])


# ---------------------------------------------------------------------------------------------
# Image error


def _blur(img: np.ndarray, sigma: float = 1.5) -> np.ndarray:
    """Separable Gaussian blur, 11 taps (the SSIM paper's window), edges reflected."""
    x = np.arange(-5, 6)
    k = np.exp(-(x**2) / (2 * sigma**2))
    k /= k.sum()
    pad = np.pad(img, 5, mode="reflect")
    rows = sum(k[i] * pad[:, i:i + img.shape[1]] for i in range(11))
    return sum(k[i] * rows[i:i + img.shape[0], :] for i in range(11))


def ssim(a: np.ndarray, b: np.ndarray) -> float:
    """Mean SSIM of two luminance images in [0, 1] (Wang et al. 2004: Gaussian window of
    sigma 1.5, K1 = 0.01, K2 = 0.03)."""
    c1, c2 = 0.01**2, 0.03**2
    mu_a, mu_b = _blur(a), _blur(b)
    saa = _blur(a * a) - mu_a**2
    sbb = _blur(b * b) - mu_b**2
    sab = _blur(a * b) - mu_a * mu_b
    s = ((2 * mu_a * mu_b + c1) * (2 * sab + c2)) / ((mu_a**2 + mu_b**2 + c1) * (saa + sbb + c2))
    return float(s.mean())


def psnr(a: np.ndarray, b: np.ndarray) -> float:
    mse = float(np.mean((a - b) ** 2))
    return float("inf") if mse == 0 else 10 * math.log10(1.0 / mse)


# ---------------------------------------------------------------------------------------------
# Tessellation error


def level_quality(level: int, s: int, m: int) -> tuple[int, int]:
    """Samples per loop and ring segments of a level (as the core's defaults choose them)."""
    if level == 0:
        return s, m
    if level == 1:
        return min(s, max(6, s // 2)), min(m, max(3, -(-2 * m // 3)))
    return min(s, 6), min(m, 3)


class Tessellation:
    """Per-stitch chord errors of the strip's centrelines at any samples per loop, and each
    stitch's pixels per scene unit, from one dense knit."""

    def __init__(self, api: Any, strip: Any, cam: Any) -> None:
        import bpy

        dense = api.knit_result(strip, **base_settings(), detail_mode="FULL",
                                samples_per_loop=DENSE)
        self.radius = dense.yarn_radius
        pts = dense.centerline_points.astype(np.float64)
        offsets = dense.course_offsets
        courses = dense.yarn_course
        self.pieces = [(int(c), pts[offsets[i]:offsets[i + 1]]) for i, c in enumerate(courses)]
        self._chord: dict[int, np.ndarray] = {}
        # Pixels per scene unit at each stitch's centre (knit object space = the strip's
        # location and rotation).
        scene = bpy.context.scene
        depsgraph = bpy.context.evaluated_depsgraph_get()
        r = scene.render
        x, y = r.resolution_x, r.resolution_y
        proj = np.array(cam.calc_matrix_camera(depsgraph, x=x, y=y))
        loc, rot, _ = strip.matrix_world.decompose()
        from mathutils import Matrix

        view = np.array(cam.matrix_world.inverted() @ Matrix.LocRotScale(loc, rot, None))
        centres = np.zeros((COURSES, WALES, 3))
        for course, p in self.pieces:
            n = min(WALES, (len(p) + DENSE - 1) // DENSE)
            for j in range(n):
                centres[course, j] = p[j * DENSE:(j + 1) * DENSE].mean(axis=0)
        hom = np.concatenate([centres, np.ones((COURSES, WALES, 1))], axis=-1)
        cs = hom @ view.T
        clip = cs @ proj.T
        depth = np.maximum(-cs[..., 2], 1e-6)
        self.ppu = proj[1, 1] * y / 2 / depth
        ndc = clip[..., :2] / np.maximum(clip[..., 3:4], 1e-9)
        self.in_view = (np.abs(ndc) <= 1.0).all(axis=-1) & (cs[..., 2] < 0)

    def chord(self, s: int) -> np.ndarray:
        """(COURSES, WALES) largest distance, scene units, between the dense spline and its
        polyline through `s` samples per stitch."""
        if s in self._chord:
            return self._chord[s]
        err = np.zeros((COURSES, WALES))
        idx = np.round(np.arange(s + 1) * DENSE / s).astype(int)  # chosen dense samples
        for course, p in self.pieces:
            n = len(p)
            for j in range(WALES):
                base = j * DENSE
                keep = base + idx
                keep = keep[keep < n]
                if len(keep) < 2:
                    continue
                worst = 0.0
                for a, b in zip(keep[:-1], keep[1:], strict=True):
                    seg = p[a:b + 1]
                    d = p[b] - p[a]
                    t = np.clip(((seg - p[a]) @ d) / max(d @ d, 1e-30), 0, 1)
                    dist = np.linalg.norm(seg - (p[a] + t[:, None] * d), axis=1)
                    worst = max(worst, float(dist.max()))
                err[course, j] = worst
        self._chord[s] = err
        return err

    def error_px(self, levels: np.ndarray, s: int, m: int) -> float:
        """99th percentile over the stitches in view of the tessellation error, pixels."""
        err = np.zeros((COURSES, WALES))
        for level in (0, 1, 2):
            sl, ml = level_quality(level, s, m)
            tube = self.radius * (1 - math.cos(math.pi / ml))
            e = np.maximum(self.chord(sl), tube)
            err = np.where(levels == level, e, err)
        err = np.where(levels == 3, 3 * self.radius, err)
        px = (err * self.ppu)[self.in_view & (levels <= 3)]
        return float(np.percentile(px, 99)) if px.size else 0.0


# ---------------------------------------------------------------------------------------------
# Sweep


def base_settings() -> dict[str, Any]:
    return {"size_mode": "COUNTS", "courses": COURSES, "wales": WALES, "seed": 1,
            "color_mode": "STRIPES", "color_count": 2, "stripe_height": 6}


def sweep_points(quick: bool) -> list[tuple[str, str, dict[str, Any]]]:
    """(series, label, settings) of every point; the settings override the defaults."""
    pts: list[tuple[str, str, dict[str, Any]]] = [("reference", "reference", REFERENCE)]
    full = {"detail_mode": "FULL"}
    for s in ([6, 16] if quick else [6, 8, 12, 16]):
        pts.append(("samples per loop (full detail)", f"{s}", full | {"samples_per_loop": s}))
    for m in ([3, 6] if quick else [3, 4, 6, 8]):
        if m != 6:
            pts.append(("ring segments (full detail)", f"{m}", full | {"ring_segments": m}))
    pts.append(("fluff off (full detail)", "no fluff", full | {"fluffiness": 0.0}))
    # The noise floor: the same knit with another seed, as different as two equally good
    # renders of it can be.
    pts.append((FLOOR, "seed 2", full | {"seed": 2}))

    def auto(k: float) -> dict[str, Any]:
        # The strip is under the add-on's Cull From, where the pass is skipped; the chart
        # measures what culling does, so it always runs here.
        return {"detail_mode": "AUTO", "detail_full_px": 12.0 * k, "detail_mid_px": 5.0 * k,
                "detail_texture_px": 1.0 * k, "cull_hidden_min_triangles": 0}

    # Auto detail culls the hidden yarn (the add-on's default); x0: every stitch in view at
    # full detail, only the hidden yarn culled.
    for k in ([0.5, 1.0] if quick else [0.0, 0.5, 1.0, 2.0, 4.0]):
        pts.append(("auto detail, thresholds x k", f"x{k:g}", auto(k)))
    for k in ([1.0] if quick else [1.0, 2.0]):
        pts.append(("auto detail, hidden yarn kept", f"x{k:g} all",
                    auto(k) | {"cull_hidden": False}))
    pts.append(("auto detail, no texture level", "no texture",
                {"detail_mode": "AUTO", "detail_texture_px": 0.0,
                 "cull_hidden_min_triangles": 0}))
    return pts


def measure(api: Any, strip: Any, tess: Tessellation, settings: dict[str, Any], out: Path,
            name: str, repeats: int) -> tuple[Record, np.ndarray]:
    import bpy

    merged = base_settings() | DEFAULTS | settings

    outcomes: list[Any] = []

    # The thresholds are image pixels; the render the add-on sizes them by is SUPERSAMPLE
    # times larger.
    knit_settings = merged | {k: merged[k] * SUPERSAMPLE for k in (
        "detail_full_px", "detail_mid_px", "detail_texture_px")}
    # The render is already SUPERSAMPLE times the image: one visibility sample per rendered
    # pixel (its centre, where the one-sample render looks) is 16 per image pixel.
    knit_settings.setdefault("cull_hidden_samples", 1)

    def run() -> None:
        if outcomes:
            _remove(outcomes[-1].object)
        outcomes.append(api.knit(strip, **knit_settings))

    seconds = median_seconds(run, repeats)
    outcome = outcomes[-1]
    core = float(np.median([o.core_seconds for o in outcomes]))
    raw = api.bound_of(outcome.object).levels
    levels = (np.zeros((COURSES, WALES), np.uint8) if raw is None
              else np.frombuffer(raw, np.uint8).reshape(COURSES, WALES))
    image = render(out / f"{name}.png")
    _remove(outcome.object)
    bpy.context.view_layer.update()
    rec = {
        "click": seconds, "core": core, "triangles": outcome.triangles,
        "full_triangles": outcome.triangles_full_detail, "levels": outcome.levels,
        "tess_px": tess.error_px(levels, merged["samples_per_loop"], merged["ring_segments"]),
    }
    return rec, image


def _remove(obj: Any) -> None:
    import bpy

    mesh = obj.data
    bpy.data.objects.remove(obj)
    if mesh.users == 0:
        bpy.data.meshes.remove(mesh)


# ---------------------------------------------------------------------------------------------
# Flicker

#: Frames of the camera move the flicker is measured over, and the dolly per frame (metres,
#: along the strip).
FLICKER_FRAMES = 3
FLICKER_STEP = 0.01


def flicker(api: Any, strip: Any, cam: Any, out: Path) -> None:
    """Flicker over a short dolly of the camera along the strip: each knit's frame-to-frame
    change of the image, against full detail's (what the motion itself changes). Printed as
    the mean absolute luminance difference, per frame pair, between the two changes. Auto
    detail as the add-on knits an animation (levels from every frame, pinned) and, to show
    what pinning buys, knitted again at every frame from that frame's view alone."""
    import bpy
    from mathutils import Vector

    scene = bpy.context.scene
    start = cam.location.copy()
    for f in range(1, FLICKER_FRAMES + 1):
        cam.location = start + Vector((0.0, (f - 1) * FLICKER_STEP, 0.0))
        cam.keyframe_insert("location", frame=f)
    scene.frame_start, scene.frame_end = 1, FLICKER_FRAMES
    full = base_settings() | DEFAULTS | {"detail_mode": "FULL"}
    auto = base_settings() | DEFAULTS | {"detail_mode": "AUTO"}
    auto |= {k: auto[k] * SUPERSAMPLE for k in
             ("detail_full_px", "detail_mid_px", "detail_texture_px")}
    auto["cull_hidden_samples"] = 1  # as `measure`: the render is already supersampled

    def frames(name: str, settings: dict[str, Any], per_frame: bool) -> list[np.ndarray]:
        images, obj, levels = [], None, []
        for f in range(1, FLICKER_FRAMES + 1):
            scene.frame_set(f)
            if per_frame or obj is None:
                if obj is not None:
                    _remove(obj)
                if per_frame:  # this frame's view only
                    scene.frame_start = scene.frame_end = f
                outcome = api.knit(strip, **settings)
                scene.frame_start, scene.frame_end = 1, FLICKER_FRAMES
                obj = outcome.object
                levels.append(outcome.levels)
            images.append(render(out / f"flicker_{name}_{f}.png"))
        _remove(obj)
        if per_frame:
            print(f"  {name}: levels per frame {levels}")
        return images

    ref = frames("full", full, False)
    motion = np.mean([np.abs(b - a).mean() for a, b in zip(ref[:-1], ref[1:], strict=True)])
    print(f"\nflicker over a {FLICKER_FRAMES}-frame dolly of {FLICKER_STEP * 100:g} cm a frame "
          f"(full detail's own frame-to-frame change: {motion:.4f}):")
    for name, settings, per_frame in (("auto, pinned", auto, False),
                                      ("auto, re-knit every frame", auto, True)):
        imgs = frames(name.replace(" ", "_").replace(",", ""), settings, per_frame)
        d = [np.abs((b - a) - (rb - ra)).mean()
             for a, b, ra, rb in zip(imgs[:-1], imgs[1:], ref[:-1], ref[1:], strict=True)]
        print(f"  {name:28s} flicker {np.mean(d):.4f} ({np.mean(d) / motion:.2f} of the "
              f"motion's change) per pair {[round(float(x), 4) for x in d]}")
    cam.animation_data_clear()
    cam.location = start
    scene.frame_set(1)


# ---------------------------------------------------------------------------------------------
# Charts (Pillow, as chart_breakage.py: CI needs no matplotlib)

WHITE, INK, GRID, GREY = (255, 255, 255), (30, 30, 30), (225, 225, 225), (120, 120, 120)
COLORS = {
    "samples per loop (full detail)": (40, 100, 200),
    "ring segments (full detail)": (230, 130, 20),
    "fluff off (full detail)": (140, 60, 170),
    FLOOR: (120, 120, 120),
    "auto detail, thresholds x k": (30, 150, 70),
    "auto detail, no texture level": (200, 40, 40),
    "auto detail, hidden yarn kept": (170, 170, 60),
    "reference": (0, 0, 0),
}


def font(size: int) -> ImageFont.FreeTypeFont | ImageFont.ImageFont:
    return ImageFont.load_default(size=size)


def _axis(lo: float, hi: float, p0: float, p1: float, log: bool) -> Any:
    f = math.log10 if log else float

    def at(v: float) -> float:
        return p0 + (f(v) - f(lo)) / (f(hi) - f(lo)) * (p1 - p0)

    return at


def _ticks(lo: float, hi: float, log: bool) -> list[float]:
    if log:
        cand = [m * 10.0**e for e in range(math.floor(math.log10(lo)),
                                           math.ceil(math.log10(hi)) + 1) for m in (1, 2, 5)]
    else:
        step = (hi - lo) / 5
        mag = 10 ** math.floor(math.log10(step))
        step = min(m * mag for m in (1, 2, 5, 10) if m * mag >= step)
        start = math.ceil(lo / step) * step
        cand = [start + i * step for i in range(int((hi - start) / step) + 1)]
    return [c for c in cand if lo <= c <= hi]


def _tick_label(v: float) -> str:
    """Tick text: 100k, 2M rather than 100000, 2e+06."""
    if abs(v) >= 1e6:
        return f"{v / 1e6:g}M"
    if abs(v) >= 1e4:
        return f"{v / 1e3:g}k"
    return f"{v:g}"


Box = tuple[float, float, float, float]


def _overlap(a: Box, b: Box) -> float:
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    return w * h if w > 0 and h > 0 else 0.0


def place_labels(d: ImageDraw.ImageDraw, labels: list[tuple[float, float, str, int]],
                 obstacles: list[Box], frame: Box) -> list[tuple[float, float, str]]:
    """Greedy label placement: each label (anchor x, y, text, font size), in the order given,
    takes the first of sixteen spots around its point (eight directions, near then far) that
    overlaps no placed label, marker or line, and otherwise the spot that overlaps least.
    Returns the top-left corner of each label's text box, in order."""
    placed: list[Box] = []
    out = []
    for x, y, text, size in labels:
        x0, y0, x1, y1 = d.textbbox((0, 0), text, font=font(size))
        w, h = x1 - x0, y1 - y0
        best: tuple[float, Box] | None = None
        for gap in (7.0, 16.0):
            for dx, dy in ((1, -1), (1, 0), (1, 1), (0, -1), (0, 1), (-1, -1), (-1, 0),
                           (-1, 1)):
                bx = x + gap * dx if dx > 0 else x - gap * -dx - w if dx < 0 else x - w / 2
                by = y + gap * dy if dy > 0 else y - gap * -dy - h if dy < 0 else y - h / 2
                box = (bx, by, bx + w, by + h)
                cost = sum(_overlap(box, o) for o in placed) * 4
                cost += sum(_overlap(box, o) for o in obstacles)
                inside = _overlap(box, frame)
                cost += (w * h - inside) * 8 + gap * 0.01
                if best is None or cost < best[0]:
                    best = (cost, box)
                if cost < 0.5:
                    break
            if best is not None and best[0] < 0.5:
                break
        assert best is not None
        box = best[1]
        placed.append(box)
        out.append((box[0] - x0, box[1] - y0, text))
    return out


def _wrap(d: ImageDraw.ImageDraw, text: str, size: int, width: float) -> list[str]:
    lines: list[str] = []
    for word in text.split(" "):
        if lines and d.textlength(lines[-1] + " " + word, font=font(size)) <= width:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return lines


def scatter_chart(path: Path, title: str, points: list[tuple[str, str, float, float, bool]],
                  xlabel: str, ylabel: str, log_x: bool, log_y: bool, note: str) -> None:
    """``points``: (series, label, x, y, is_default). Each series is a line through its
    points in the order given; the default is ringed. The legend stands to the right of the
    plot, and points that fall on one pixel share one label."""
    w, h, left, right, top, bottom = 1200, 620, 90, 300, 56, 520
    img = Image.new("RGB", (w, h), WHITE)
    d = ImageDraw.Draw(img)
    xs = [p[2] for p in points]
    ys = [p[3] for p in points]
    def pad(lo: float, hi: float, log: bool) -> tuple[float, float]:
        if log:
            return lo / 1.4, hi * 1.4
        return lo - 0.08 * (hi - lo + 1e-9), hi + 0.08 * (hi - lo + 1e-9)

    xlo, xhi = pad(min(xs), max(xs), log_x)
    ylo, yhi = pad(min(ys), max(ys), log_y)
    x1 = w - right
    ax = _axis(xlo, xhi, left, x1, log_x)
    ay = _axis(ylo, yhi, bottom, top, log_y)
    d.text(((left + x1) / 2, 16), title, fill=INK, font=font(19), anchor="mt")
    for t in _ticks(ylo, yhi, log_y):
        d.line([(left, ay(t)), (x1, ay(t))], fill=GRID)
        d.text((left - 6, ay(t)), _tick_label(t), fill=INK, font=font(13), anchor="rm")
    for t in _ticks(xlo, xhi, log_x):
        d.line([(ax(t), top), (ax(t), bottom)], fill=GRID)
        d.text((ax(t), bottom + 6), _tick_label(t), fill=INK, font=font(13), anchor="mt")
    d.rectangle([left, top, x1, bottom], outline=INK)
    d.text(((left + x1) / 2, bottom + 28), xlabel, fill=INK, font=font(15), anchor="mt")
    lab = Image.new("RGBA", (420, 22), (255, 255, 255, 0))
    ImageDraw.Draw(lab).text((210, 11), ylabel, fill=INK, font=font(15), anchor="mm")
    rot = lab.rotate(90, expand=True)
    img.paste(rot, (8, int((top + bottom) / 2 - rot.height / 2)), rot)
    series = list(dict.fromkeys(p[0] for p in points))
    obstacles: list[Box] = []
    for name in series:
        # In the order the knob was swept (not by x: a time that does not fall with the knob
        # shows as a kink rather than a reordered line).
        pts = [p for p in points if p[0] == name]
        color = COLORS.get(name, GREY)
        xy = [(ax(p[2]), ay(p[3])) for p in pts]
        if len(xy) > 1:
            d.line(xy, fill=color, width=2)
            for (ax0, ay0), (ax1, ay1) in zip(xy, xy[1:], strict=False):
                n = max(1, int(math.hypot(ax1 - ax0, ay1 - ay0) / 4))
                obstacles += [(ax0 + (ax1 - ax0) * i / n - 2, ay0 + (ay1 - ay0) * i / n - 2,
                               ax0 + (ax1 - ax0) * i / n + 2, ay0 + (ay1 - ay0) * i / n + 2)
                              for i in range(n + 1)]
        for (px, py), p in zip(xy, pts, strict=True):
            d.ellipse([px - 4, py - 4, px + 4, py + 4], fill=color)
            r = 11 if p[4] else 5
            obstacles.append((px - r, py - r, px + r, py + r))
            if p[4]:
                d.ellipse([px - 10, py - 10, px + 10, py + 10], outline=(200, 0, 0), width=3)
    # Points on one pixel (or nearly) share a label, in the series colour when they share one.
    groups: list[list[tuple[float, float, tuple[str, str, float, float, bool]]]] = []
    for p in points:
        px, py = ax(p[2]), ay(p[3])
        for g in groups:
            if abs(g[0][0] - px) < 5 and abs(g[0][1] - py) < 5:
                g.append((px, py, p))
                break
        else:
            groups.append([(px, py, p)])
    labels = []
    colors = []
    for g in groups:
        names = {q[2][0] for q in g}
        text = ", ".join(dict.fromkeys(q[2][1] for q in g))
        if any(q[2][4] for q in g):
            text += " (default)"
        colors.append((200, 0, 0) if any(q[2][4] for q in g)
                      else COLORS.get(g[0][2][0], GREY) if len(names) == 1 else INK)
        labels.append((g[0][0], g[0][1], text, 12))
    for (tx, ty, text), color in zip(place_labels(d, labels, obstacles, (left, top, x1, bottom)),
                                     colors, strict=True):
        d.text((tx, ty), text, fill=color, font=font(12))
    lx, ly = x1 + 16, top
    for i, name in enumerate(series):
        y = ly + 20 * i
        d.line([(lx, y + 7), (lx + 22, y + 7)], fill=COLORS.get(name, GREY), width=3)
        d.text((lx + 28, y), name, fill=INK, font=font(13))
    d.ellipse([lx + 4, ly + 20 * len(series) + 2, lx + 18, ly + 20 * len(series) + 16],
              outline=(200, 0, 0), width=3)
    d.text((lx + 28, ly + 20 * len(series)), "the defaults", fill=INK, font=font(13))
    for i, line in enumerate(_wrap(d, note, 12, w - left - 20)):
        d.text((left, bottom + 58 + 16 * i), line, fill=GREY, font=font(12))
    path.parent.mkdir(parents=True, exist_ok=True)
    img.quantize(64).save(path, optimize=True)


def renders_chart(path: Path, renders: dict[str, Path], titles: dict[str, str]) -> None:
    """The renders side by side (2 x 2), titled."""
    tiles = [Image.open(renders[k]).convert("RGB") for k in titles]
    tw, th = tiles[0].size
    scale = 480 / tw
    tw, th = int(tw * scale), int(th * scale)
    img = Image.new("RGB", (2 * tw + 30, 2 * (th + 30) + 10), WHITE)
    d = ImageDraw.Draw(img)
    for i, (tile, title) in enumerate(zip(tiles, titles.values(), strict=True)):
        x, y = 10 + (i % 2) * (tw + 10), 10 + (i // 2) * (th + 30)
        img.paste(tile.resize((tw, th), Image.LANCZOS), (x, y + 22))
        d.text((x, y + 2), title, fill=INK, font=font(14))
    img.save(path, optimize=True)


def diff_image(a: Path, b: Path, out: Path, gain: float = 4.0) -> None:
    x = np.asarray(Image.open(a).convert("RGB"), dtype=np.float64)
    y = np.asarray(Image.open(b).convert("RGB"), dtype=np.float64)
    diff = np.clip(np.abs(x - y).mean(axis=-1) * gain, 0, 255).astype(np.uint8)
    Image.fromarray(255 - diff).save(out)


# ---------------------------------------------------------------------------------------------


#: The figures of the last sweep, beside the charts, so the charts can be redrawn (--replot).
DATA = "speed_accuracy.json"
#: The measured fields of a record that the charts and the table use.
DATA_FIELDS = ("series", "label", "default", "click", "core", "triangles", "full_triangles",
               "tess_px", "ssim", "psnr", "ssim_full")


def save_data(path: Path, records: list[Record]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    scene = {"courses": COURSES, "wales": WALES, "resolution": list(RES),
             "supersample": SUPERSAMPLE}
    points = [{k: r[k] for k in DATA_FIELDS} for r in records]
    path.write_text(json.dumps({"scene": scene, "points": points}, indent=1) + "\n")


def draw_scatter_charts(out: Path, records: list[Record]) -> None:
    """The three scatter charts, from the sweep's records (or the saved figures)."""
    points = [r for r in records if r["series"] != "reference"]
    default = next(r for r in records if r["default"])
    note = (f"{COURSES} x {WALES} stitches receding from a 35 mm camera, {RES[0]} x {RES[1]}; "
            f"default auto detail: {default['triangles']:,} triangles vs "
            f"{default['full_triangles']:,} at full detail")
    scatter_chart(out / "speed_accuracy_ssim.png",
                  "Image error against click-to-mesh time",
                  [(r["series"], r["label"], r["click"], r["ssim"], r["default"])
                   for r in points],
                  "click to mesh (s)", "SSIM against the reference render", True, False, note)
    scatter_chart(out / "speed_accuracy_tessellation.png",
                  "Tessellation error against triangles",
                  [(r["series"], r["label"], r["triangles"], max(r["tess_px"], 1e-3),
                    r["default"]) for r in points],
                  "triangles", "tessellation error, 99th percentile (pixels)", True, True, note)
    scatter_chart(out / "speed_accuracy_target.png",
                  "Image error against triangles: the issue's target",
                  [(r["series"], r["label"], r["triangles"], r["ssim_full"], r["default"])
                   for r in points if r["label"] != "16"],
                  "triangles", "SSIM against full detail at the defaults", True, False,
                  note + "; target: 5x fewer triangles at SSIM 0.98 or better")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--zip", type=Path, default=None, help="extension zip to install")
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "charts")
    parser.add_argument("--renders", type=Path, default=None,
                        help="folder for the renders (default: a temporary one)")
    parser.add_argument("--quick", action="store_true", help="fewer points, half resolution")
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--no-flicker", action="store_true",
                        help="skip the flicker measurement (9 more renders)")
    parser.add_argument("--replot", action="store_true",
                        help=f"redraw the three scatter charts from --out/{DATA}, the figures "
                        "the last sweep saved, without sweeping again")
    args = parser.parse_args()
    if args.replot:
        draw_scatter_charts(args.out, json.loads((args.out / DATA).read_text())["points"])
        return

    start_blender(args.zip)
    from bl_ext.user_default.knitwear import api, texture  # noqa: I001

    renders = args.renders or Path(tempfile.mkdtemp(prefix="knitwear-speed-accuracy-"))
    renders.mkdir(parents=True, exist_ok=True)
    strip, cam = build_scene(args.quick)
    # Every render shows the source with the knitwear texture, as auto detail leaves it.
    texture.texture_object(strip, width=8 * WALES, height=4096, **base_settings())
    tess = Tessellation(api, strip, cam)

    records: list[Record] = []
    reference_img: np.ndarray | None = None
    images: list[np.ndarray] = []
    for i, (series, label, settings) in enumerate(sweep_points(args.quick)):
        rec, image = measure(api, strip, tess, settings, renders, f"{i:02d}", args.repeats)
        if reference_img is None:
            reference_img = image
        images.append(image)
        rec |= {"series": series, "label": label, "file": renders / f"{i:02d}.png",
                "ssim": ssim(image, reference_img), "psnr": psnr(image, reference_img),
                "default": settings.get("detail_mode") == "AUTO"
                and "cull_hidden" not in settings
                and all(settings.get(k, v) == v for k, v in DEFAULTS.items())}
        records.append(rec)
        lv = rec["levels"]
        print(f"{series:32s} {label:10s} click {rec['click']:6.3f} s  core {rec['core']:6.3f} s  "
              f"tris {rec['triangles']:>9,}  SSIM {rec['ssim']:.4f}  PSNR {rec['psnr']:5.1f}  "
              f"tess p99 {rec['tess_px']:.2f} px  levels {lv}", flush=True)

    default = next(r for r in records if r["default"])
    k_uniform = next(i for i, r in enumerate(records) if r["series"].startswith("samples")
                     and r["label"] == "16")
    uniform = records[k_uniform]
    floor = ssim(images[next(i for i, r in enumerate(records) if r["series"] == FLOOR)],
                 images[k_uniform])
    print("\nagainst the full-detail render at the defaults (the issue's target); 'of floor':"
          f" 1 - SSIM as a fraction of the seed-to-seed 1 - SSIM (floor SSIM {floor:.4f}):")
    for r, image in zip(records, images, strict=True):
        r["ssim_full"] = ssim(image, images[k_uniform])
        print(f"  {r['series']:32s} {r['label']:10s} SSIM {r['ssim_full']:.4f}  "
              f"of floor {(1 - r['ssim_full']) / (1 - floor):.2f}  "
              f"PSNR {psnr(image, images[k_uniform]):5.1f}  triangles {r['triangles']:,}")
    save_data(args.out / DATA, records)
    draw_scatter_charts(args.out, records)
    diff = renders / "diff.png"
    diff_image(uniform["file"], default["file"], diff)
    renders_chart(args.out / "speed_accuracy_renders.png",
                  {"ref": records[0]["file"], "full": uniform["file"],
                   "auto": default["file"], "diff": diff},
                  {"ref": "reference: full detail, 24 samples, 8 segments",
                   "full": f"full detail, defaults ({uniform['triangles']:,} tris)",
                   "auto": f"auto detail, defaults ({default['triangles']:,} tris)",
                   "diff": "|full detail - auto| x 4"})
    print(f"\ndefault auto detail: {default['triangles']:,} triangles, uniform full detail "
          f"{uniform['triangles']:,} ({uniform['triangles'] / default['triangles']:.1f}x); "
          f"SSIM against the reference {default['ssim']:.4f} (full detail {uniform['ssim']:.4f}), "
          f"against full detail {default['ssim_full']:.4f}; click "
          f"{default['click']:.2f} s vs {uniform['click']:.2f} s; core {default['core']:.3f} s "
          f"vs {uniform['core']:.3f} s")
    if not (args.quick or args.no_flicker):
        flicker(api, strip, cam, renders)
    print(f"charts in {args.out}, renders in {renders}")


if __name__ == "__main__":
    main()
