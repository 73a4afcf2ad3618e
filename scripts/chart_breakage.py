"""Charts of where knitting on a surface breaks (issue 4): sweeps the four parameters that break
knit-on-surface methods, and the centreline's sampling, and plots the yarn clearance
(docs/design.md section 7) against each, with the places where the core's safeguards engage
(offsets clamped to the curvature, stitches skipped, requests refused), the interlock and the
optical cover.

    PYTHONPATH=build/site .venv/bin/python scripts/chart_breakage.py [--out docs/charts]

Core Python API only (no Blender); surfaces are generated with numpy. Every point records the
clearance min and 1st percentile in yarn diameters, the stitches built, skipped and clamped, the
interlock (the fraction of crossings between adjacent courses whose order agrees with the stitch
as knitted: design.md section 3; 1.0 is a knitted fabric, every crossing decided) and, on the
flat sweeps, the optical cover (`knitwear.measure_cover`: the fraction of the fabric's middle,
a stitch in from every edge, hidden by the yarn's tubes seen square-on), and the
`knitwear.KnitError` subclass if the knit was refused. Charts are drawn with Pillow.
"""

from __future__ import annotations

import argparse
import math
import time
from collections.abc import Callable, Sequence
from itertools import pairwise
from pathlib import Path
from typing import Any

import knitwear
import numpy as np
from PIL import Image, ImageDraw, ImageFont

#: Stitch size every sweep is built around: the default gauge (20 x 28 per 10 cm).
STITCH_W = 0.005
STITCH_H = 0.1 / 28
#: The core's automatic yarn radius (`yarn_radius` 0): an eighth of the stitch width.
DEFAULT_YARN = 0.125
#: The core's default samples per loop.
DEFAULT_SAMPLES = 16
#: Cheap bundles: clearance is measured on the centrelines, which do not depend on them.
FAST = {"ring_segments": 3, "threads": 2, "measure_clearance": True}
PATTERN = "stockinette"
KAPPA_MAX = 0.02

Record = dict[str, Any]


# ---------------------------------------------------------------------------------------------
# Surfaces


def sheet(width: float = 0.1, height: float = 0.1, n: int = 24) -> knitwear.GridSurface:
    """A flat `width x height` sheet in z = 0, normals +Z."""
    u, v = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    pos = np.stack([width * u, height * v, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return knitwear.GridSurface(pos, nrm)


def cylinder(radius: float, height: float, cols: int, rows: int = 24) -> knitwear.GridSurface:
    """An open cylinder round the z axis, cyclic in u (knitted in the round)."""
    a, z = np.meshgrid(np.linspace(0, 2 * np.pi, cols, endpoint=False),
                       np.linspace(0, height, rows))
    nrm = np.stack([np.cos(a), np.sin(a), np.zeros_like(a)], axis=-1)
    pos = radius * nrm + np.stack([0 * a, 0 * a, z], axis=-1)
    return knitwear.GridSurface(pos.astype(np.float32), nrm.astype(np.float32), cyclic_u=True)


def stretched_strip(ratio: float, n: int = 20) -> knitwear.MeshSurface:
    """A flat strip of 3D size `0.1 sqrt(ratio) x 0.1 / sqrt(ratio)` (constant area) whose UVs
    are the unit square: a UV step along u is `ratio` times longer on the surface than along v.
    """
    lx, ly = 0.1 * math.sqrt(ratio), 0.1 / math.sqrt(ratio)
    t = np.linspace(0, 1, n + 1)
    u, v = np.meshgrid(t, t)
    pos = np.stack([lx * u, ly * v, np.zeros_like(u)], axis=-1).reshape(-1, 3)
    uv = np.stack([u, v], axis=-1).reshape(-1, 2)
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    a = (i * (n + 1) + j).ravel()
    b, c, d = a + 1, a + n + 2, a + n + 1
    tris = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)]).astype(np.int32)
    nrm = np.zeros_like(pos)
    nrm[:, 2] = 1.0
    return knitwear.MeshSurface(
        pos.astype(np.float32), nrm.astype(np.float32), tris, uv[tris].astype(np.float32)
    )


# ---------------------------------------------------------------------------------------------
# Sweeps


#: Pixels per side of the cover measure's raster (a stitch is about 20 of them on the sheet).
COVER_RESOLUTION = 400


def knit_point(x: float, surface: Any, cover_bounds: tuple[float, float, float, float] | None
               = None, **settings: Any) -> Record:
    """Knits one sweep point; a refusal is recorded (class name and message), not raised.
    `cover_bounds` (x_min, y_min, x_max, y_max in the surface's space): where to measure the
    optical cover, on a flat surface in z = 0 seen along z; None: not measured."""
    rec: Record = {
        "x": x, "error": None, "message": "", "clearance_min": None, "clearance_p01": None,
        "stitches": 0, "stitches_skipped": 0, "stitches_clamped": 0, "interlock": None,
        "cover": None,
    }
    try:
        r = knitwear.knit(surface, knitwear.Pattern.preset(PATTERN), **(FAST | settings))
    except knitwear.KnitError as e:
        rec["error"], rec["message"] = type(e).__name__, str(e)
        return rec
    s = r.stats
    for key in ("stitches", "stitches_skipped", "stitches_clamped", "clearance_min",
                "clearance_p01"):
        rec[key] = s[key]
    decided, agree = s["interlock"]
    rec["interlock"] = agree / decided if decided else None
    if cover_bounds is not None:
        rec["cover"] = knitwear.measure_cover(r, cover_bounds, COVER_RESOLUTION)
    return rec


def middle(width: float, height: float) -> tuple[float, float, float, float]:
    """The cover rectangle of a `width x height` sheet at the origin: a stitch in from each
    side and a course in from the top and bottom, where the cast-on and bind-off lie."""
    return (STITCH_W, STITCH_H, width - STITCH_W, height - STITCH_H)


def log_space(lo: float, hi: float, n: int) -> list[float]:
    return [float(x) for x in np.geomspace(lo, hi, n)]


def sweep_curvature(ratios: Sequence[float], courses: int = 12) -> list[Record]:
    """Cylinders of radius `R = ratio * stitch width`, knitted in the round with the stitch size
    and yarn pinned (the default yarn radius, an eighth of the stitch width): as many wales as
    fit round (at least one; below R/w = 1/(2 pi) one stitch is wider than the
    circumference)."""
    out = []
    for ratio in ratios:
        radius = ratio * STITCH_W
        wales = max(1, round(2 * np.pi * radius / STITCH_W))
        surf = cylinder(radius, (courses + 0.7) * STITCH_H, cols=max(48, 8 * wales))
        rec = knit_point(ratio, surf, courses=courses, wales=wales,
                         stitch_size=(STITCH_W, STITCH_H),
                         yarn_radius=DEFAULT_YARN * STITCH_W)
        rec["wales"] = wales
        out.append(rec)
    return out


def sweep_kappa(kappas: Sequence[float], seeds: Sequence[int]) -> list[Record]:
    """A flat 10 x 10 cm sheet at the default gauge, irregularity `kappa`, several seeds."""
    surf = sheet()
    out = []
    for kappa in kappas:
        for seed in seeds:
            rec = knit_point(kappa, surf, middle(0.1, 0.1), kappa=kappa, seed=seed)
            rec["seed"] = seed
            out.append(rec)
    return out


def sweep_stretch(ratios: Sequence[float], counts: int = 20) -> list[Record]:
    """UV stretch `ratio`:1 (`stretched_strip`), knitted by gauge (counts follow the surface)
    and by fixed `counts x counts` stitches (the stitch follows the UVs)."""
    out = []
    for ratio in ratios:
        surf = stretched_strip(ratio)
        lx, ly = 0.1 * math.sqrt(ratio), 0.1 / math.sqrt(ratio)
        for mode, settings in (("gauge", {}), ("counts", {"courses": counts, "wales": counts})):
            # A stitch in from each side: by gauge the default stitch; by counts the stitch
            # the UVs give, which grows along u and shrinks along v with the stretch.
            w, h = (STITCH_W, STITCH_H) if mode == "gauge" else (lx / counts, ly / counts)
            rec = knit_point(ratio, surf, (w, h, lx - w, ly - h), **settings)
            rec["mode"] = mode
            out.append(rec)
    return out


def sweep_samples(counts: Sequence[int]) -> list[Record]:
    """A flat sheet at the defaults, `samples_per_loop` samples along the yarn per stitch: the
    quality knob that shapes the centreline every metric is measured on (the speed-accuracy
    chart times it; here is what it costs the structure)."""
    surf = sheet()
    return [knit_point(n, surf, middle(0.1, 0.1), samples_per_loop=n) for n in counts]


def sweep_yarn(ratios: Sequence[float]) -> list[Record]:
    """A flat sheet at the default gauge, yarn radius `ratio * stitch width`."""
    surf = sheet()
    return [knit_point(r, surf, middle(0.1, 0.1), yarn_radius=r * STITCH_W) for r in ratios]


# ---------------------------------------------------------------------------------------------
# Drawing (Pillow): one clearance panel and a strip of safeguard counts below it

WHITE, INK, GRID = (255, 255, 255), (40, 40, 40), (225, 225, 225)
BLUE, ORANGE, GREEN = (31, 100, 180), (225, 110, 20), (40, 150, 70)
RED, GREY = (200, 40, 40), (120, 120, 120)
LIGHT_BLUE, LIGHT_ORANGE = (150, 190, 235), (250, 200, 150)
PURPLE, TEAL = (130, 60, 170), (20, 150, 140)
CLAMP_FILL, REFUSE_FILL = (255, 236, 200), (250, 212, 212)


def font(size: int) -> ImageFont.FreeTypeFont | ImageFont.ImageFont:
    return ImageFont.load_default(size=size)


class Axis:
    """Maps data to pixels along one axis, linear or log10."""

    def __init__(self, lo: float, hi: float, p0: float, p1: float, log: bool = False) -> None:
        self.lo, self.hi, self.p0, self.p1, self.log = lo, hi, p0, p1, log

    def __call__(self, x: float) -> float:
        f = math.log10 if self.log else float
        t = (f(x) - f(self.lo)) / (f(self.hi) - f(self.lo))
        return self.p0 + t * (self.p1 - self.p0)

    def ticks(self) -> list[float]:
        if self.log:
            lo, hi = math.floor(math.log10(self.lo)), math.ceil(math.log10(self.hi))
            cand = [m * 10.0**e for e in range(lo, hi + 1) for m in (1, 2, 5)]
        else:
            raw = (self.hi - self.lo) / 6
            mag = 10 ** math.floor(math.log10(raw))
            step = min((m * mag for m in (1, 2, 2.5, 5, 10) if m * mag >= raw), default=raw)
            start = math.ceil(self.lo / step - 1e-9) * step
            cand = [start + i * step for i in range(int((self.hi - start) / step + 1e-9) + 1)]
        return [c for c in cand if self.lo * (1 - 1e-9) <= c <= self.hi * (1 + 1e-9) + 1e-12]


def label(v: float) -> str:
    return f"{v:g}"


class Chart:
    """A 900 x 720 chart: clearance against the swept value on top, fractions (interlock, cover,
    stitches a safeguard touched) in a strip below, shared x axis, and the legend in two
    columns under the x label, where it hides no data."""

    W, H = 900, 720
    XLABEL_Y = 574
    LEFT, RIGHT, TOP = 80, 24, 52
    MAIN_BOTTOM, STRIP_TOP, STRIP_BOTTOM = 400, 438, 530

    def __init__(self, title: str, xlabel: str, xlim: tuple[float, float], log_x: bool,
                 ylim: tuple[float, float]) -> None:
        self.img = Image.new("RGB", (self.W, self.H), WHITE)
        self.d = ImageDraw.Draw(self.img)
        self.title, self.xlabel = title, xlabel
        self.x = Axis(*xlim, self.LEFT, self.W - self.RIGHT, log_x)
        self.y = Axis(*ylim, self.MAIN_BOTTOM, self.TOP)
        self.ys = Axis(0.0, 1.0, self.STRIP_BOTTOM, self.STRIP_TOP)
        self.legend: list[tuple[str, tuple[int, int, int], str]] = []
        # Text drawn over the plot, placed last (see `_place_labels`): (at, text, colour,
        # size, anchor, the colour of the box behind it).
        self.labels: list[tuple[tuple[float, float], str, tuple[int, int, int], int, str,
                                tuple[int, int, int]]] = []
        # Where they went: (left, top, right, bottom) pixels, each with its box.
        self.placed: list[tuple[float, float, float, float]] = []
        self._frame()

    def _frame(self) -> None:
        d = self.d
        d.text((self.W / 2, 16), self.title, fill=INK, font=font(19), anchor="mt")
        for ax, top, bottom in ((self.y, self.TOP, self.MAIN_BOTTOM),
                                (self.ys, self.STRIP_TOP, self.STRIP_BOTTOM)):
            for t in (ax.ticks() if ax is self.y else [0.0, 0.5, 1.0]):
                py = ax(t)
                d.line([(self.LEFT, py), (self.W - self.RIGHT, py)], fill=GRID)
                d.text((self.LEFT - 6, py), label(t), fill=INK, font=font(13), anchor="rm")
            for t in self.x.ticks():
                px = self.x(t)
                d.line([(px, top), (px, bottom)], fill=GRID)
        for t in self.x.ticks():
            px = self.x(t)
            d.text((px, self.STRIP_BOTTOM + 6), label(t), fill=INK, font=font(13), anchor="mt")
        d.text((self.W / 2, self.XLABEL_Y), self.xlabel, fill=INK, font=font(15), anchor="mt")
        mid = (self.TOP + self.MAIN_BOTTOM) / 2
        ylab = Image.new("RGBA", (340, 22), (255, 255, 255, 0))
        ImageDraw.Draw(ylab).text((170, 11), "clearance (yarn diameters)", fill=INK,
                                  font=font(15), anchor="mm")
        rot = ylab.rotate(90, expand=True)
        self.img.paste(rot, (4, int(mid - rot.height / 2)), rot)
        d.text((self.LEFT, self.STRIP_TOP - 9), "lower panel: fractions: interlock (crossings "
               "in the knitted order), cover (yarn square-on), stitches a safeguard touched",
               fill=INK, font=font(12), anchor="ls")

    def _clip(self, v: float, ax: Axis) -> float:
        return min(max(v, min(ax.lo, ax.hi)), max(ax.lo, ax.hi))

    def region(self, x0: float, x1: float, fill: tuple[int, int, int], text: str) -> None:
        """Shades `[x0, x1]` in both panels, labelled at the top of the main panel."""
        p0, p1 = self.x(self._clip(x0, self.x)), self.x(self._clip(x1, self.x))
        for top, bottom in ((self.TOP, self.MAIN_BOTTOM), (self.STRIP_TOP, self.STRIP_BOTTOM)):
            self.d.rectangle([p0, top, p1, bottom], fill=fill)
        if text:
            self.labels.append((((p0 + p1) / 2, self.TOP + 6), text, INK, 13, "mt", fill))

    def redraw_grid(self) -> None:
        """Grid lines over shaded regions (regions are drawn first and cover them)."""
        for t in self.y.ticks():
            self.d.line([(self.LEFT, self.y(t)), (self.W - self.RIGHT, self.y(t))], fill=GRID)

    def hline(self, y: float, color: tuple[int, int, int], text: str, below: bool = False) -> None:
        py = self.y(y)
        x0, x1 = self.LEFT, self.W - self.RIGHT
        for s in range(int(x0), int(x1), 12):
            self.d.line([(s, py), (min(s + 7, x1), py)], fill=color, width=2)
        at, anchor = ((x1 - 4, py + 4), "rt") if below else ((x1 - 4, py - 3), "rb")
        self.labels.append((at, text, color, 12, anchor, WHITE))

    def vline(self, x: float, color: tuple[int, int, int], text: str) -> None:
        px = self.x(x)
        for s in range(self.TOP, self.STRIP_BOTTOM, 10):
            self.d.line([(px, s), (px, min(s + 6, self.STRIP_BOTTOM))], fill=color, width=2)
        self.labels.append(((px + 4, self.MAIN_BOTTOM - 6), text, color, 13, "lb", WHITE))

    def series(self, xs: Sequence[float], ys: Sequence[float | None],
               color: tuple[int, int, int], name: str, strip: bool = False,
               marker: str = "o", dashed: bool = False, width: int = 2) -> None:
        """A line with markers; None values break the line."""
        ax = self.ys if strip else self.y
        pts: list[tuple[float, float] | None] = [
            None if v is None else (self.x(x), ax(self._clip(v, ax)))
            for x, v in zip(xs, ys, strict=True)
        ]
        for a, b in pairwise(pts):
            if a and b:
                if dashed:
                    n = max(1, int(math.dist(a, b) / 8))
                    for i in range(0, n, 2):
                        t0, t1 = i / n, min(i + 1, n) / n
                        self.d.line([(a[0] + t0 * (b[0] - a[0]), a[1] + t0 * (b[1] - a[1])),
                                     (a[0] + t1 * (b[0] - a[0]), a[1] + t1 * (b[1] - a[1]))],
                                    fill=color, width=width)
                else:
                    self.d.line([a, b], fill=color, width=width)
        for p in pts:
            if p and marker:
                self._marker(p, color, marker)
        self.legend.append((name, color, marker))

    def _marker(self, p: tuple[float, float], color: tuple[int, int, int], marker: str) -> None:
        x, y = p
        if marker == "o":
            self.d.ellipse([x - 4, y - 4, x + 4, y + 4], fill=color)
        elif marker == "s":
            self.d.rectangle([x - 3.5, y - 3.5, x + 3.5, y + 3.5], fill=color)
        elif marker == "x":
            self.d.line([(x - 6, y - 6), (x + 6, y + 6)], fill=color, width=3)
            self.d.line([(x - 6, y + 6), (x + 6, y - 6)], fill=color, width=3)
        elif marker == "^":
            self.d.polygon([(x, y - 5), (x - 5, y + 4), (x + 5, y + 4)], fill=color)
        elif marker == "O":
            self.d.ellipse([x - 6, y - 6, x + 6, y + 6], fill=color)

    def crossings(self, xs: Sequence[float], ys: Sequence[float], gentle_first: bool) -> None:
        """Rings where the line `ys` first drops below 1.0 and 0.95, labelled with the value."""
        order = sorted(range(len(xs)), key=lambda i: xs[i], reverse=not gentle_first)
        px = [self.x(xs[i]) for i in order]
        for level, color, dy in ((1.0, GREEN, -22), (0.95, RED, 10)):
            p = crossing(px, [ys[i] for i in order], level)
            if p is None:
                continue
            t = (p - self.x.p0) / (self.x.p1 - self.x.p0)
            f = math.log10 if self.x.log else float
            v = f(self.x.lo) + t * (f(self.x.hi) - f(self.x.lo))
            v = 10**v if self.x.log else v
            py = self.y(level)
            self.d.ellipse([p - 6, py - 6, p + 6, py + 6], outline=color, width=2)
            side = 8 if gentle_first else -8
            self.labels.append(((p + side, py + dy), f"< {level:g} at {v:.3g}", color, 13,
                                "lt" if gentle_first else "rt", WHITE))

    def marks(self, xs: Sequence[float], y: float, color: tuple[int, int, int], name: str,
              marker: str = "x") -> None:
        """Markers without a line (refused points drawn at height `y`)."""
        for x in xs:
            self._marker((self.x(x), self.y(y)), color, marker)
        if xs:
            self.legend.append((name, color, marker))

    def _place_labels(self) -> None:
        """Draws the queued labels over everything plotted, each on a box of its
        background's colour so that no line runs through its letters, moved up or down (in
        the order queued, nearest free place first) off any label already placed, within the
        main panel."""
        placed = self.placed
        pad = 2

        def clashes(box: tuple[float, float, float, float]) -> bool:
            return any(box[0] < b[2] and b[0] < box[2] and box[1] < b[3] and b[1] < box[3]
                       for b in placed)

        for (x, y), text, color, size, anchor, back in self.labels:
            f = font(size)
            x0, y0, x1, y1 = self.d.textbbox((x, y), text, font=f, anchor=anchor)
            box = (x0 - pad, y0 - pad, x1 + pad, y1 + pad)
            step = box[3] - box[1]
            for k in range(1, 12):
                if not clashes(box):
                    break
                # 1, -1, 2, -2, ... boxes down and up from where it was asked for.
                shift = step * ((k + 1) // 2) * (1 if k % 2 else -1)
                moved = (box[0], box[1] + shift, box[2], box[3] + shift)
                if moved[1] >= self.TOP and moved[3] <= self.MAIN_BOTTOM and not clashes(moved):
                    box, y = moved, y + shift
                    break
            placed.append(box)
            self.d.rectangle(box, fill=back)
            self.d.text((x, y), text, fill=color, font=f, anchor=anchor)

    def save(self, path: Path) -> None:
        self._place_labels()
        d, f = self.d, font(13)
        d.rectangle([self.LEFT, self.TOP, self.W - self.RIGHT, self.MAIN_BOTTOM], outline=INK)
        d.rectangle([self.LEFT, self.STRIP_TOP, self.W - self.RIGHT, self.STRIP_BOTTOM],
                    outline=INK)
        rows = (len(self.legend) + 1) // 2
        col = (self.W - self.LEFT - self.RIGHT) / 2
        for i, (name, color, marker) in enumerate(self.legend):
            x0 = self.LEFT + col * (i // rows)
            y = self.XLABEL_Y + 34 + 20 * (i % rows)
            d.line([(x0 + 6, y), (x0 + 28, y)], fill=color, width=3)
            self._marker((x0 + 17, y), color, marker)
            d.text((x0 + 36, y), name, fill=INK, font=f, anchor="lm")
        path.parent.mkdir(parents=True, exist_ok=True)
        self.img.quantize(64).save(path, optimize=True)


# ---------------------------------------------------------------------------------------------
# Charts


def ok(recs: Sequence[Record]) -> list[Record]:
    return [r for r in recs if r["error"] is None]


def fraction(r: Record, key: str) -> float:
    total = r["stitches"] + r["stitches_skipped"]
    return r[key] / total if total else 0.0


def ylim_for(recs: Sequence[Record]) -> tuple[float, float]:
    vals = [r["clearance_p01"] for r in ok(recs)] + [1.1]
    return 0.0, math.ceil(max(vals) * 1.1 * 5) / 5


def between(a: float, b: float, log: bool) -> float:
    """Midway between two sampled values: where a safeguard starts lies between them."""
    return math.sqrt(a * b) if log else (a + b) / 2


def edge(recs: Sequence[Record], inside: Callable[[Record], bool], log: bool) -> float | None:
    """The boundary of the region where `inside` holds, if it is one end of the sweep."""
    for a, b in pairwise(sorted(recs, key=lambda r: r["x"])):
        if inside(a) != inside(b):
            return between(a["x"], b["x"], log)
    return None


def clearance_lines(c: Chart, good: Sequence[Record], gentle_first: bool) -> None:
    xs = [r["x"] for r in good]
    c.series(xs, [r["clearance_p01"] for r in good], LIGHT_BLUE, "clearance p01", marker="",
             width=7)
    c.series(xs, [r["clearance_min"] for r in good], ORANGE, "clearance min", marker="s")
    c.crossings(xs, [r["clearance_min"] for r in good], gentle_first)


def acceptance_lines(c: Chart) -> None:
    c.hline(1.0, GREEN, "1.0: no interpenetration")
    c.hline(0.95, RED, "0.95: acceptance bound", below=True)


def strip_series(c: Chart, good: Sequence[Record], key: str, color: tuple[int, int, int],
                 what: str) -> None:
    fr = [fraction(r, key) for r in good]
    name = f"{what} (lower panel)" if any(fr) else f"{what}: none (lower panel)"
    c.series([r["x"] for r in good], fr, color, name, strip=True, marker="^")


def fabric_series(c: Chart, xs: Sequence[float], groups: Sequence[Sequence[Record]],
                  what: str = "") -> None:
    """Interlock and cover in the lower panel: the worst over each x's records (seeds)."""
    cover = [min((r["cover"] for r in g if r["cover"] is not None), default=None)
             for g in groups]
    if any(v is not None for v in cover):
        c.series(xs, cover, PURPLE, f"cover{what} (lower panel)", strip=True, marker="s")
    # Drawn last, so that it shows where the cover reaches 1 too.
    interlock = [min((r["interlock"] for r in g if r["interlock"] is not None), default=None)
                 for g in groups]
    c.series(xs, interlock, TEAL, f"interlock{what} (lower panel)", strip=True, marker="o")


def chart_curvature(recs: Sequence[Record], path: Path) -> None:
    good = ok(recs)
    xs = [r["x"] for r in recs]
    c = Chart("Cylinder knitted in the round: clearance vs curvature radius",
              "cylinder radius / stitch width  (log; stitch size and yarn pinned, "
              "the default yarn radius 0.125 stitch width)", (min(xs), max(xs)), True,
              ylim_for(recs))
    end = edge(good, lambda r: r["stitches_clamped"] > 0, True)
    if end is not None and good[0]["stitches_clamped"]:
        c.region(min(xs), end, CLAMP_FILL, "offsets clamped")
    c.redraw_grid()
    acceptance_lines(c)
    c.vline(1 / (2 * math.pi), GREY, "1 stitch round")
    clearance_lines(c, good, gentle_first=False)
    strip_series(c, good, "stitches_clamped", RED, "fraction clamped")
    fabric_series(c, [r["x"] for r in good], [[r] for r in good])
    c.marks([r["x"] for r in recs if r["error"]], 0.05, RED, "refused")
    c.save(path)


def chart_kappa(recs: Sequence[Record], path: Path) -> None:
    kappas = sorted({r["x"] for r in recs})
    allowed = [k for k in kappas if k <= KAPPA_MAX]
    refused = sorted({r["x"] for r in recs if r["error"]})
    hi = max(kappas)
    c = Chart("Irregularity (kappa) on a flat sheet: clearance over seeds",
              "kappa  (0 = regular; 0.02 = the allowed maximum)", (0.0, hi), False,
              (0.8, ylim_for(recs)[1] + 0.3))
    if refused:
        c.region(KAPPA_MAX, hi, REFUSE_FILL, "refused")
    c.redraw_grid()
    acceptance_lines(c)
    by = {k: [r for r in ok(recs) if r["x"] == k] for k in allowed}
    nseeds = max(len(v) for v in by.values())
    c.series(allowed, [float(np.mean([r["clearance_p01"] for r in by[k]])) for k in allowed],
             LIGHT_BLUE, "mean over seeds of p01", marker="", width=7)
    c.series(allowed, [min(r["clearance_p01"] for r in by[k]) for k in allowed], BLUE,
             "min over seeds of p01")
    c.series(allowed, [float(np.mean([r["clearance_min"] for r in by[k]])) for k in allowed],
             ORANGE, "mean over seeds of min", dashed=True, marker="")
    worst = [min(r["clearance_min"] for r in by[k]) for k in allowed]
    c.series(allowed, worst, ORANGE, f"min over {nseeds} seeds of min", marker="s")
    c.crossings(allowed, worst, gentle_first=True)
    c.marks(refused, 0.85, RED, "refused: ParameterError")
    strip_series(c, [by[k][0] for k in allowed], "stitches_clamped", GREY,
                 "skipped or clamped")
    fabric_series(c, allowed, [by[k] for k in allowed], " (worst seed)")
    c.save(path)


def chart_stretch(recs: Sequence[Record], path: Path) -> None:
    xs = sorted({r["x"] for r in recs})
    c = Chart("UV stretch: a strip whose UVs are squeezed N:1 against the surface",
              "UV stretch ratio N  (log; 3D strip 0.1 sqrt(N) x 0.1/sqrt(N) m on the unit UV "
              "square)", (min(xs), max(xs)), True, ylim_for(recs))
    counts = [r for r in recs if r["mode"] == "counts"]
    refused = [r["x"] for r in counts if r["error"]]
    start = edge(counts, lambda r: r["error"] is not None, True)
    if refused and start is not None:
        c.region(start, max(xs), REFUSE_FILL, "20 x 20 counts refused: yarn thicker than a "
                 "stitch")
    c.redraw_grid()
    acceptance_lines(c)
    for mode, light, dark in (("gauge", LIGHT_BLUE, BLUE), ("counts", LIGHT_ORANGE, ORANGE)):
        good = [r for r in ok(recs) if r["mode"] == mode]
        name = "by gauge" if mode == "gauge" else "20 x 20 fixed counts"
        gx = [r["x"] for r in good]
        c.series(gx, [r["clearance_p01"] for r in good], light, f"{name}: p01", marker="",
                 width=7)
        c.series(gx, [r["clearance_min"] for r in good], dark, f"{name}: min",
                 marker="o" if mode == "gauge" else "s")
        c.crossings(gx, [r["clearance_min"] for r in good], gentle_first=True)
    c.marks(refused, 0.1, RED, "20 x 20 refused (ParameterError)")
    for mode, color in (("gauge", BLUE), ("counts", ORANGE)):
        good = [r for r in ok(recs) if r["mode"] == mode]
        strip_series(c, good, "stitches_skipped", color, f"skipped, {mode}")
    good = [r for r in ok(recs) if r["mode"] == "gauge"]
    fabric_series(c, [r["x"] for r in good], [[r] for r in good], ", by gauge")
    c.save(path)


def chart_yarn(recs: Sequence[Record], path: Path) -> None:
    xs = [r["x"] for r in recs]
    good = ok(recs)
    refused = [r["x"] for r in recs if r["error"]]
    c = Chart("Yarn radius on a flat sheet: clearance vs yarn thickness",
              "yarn radius / stitch width  (default gauge 20 x 28 per 10 cm)",
              (min(xs), max(xs)), False, ylim_for(recs))
    start = edge(recs, lambda r: r["error"] is not None, False)
    if refused and start is not None:
        c.region(start, max(xs), REFUSE_FILL, "refused: r > w/2")
    c.redraw_grid()
    acceptance_lines(c)
    c.vline(DEFAULT_YARN, GREY, f"default {DEFAULT_YARN:g}")
    clearance_lines(c, good, gentle_first=True)
    strip_series(c, good, "stitches_clamped", GREY, "skipped or clamped")
    fabric_series(c, [r["x"] for r in good], [[r] for r in good])
    c.marks(refused, 0.1, RED, "refused: ParameterError")
    c.save(path)


def chart_samples(recs: Sequence[Record], path: Path) -> None:
    xs = [r["x"] for r in recs]
    good = ok(recs)
    c = Chart("Samples per loop on a flat sheet: clearance vs centreline sampling",
              "samples per loop  (log; default gauge and yarn)", (min(xs), max(xs)), True,
              ylim_for(recs))
    c.redraw_grid()
    acceptance_lines(c)
    c.vline(DEFAULT_SAMPLES, GREY, f"default {DEFAULT_SAMPLES}")
    clearance_lines(c, good, gentle_first=False)
    strip_series(c, good, "stitches_clamped", GREY, "skipped or clamped")
    fabric_series(c, [r["x"] for r in good], [[r] for r in good])
    c.save(path)


# ---------------------------------------------------------------------------------------------


def crossing(xs: Sequence[float], ys: Sequence[float], level: float) -> float | None:
    """The first swept value, scanning from the gentle end (`xs` given in that order), where
    `ys` drops below `level`, interpolated; None if it never does."""
    for (x0, y0), (x1, y1) in pairwise(zip(xs, ys, strict=True)):
        if y0 >= level > y1:
            return x0 + (y0 - level) / (y0 - y1) * (x1 - x0)
    return None


def summary(name: str, recs: Sequence[Record], gentle_first: bool) -> str:
    good = sorted(ok(recs), key=lambda r: r["x"], reverse=not gentle_first)
    parts = [name]
    if good:
        worst = min(good, key=lambda r: r["clearance_min"])
        parts.append(f"clearance_min {good[0]['clearance_min']:.3f} at {good[0]['x']:.3g}, "
                     f"worst {worst['clearance_min']:.3f} at {worst['x']:.3g}")
        xs = [r["x"] for r in good]
        for level in (1.0, 0.95):
            ys = [r["clearance_min"] for r in good]
            if ys[0] < level:
                parts.append(f"< {level} from the start")
            else:
                x = crossing(xs, ys, level)
                parts.append(f"< {level}: {'never' if x is None else f'{x:.3g}'}")
    interlock = [r["interlock"] for r in good if r["interlock"] is not None]
    if interlock:
        parts.append(f"interlock {min(interlock):.4f}..{max(interlock):.4f}")
    cover = [r["cover"] for r in good if r["cover"] is not None]
    if cover:
        parts.append(f"cover {min(cover):.3f}..{max(cover):.3f}")
    clamped = [r["x"] for r in good if r["stitches_clamped"]]
    skipped = [r["x"] for r in good if r["stitches_skipped"]]
    errors = sorted({(r["x"], r["error"]) for r in recs if r["error"]})
    if clamped:
        parts.append(f"clamped at {min(clamped):.3g}..{max(clamped):.3g}")
    if skipped:
        parts.append(f"skips at {min(skipped):.3g}..{max(skipped):.3g}")
    if errors:
        parts.append(f"refused at {errors[0][0]:.3g}..{errors[-1][0]:.3g} ({errors[0][1]})")
    return "; ".join(parts)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=Path("docs/charts"))
    args = ap.parse_args()
    start = time.perf_counter()
    jobs: list[tuple[str, Callable[[], list[Record]], Callable[..., None], bool]] = [
        ("curvature", lambda: sweep_curvature(log_space(0.1, 10, 17)), chart_curvature, False),
        ("kappa", lambda: sweep_kappa([i * 0.0025 for i in range(9)] + [0.021], range(5)),
         chart_kappa, True),
        ("stretch", lambda: sweep_stretch(log_space(1, 100, 13)), chart_stretch, True),
        ("samples", lambda: sweep_samples([6, 8, 10, 12, 14, 16, 20, 24, 32, 48, 64]),
         chart_samples, False),
        ("yarn", lambda: sweep_yarn([round(0.05 + 0.025 * i, 3) for i in range(23)]),
         chart_yarn, True),
    ]
    for name, sweep, draw, gentle_first in jobs:
        t = time.perf_counter()
        recs = sweep()
        path = args.out / f"breakage_{name}.png"
        draw(recs, path)
        if name == "stretch":
            for mode in ("gauge", "counts"):
                sub = [r for r in recs if r["mode"] == mode]
                print(summary(f"{name} ({mode})", sub, gentle_first))
        else:
            print(summary(name, recs, gentle_first))
        print(f"  -> {path} ({len(recs)} knits, {time.perf_counter() - t:.1f} s)")
    print(f"total {time.perf_counter() - start:.1f} s")


if __name__ == "__main__":
    main()
