"""scripts/swatches.py (the swatch gallery of docs/stitches.md) renders a swatch that shows yarn."""

import importlib.util
from pathlib import Path
from types import ModuleType

import numpy as np
from PIL import Image

ROOT = Path(__file__).resolve().parents[3]


def _swatches() -> ModuleType:
    spec = importlib.util.spec_from_file_location("swatches", ROOT / "scripts" / "swatches.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_a_swatch_shows_yarn_on_the_background(api: ModuleType, tmp_path: Path) -> None:
    swatches = _swatches()
    assert swatches.swatch_counts(18, 4) == (36, 52)  # two repeats wide, about square
    png = tmp_path / "eyelet_rows.png"
    info = swatches.render_swatch("eyelet_rows", png, size=96)
    assert (info["wales"], info["courses"]) == (16, 24)
    rgb = np.asarray(Image.open(png).convert("RGB"), dtype=np.float32) / 255.0
    assert rgb.shape == (96, 96, 3)
    background = rgb[0, 0]
    yarn = np.linalg.norm(rgb - background, axis=-1) > 0.15
    # The frame's margin is background; the swatch inside is mostly yarn, with gaps between
    # loops and at the eyelets.
    assert not yarn[:2].any() and not yarn[-2:].any()
    assert 0.4 < yarn.mean() < 0.95, f"yarn covers {yarn.mean():.0%} of the frame"
    assert len(np.unique((rgb[yarn] * 32).astype(int), axis=0)) > 20  # shaded, not flat
