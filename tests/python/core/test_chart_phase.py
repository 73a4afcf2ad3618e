"""Where a chart starts (issue 17, bug 1): the same fabric charted from another column of its
repeat must knit as well. A chart started in the middle of a cable used to be tuned with the
cable cut at both sides of its patch: the twisted cable rib charted two columns on cleared
0.169 yarn diameters on a tube instead of 0.386.

On a tube (no edges) each phase's clearance is the tuning's alone. Crosses move loops only
within their own columns, so a chart's rotated text is exactly the same fabric."""

from __future__ import annotations

import math

import knitwear
import numpy as np
import pytest


def tube() -> knitwear.GridSurface:
    """A 40 x 40 stitch tube at the default gauge, knitted in the round."""
    radius, height = 0.4 / (2 * math.pi), 0.4
    a, z = np.meshgrid(np.linspace(0, 2 * np.pi, 96, endpoint=False), np.linspace(0, height, 24))
    nrm = np.stack([np.cos(a), np.sin(a), np.zeros_like(a)], axis=-1)
    pos = radius * nrm + np.stack([0 * a, 0 * a, z], axis=-1)
    return knitwear.GridSurface(pos.astype(np.float32), nrm.astype(np.float32), cyclic_u=True)


def rotated(pattern: knitwear.Pattern, shift: int) -> knitwear.Pattern:
    """The chart started `shift` columns further right (its legend kept)."""
    grid, _, legend = pattern.chart().partition("\n\n")
    rows = "\n".join(r[shift:] + r[:shift] for r in grid.split("\n"))
    return knitwear.Pattern.from_chart(f"{rows}\n\n{legend}")


def clearance(pattern: knitwear.Pattern) -> tuple[float, float, float]:
    stats = knitwear.knit(tube(), pattern, measure_clearance=True, threads=2).stats
    decided, agree = stats["interlock"]
    return stats["clearance_min"], stats["clearance_p01"], agree / decided


def test_a_chart_started_inside_a_cable_knits_as_well_as_its_own_phase() -> None:
    rib = knitwear.Pattern.preset("twisted_cable_rib")  # pXXp, X = 1/1 LC
    own = clearance(rib)
    cut = clearance(rotated(rib, 2))  # XppX: the cross split over the chart's edge
    clean = clearance(rotated(rib, 3))  # ppXX: the phase the cut chart is tuned in
    # Tuned alike; the tube's facets meet the loops at other columns, so not to the last bit.
    assert cut == pytest.approx(clean, abs=1e-4), "a cut chart is tuned where nothing is cut"
    assert cut[2] == own[2] == 1.0, "every course interlocks at every phase"
    assert cut[0] >= 0.9 * own[0] and cut[1] >= 0.9 * own[1], (cut, own)
