"""Stopping a long core call: `knitwear.cancel()` from another thread (what the add-on does on
Esc) and Ctrl-C (SIGINT) in the calling thread. A stopped call raises, keeps nothing, and the
next call gives what a fresh process gives, bit for bit.

The long call is the first knit of a pattern no other test uses (its loop shapes are tuned
first: seconds). How fast a call stops is a figure in `benchmarks/bench_cancel.py`, not an
assertion here."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
from pathlib import Path

import knitwear
import numpy as np
import pytest


def sheet() -> knitwear.GridSurface:
    u, v = np.meshgrid(np.linspace(0, 1, 12), np.linspace(0, 1, 12))
    pos = np.stack([u * 0.05, v * 0.05, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return knitwear.GridSurface(pos, nrm)


def fresh_chart(seed: int) -> str:
    """A 10 x 10 knit/purl chart that no other test knits, so its tuning is not cached."""
    rng = np.random.default_rng(seed)
    return "\n".join("".join(rng.choice(["k", "p"], 10)) for _ in range(10))


KNIT = "knitwear.knit(s, knitwear.Pattern.from_chart(chart), courses=10, wales=10)"


def test_cancel_from_another_thread_stops_a_first_knit_and_keeps_nothing(tmp_path: Path) -> None:
    chart = fresh_chart(11)
    timer = threading.Timer(0.5, knitwear.cancel)
    timer.start()
    try:
        with pytest.raises(knitwear.CancelledError, match="stopped before it finished"):
            knitwear.knit(sheet(), knitwear.Pattern.from_chart(chart), courses=10, wales=10)
    finally:
        timer.cancel()
    # The half-made tuning was not cached: knitting again gives what a fresh process gives.
    again = knitwear.knit(sheet(), knitwear.Pattern.from_chart(chart), courses=10, wales=10)
    script = tmp_path / "fresh.py"
    script.write_text(
        "import sys, numpy as np, knitwear\n"
        f"sys.path.insert(0, {str(Path(__file__).parent)!r})\n"
        "from test_cancel import sheet\n"
        f"chart = {chart!r}\n"
        f"s = sheet()\nr = {KNIT}\n"
        f"np.save({str(tmp_path / 'fresh.npy')!r}, r.vertices)\n"
    )
    subprocess.run([sys.executable, str(script)], check=True, env=dict(os.environ))
    assert np.array_equal(again.vertices, np.load(tmp_path / "fresh.npy"))


def test_a_cancel_with_no_call_running_does_not_stop_the_next_one() -> None:
    knitwear.cancel()
    r = knitwear.knit(sheet(), knitwear.Pattern.preset("stockinette"), courses=6, wales=6)
    assert r.stats["stitches"] == 36


def test_ctrl_c_interrupts_a_first_knit() -> None:
    chart = fresh_chart(12)
    # Python raises KeyboardInterrupt on SIGINT only if it started with SIGINT's default
    # handling; a shell's background job starts with SIGINT ignored (where this test could
    # not pass), so the handler a terminal gives is set here.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            knitwear.knit(sheet(), knitwear.Pattern.from_chart(chart), courses=10, wales=10)
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    # The process goes on, and so does the core.
    r = knitwear.knit(sheet(), knitwear.Pattern.preset("stockinette"), courses=6, wales=6)
    assert r.stats["stitches"] == 36
