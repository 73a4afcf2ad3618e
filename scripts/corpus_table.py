"""Prints the corpus table of docs/where-it-breaks.md: each written pattern of
tests/data/knitspeak and tests/data/corpus, whether it parses, its repeat, the interlock
and minimum clearance on the sheet and the tube of `tests/python/core/test_corpus.py`, and
its first knit's time (the sheet, which tunes the pattern; the tube then reuses the tuning).

    PYTHONPATH=build/site .venv/bin/python scripts/corpus_table.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests/python/core"))

import knitwear  # noqa: E402
from test_corpus import FILES, sheet, tube  # noqa: E402


def main() -> None:
    print(
        "| pattern | repeat | parses | interlock (sheet / tube) | clearance (sheet / tube) "
        "| first knit |"
    )
    print("|---|---|---|---|---|---|")
    for path in FILES:
        try:
            pattern = knitwear.Pattern.from_text(path.read_text(encoding="utf-8"))
        except knitwear.KnitError as e:
            print(f"| {path.stem} | | no: {e} | | | |")
            continue
        cells, clear, first = [], [], 0.0
        for i, surface in enumerate((sheet(), tube(pattern.width))):
            t0 = time.perf_counter()
            stats = knitwear.knit(surface, pattern, measure_clearance=True).stats
            if i == 0:
                first = time.perf_counter() - t0
            decided, agree = stats["interlock"]
            cells.append(f"{100.0 * agree / decided:.0f}%")
            clear.append(f"{stats['clearance_min']:.3f}")
        print(
            f"| {path.stem} | {pattern.width} x {pattern.height} | yes | {' / '.join(cells)} "
            f"| {' / '.join(clear)} | {first:.1f} s |",
            flush=True,
        )


if __name__ == "__main__":
    main()
