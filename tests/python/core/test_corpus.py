"""The written-pattern corpus (issue 17's "Show"): 44 Knitspeak patterns covering each stitch
family, the team's shared ones (tests/data/knitspeak) and the corpus (tests/data/corpus).

For each: it parses (its width note, where it has one, checked against its rows by the
reader), `chart()` reads back to the same chart, and it knits at the default gauge and yarn on
a 12 x 10 cm sheet and on a tube knitted in the round (its circumference whole repeats of
5 mm stitches, the sheet's stitch, so the two share one tuning) with every interlock crossing
the right way round and no free loop. Clearance is held to what this commit measures
(`FLOORS`, a floor 0.02 under it): most patterns fall short of the issue's 0.95, and the
corpus table in docs/where-it-breaks.md (`scripts/corpus_table.py`) says so; a change that
loses clearance shows here.
"""

from __future__ import annotations

from pathlib import Path

import knitwear
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[3]
FILES = sorted(
    [*(ROOT / "tests/data/knitspeak").glob("*.ks"), *(ROOT / "tests/data/corpus").glob("*.ks")]
)
STITCH_WIDTH = 0.005  # metres: the default gauge, 20 stitches per 10 cm

# Minimum clearance (yarn diameters) measured at this commit on the sheet and the tube.
FLOORS: dict[str, tuple[float, float]] = {
    "arrowhead-lace": (0.336, 0.351),
    "basketweave": (0.628, 0.608),
    "bobble-rib": (0.848, 0.848),
    "bobbles": (0.892, 0.962),
    "box-stitch": (0.679, 0.687),
    "braid": (0.368, 0.366),
    "british-cable-rib": (0.448, 0.455),
    "broken-rib": (0.722, 0.716),
    "cable-4": (0.575, 0.603),
    "cable-4-in-the-round": (0.452, 0.450),
    "cable-6": (0.365, 0.348),
    "cable-8": (0.354, 0.407),
    "cable-panel-markers": (0.369, 0.359),
    "centre-cross": (0.430, 0.444),
    "diagonal-rib": (0.663, 0.778),
    "double-moss": (0.738, 0.775),
    "eyelet-rib": (0.745, 0.787),
    "eyelet-rows": (0.565, 0.562),
    "faggoting": (0.505, 0.507),
    "feather-and-fan": (0.388, 0.382),
    "garter": (0.874, 0.891),
    "garter-rib": (0.718, 0.709),
    "heel-stitch": (0.501, 0.507),
    "herringbone-lace": (0.313, 0.328),
    "horseshoe-cable": (0.451, 0.459),
    "lace-rib": (0.652, 0.772),
    "linen-stitch": (0.258, 0.284),
    "mock-cable": (0.636, 0.647),
    "rib-1x1": (0.967, 0.944),
    "rib-2x2": (0.892, 0.866),
    "rice-stitch": (0.632, 0.670),
    "ripple-lace": (0.189, 0.196),
    "sand-stitch": (0.591, 0.647),
    "seed": (0.699, 0.695),
    "seeded-rib": (0.657, 0.645),
    "slip-stitch-rib": (0.293, 0.301),
    "stockinette": (0.969, 0.982),
    "trellis": (0.407, 0.449),
    "tweed-stitch": (0.382, 0.398),
    "twisted-rib": (0.752, 0.752),
    "twisted-rib-2x2": (0.855, 0.866),
    "twisted-eyelet-rib": (0.107, 0.325),
    "waffle": (0.793, 0.793),
    "walker-eyelets": (0.486, 0.485),
    "wave": (0.627, 0.626),
    "welt": (0.592, 0.631),
    "zigzag-lace": (0.196, 0.211),
}


def sheet() -> knitwear.GridSurface:
    u, v = np.meshgrid(np.linspace(0, 1, 24), np.linspace(0, 1, 24))
    pos = np.stack([u * 0.12, v * 0.10, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return knitwear.GridSurface(pos, nrm)


def tube(repeat: int) -> knitwear.GridSurface:
    """A tube 10 cm tall whose circumference is whole repeats of the pattern (about 24
    stitches) of exactly the sheet's stitch width (the polygon's perimeter, not the
    circle's)."""
    wales = repeat * max(1, round(24 / repeat))
    columns, rows = 96, 24
    a = np.arange(columns) / columns * 2 * np.pi
    r = wales * STITCH_WIDTH / (2 * columns * np.sin(np.pi / columns))
    v = np.linspace(0, 1, rows)
    pos = np.zeros((rows, columns, 3), np.float32)
    nrm = np.zeros_like(pos)
    pos[..., 0] = r * np.cos(a)[None]
    pos[..., 1] = r * np.sin(a)[None]
    pos[..., 2] = 0.10 * v[:, None]
    nrm[..., 0] = np.cos(a)[None]
    nrm[..., 1] = np.sin(a)[None]
    return knitwear.GridSurface(pos, nrm, cyclic_u=True)


def test_the_corpus_has_47_patterns_each_with_its_floor() -> None:
    names = sorted(f.stem for f in FILES)
    assert len(names) >= 47, names
    assert names == sorted(FLOORS), set(names) ^ set(FLOORS)


@pytest.mark.parametrize("path", FILES, ids=[f.stem for f in FILES])
def test_a_written_pattern_reads_charts_back_and_knits_interlocked(path: Path) -> None:
    pattern = knitwear.Pattern.from_text(path.read_text(encoding="utf-8"))
    chart = pattern.chart()
    assert knitwear.Pattern.from_chart(chart).chart() == chart
    for i, surface in enumerate((sheet(), tube(pattern.width))):
        stats = knitwear.knit(surface, pattern, measure_clearance=True).stats
        decided, agree = stats["interlock"]
        assert decided > 1000 and agree == decided, (path.stem, i, decided, agree)
        assert stats["free_loops"] == (0, 0), (path.stem, i)
        assert abs(stats["stitch_width"] - STITCH_WIDTH) < 1e-5, stats["stitch_width"]
        floor = FLOORS[path.stem][i] - 0.02
        assert stats["clearance_min"] >= floor, (path.stem, i, stats["clearance_min"])
