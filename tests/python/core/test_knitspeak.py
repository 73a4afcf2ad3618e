"""Knitspeak from Python: the same chart as the preset, and errors a user can act on."""

from __future__ import annotations

import knitwear
import pytest


def test_knitspeak_reads_to_the_presets_chart() -> None:
    seed = knitwear.Pattern.from_knitspeak(
        "Row 1 (RS): *K1, p1, rep from *.\nRow 2: *P1, k1, rep from *."
    )
    assert seed.chart() == "pk\nkp\n"
    assert knitwear.Pattern.looks_like_knitspeak("Rnd 1: Knit.")
    assert not knitwear.Pattern.looks_like_knitspeak("kkpp\npppp")


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        ("Row 1: *k2, 2/2 RC; rep from *.", "2/2 RC"),
        ("Row 1: Knit.\nRow 3: Purl.", "row 2 has no instructions"),
        ("Row x: Knit.", "not a row header"),
    ],
)
def test_knitspeak_errors_are_pattern_errors(text: str, needle: str) -> None:
    with pytest.raises(knitwear.PatternError, match=needle):
        knitwear.Pattern.from_knitspeak(text)
