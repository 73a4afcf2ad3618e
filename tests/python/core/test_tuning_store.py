"""The tuning store (`src/skeleton/tuning_store.rs`): a pattern's tuned loop shapes kept on
disk, so that a new process knits at once what an earlier one tuned. A stored tuning must
give exactly what tuning afresh gives, a damaged or foreign file must be ignored, and the
store must really be read (a planted value changes the knit).

Each knit runs in its own process: within one process the tuning is kept in memory and the
store is never asked."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import knitwear
import pytest

#: Knits the seed-stitch preset (tuned in about a second) on a small sheet and prints the
#: SHA-256 of its vertices.
CHILD = """
import hashlib, numpy as np, knitwear
u, v = np.meshgrid(np.linspace(0, 1, 12), np.linspace(0, 1, 12))
pos = np.stack([u * 0.05, v * 0.05, np.zeros_like(u)], axis=-1).astype(np.float32)
nrm = np.zeros_like(pos); nrm[..., 2] = 1.0
r = knitwear.knit(knitwear.GridSurface(pos, nrm), knitwear.Pattern.preset("seed"), threads=2)
print(hashlib.sha256(r.vertices.tobytes()).hexdigest())
"""


def knit_in_new_process(store: Path | None) -> str:
    env = dict(os.environ)
    env.pop("KNITWEAR_TUNING_STORE", None)
    if store is not None:
        env["KNITWEAR_TUNING_STORE"] = str(store)
    done = subprocess.run(
        [sys.executable, "-c", CHILD], env=env, capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, done.stderr
    return done.stdout.strip()


def stored_files(store: Path) -> list[Path]:
    return sorted(store.glob("*.tuning"))


def test_a_stored_tuning_knits_what_tuning_afresh_knits(tmp_path: Path) -> None:
    store = tmp_path / "store"
    fresh = knit_in_new_process(None)
    assert knit_in_new_process(store) == fresh  # tunes, and stores
    files = stored_files(store)
    assert len(files) == 1, files
    text = files[0].read_text()
    assert text.startswith("knitwear tuning store 1\nbuild ") and text.endswith("\n")
    assert "\nkey Key { pattern: StitchPattern { name: \"seed\"" in text
    assert knit_in_new_process(store) == fresh  # reads it
    assert not list(store.glob("*.partial")), "a temporary file was left behind"


def test_the_store_is_read_and_a_damaged_file_is_ignored(tmp_path: Path) -> None:
    store = tmp_path / "store"
    fresh = knit_in_new_process(store)
    (file,) = stored_files(store)
    good = file.read_text()
    # A planted value (the first offset coefficient, one bit changed) is what the next
    # process knits with: the store is really read, not only written.
    head, value = good.rstrip("\n").rsplit("\nvalue ", 1)
    words = value.split(" ")
    words[0] = f"{int(words[0], 16) ^ 0x0040_0000:08x}"
    file.write_text(f"{head}\nvalue {' '.join(words)}\n")
    assert knit_in_new_process(store) != fresh
    # A file cut short, another build's or rubbish is ignored and written anew, whole.
    for damaged in (good[: len(good) // 2], good.replace("\nbuild ", "\nbuild 0"), "rubbish"):
        file.write_text(damaged)
        assert knit_in_new_process(store) == fresh
        assert file.read_text() == good


def test_the_folder_is_set_per_process_and_overrides_the_environment(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    before = knitwear.tuning_store()
    try:
        monkeypatch.setenv("KNITWEAR_TUNING_STORE", str(tmp_path / "from-env"))
        knitwear.set_tuning_store(tmp_path / "set")
        assert knitwear.tuning_store() == str(tmp_path / "set")
        knitwear.set_tuning_store(None)
        assert knitwear.tuning_store() is None
    finally:
        knitwear.set_tuning_store(before)
