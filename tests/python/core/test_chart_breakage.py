"""scripts/chart_breakage.py (issue 4's charts of where knitting breaks) must not rot silently:
a tiny sweep of each kind gives records with every field, and the refusal points are refused
with the error classes the charts mark."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

SCRIPT = Path(__file__).resolve().parents[3] / "scripts" / "chart_breakage.py"
FIELDS = {"x", "error", "message", "clearance_min", "clearance_p01", "stitches",
          "stitches_skipped", "stitches_clamped", "interlock", "cover"}


@pytest.fixture(scope="module")
def charts() -> ModuleType:
    spec = importlib.util.spec_from_file_location("chart_breakage", SCRIPT)
    assert spec and spec.loader
    module = importlib.util.module_from_spec(spec)
    sys.modules["chart_breakage"] = module
    spec.loader.exec_module(module)
    return module


#: Stockinette's clearance at the default yarn, interlocked (docs/how-it-works.md, "Every
#: course interlocks"): 0.955 on a 12 x 10 cm sheet, finished. The earlier assertion of
#: more than 1.0 was the stacked knit's figure (courses lying over each other like roof
#: shingles).
STOCKINETTE_FLOOR = 0.9


def check(recs: list[dict], n: int) -> None:
    assert len(recs) == n
    for r in recs:
        assert FIELDS <= r.keys(), r
        if r["error"] is None:
            assert r["stitches"] > 0
            assert 0 < r["clearance_min"] <= r["clearance_p01"]
            # Every crossing between adjacent courses decided, in the knitted order, at
            # every point the charts plot: safeguards never buy clearance with the structure.
            assert r["interlock"] == 1.0, r


def test_curvature_clamps_on_a_thin_cylinder(charts: ModuleType) -> None:
    # A radius of 0.3 stitch widths: two stitches round, each offset clamped. (At 0.2, one
    # stitch round a tube not twice as thick as the quarter-stitch yarn, the loop passes
    # through itself: clearance 0.)
    recs = charts.sweep_curvature([0.3, 5.0], courses=4)
    check(recs, 2)
    assert recs[0]["error"] is None and recs[0]["stitches_clamped"] > 0
    assert recs[1]["stitches_clamped"] == 0 and recs[1]["clearance_min"] > STOCKINETTE_FLOOR


def test_kappa_beyond_the_maximum_is_refused(charts: ModuleType) -> None:
    recs = charts.sweep_kappa([0.0, 0.02, 0.021], seeds=[0, 1])
    check(recs, 6)
    assert [r["error"] for r in recs] == [None] * 4 + ["ParameterError"] * 2
    assert "kappa" in recs[-1]["message"]


def test_stretch_refuses_fixed_counts_not_the_gauge(charts: ModuleType) -> None:
    recs = charts.sweep_stretch([1.0, 30.0])
    check(recs, 4)
    by = {(r["x"], r["mode"]): r for r in recs}
    assert by[(1.0, "counts")]["error"] is None
    assert by[(30.0, "gauge")]["error"] is None
    assert by[(30.0, "counts")]["error"] == "ParameterError"
    assert "thicker than a stitch" in by[(30.0, "counts")]["message"]


def test_yarn_thicker_than_a_stitch_is_refused(charts: ModuleType) -> None:
    recs = charts.sweep_yarn([0.1, charts.DEFAULT_YARN, 0.55])
    check(recs, 3)
    thin, default, thick = recs
    assert default["error"] is None and default["clearance_min"] > STOCKINETTE_FLOOR
    # The cover bound for stockinette at the default yarn (0.895 here), and a
    # thinner yarn hides less of the fabric.
    assert default["cover"] >= 0.88, default
    assert thin["cover"] < default["cover"], (thin, default)
    assert thick["error"] == "ParameterError"


def test_charts_are_drawn(charts: ModuleType, tmp_path: Path) -> None:
    recs = charts.sweep_yarn([0.1, 0.3, 0.55])
    charts.chart_yarn(recs, tmp_path / "yarn.png")
    assert (tmp_path / "yarn.png").stat().st_size > 1000


def test_labels_do_not_overlap(charts: ModuleType, tmp_path: Path) -> None:
    # Two series crossing 1.0 and 0.95 at nearly the same place, beside the reference lines'
    # own labels: every label ends up clear of every other, inside the main panel.
    c = charts.Chart("t", "x", (1.0, 100.0), True, (0.0, 1.4))
    charts.acceptance_lines(c)
    for ys in ([1.0, 0.9, 0.5], [1.01, 0.93, 0.4]):
        c.crossings([1.0, 1.5, 3.0], ys, gentle_first=True)
    c.hline(0.96, (0, 0, 0), "a third line's label")
    c.save(tmp_path / "labels.png")
    boxes = c.placed
    assert len(boxes) == 7
    for i, a in enumerate(boxes):
        assert c.TOP <= a[1] and a[3] <= c.MAIN_BOTTOM, a
        for b in boxes[i + 1:]:
            assert not (a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]), (a, b)


def test_coarse_sampling_costs_clearance_not_the_interlock(charts: ModuleType) -> None:
    # Chords through 6 samples a loop cut the loops' corners (0.68 diameters); the default
    # 16 clears the floor. Both keep every crossing in the knitted order (`check`).
    coarse, default = charts.sweep_samples([6, charts.DEFAULT_SAMPLES])
    check([coarse, default], 2)
    assert coarse["clearance_min"] < default["clearance_min"]
    assert default["clearance_min"] > STOCKINETTE_FLOOR
