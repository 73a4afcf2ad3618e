"""The plush close up (issue 16 item 6): the paper's palm print at 1024 px, in Workbench and
EEVEE, as one labelled sheet, with the two figures that say whether the pile looks right:

    .venv/bin/python scripts/plush_closeups.py [--zip dist/knitwear-0.1.0.zip]
        [--before old.zip] [--out docs/charts/plush_closeups.png]

- **Line step**: the largest brightness change over 8 rows of the palm's row profile (smoothed
  over 9 rows), as a share of its mean. A hard line where piles change slice kind gives a
  large step; a blend across a band spreads it.
- **Grid peak**: in an unpressed crop of the EEVEE render, the strongest spectral peak over
  the median power at its frequency. Piles on an exact grid give a sharp peak at the grid's
  frequency; a pile with no rows gives none (Workbench's flat pile reads about 20).

Each build renders with examples/plush_cushion.py in its own Blender process (it installs its
zip in a fresh user folder). With ``--before`` (another build's zip) a first row shows that
build. Look at the sheet.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw

ROOT = Path(__file__).resolve().parents[1]
#: Render size, and the crops (left, top, right, bottom) of the palm and of unpressed pile.
SIZE = 1024
PALM = (420, 500, 620, 670)
PROFILE = (470, 500, 580, 635)
UNPRESSED = (620, 600, 780, 760)
SCALE = 2


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    parser.add_argument("--before", type=Path, help="another build's zip, for a first row")
    parser.add_argument(
        "--out", type=Path, default=ROOT / "docs" / "charts" / "plush_closeups.png"
    )
    return parser.parse_args()


def luminance(image: Image.Image) -> np.ndarray:
    rgb = np.asarray(image.convert("RGB"), np.float64) / 255.0
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def line_step(image: Image.Image) -> float:
    left, top, right, bottom = PROFILE
    profile = luminance(image)[top:bottom, left:right].mean(axis=1)
    smooth = np.convolve(profile, np.ones(9) / 9, mode="valid")
    return float(np.abs(smooth[8:] - smooth[:-8]).max() / smooth.mean())


def grid_peak(image: Image.Image) -> float:
    left, top, right, bottom = UNPRESSED
    g = luminance(image)[top:bottom, left:right]
    g = g - g.mean()
    window = np.hanning(g.shape[0])[:, None] * np.hanning(g.shape[1])[None, :]
    power = np.abs(np.fft.fftshift(np.fft.fft2(g * window))) ** 2
    y, x = np.indices(power.shape) - g.shape[0] // 2
    radius = np.hypot(x, y).round().astype(int)
    return max(
        float(power[radius == k].max() / np.median(power[radius == k]))
        for k in range(8, g.shape[0] // 2)
    )


def render(zip_path: Path | None, folder: Path) -> tuple[Image.Image, Image.Image]:
    command = [
        sys.executable, str(ROOT / "examples" / "plush_cushion.py"), "--out", str(folder),
        "--width", str(SIZE), "--height", str(SIZE), "--eevee",
    ]
    if zip_path is not None:
        command += ["--zip", str(zip_path)]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    return (
        Image.open(folder / "plush_cushion.png").convert("RGB"),
        Image.open(folder / "plush_cushion_eevee.png").convert("RGB"),
    )


def main() -> None:
    args = parse_args()
    builds = ([("before", args.before)] if args.before else []) + [("this build", args.zip)]
    rows = []
    with tempfile.TemporaryDirectory(prefix="knitwear-plush-closeups-") as tmp:
        for k, (name, zip_path) in enumerate(builds):
            workbench, eevee = render(zip_path, Path(tmp) / str(k))
            step, peak = line_step(workbench), grid_peak(eevee)
            print(f"{name}: line step {step:.3f} (Workbench), grid peak {peak:.0f} (EEVEE)")
            rows.append((name, workbench, eevee, step, peak))

    def crop(image: Image.Image, box: tuple[int, int, int, int]) -> Image.Image:
        part = image.crop(box)
        return part.resize((part.width * SCALE, part.height * SCALE), Image.NEAREST)

    tiles = [(crop(w, PALM), crop(e, UNPRESSED)) for _, w, e, _, _ in rows]
    label_h, gap = 22, 8
    width = tiles[0][0].width + tiles[0][1].width + gap
    height = max(tile.height for pair in tiles for tile in pair)
    sheet = Image.new("RGB", (width, len(rows) * (height + label_h)), (255, 255, 255))
    draw = ImageDraw.Draw(sheet)
    for r, ((name, _, _, step, peak), (palm, pile)) in enumerate(zip(rows, tiles, strict=True)):
        y = r * (height + label_h)
        draw.text(
            (4, y + 4),
            f"{name}: Workbench palm, line step {step:.3f} | EEVEE pile, grid peak {peak:.0f}",
            fill=(0, 0, 0),
        )
        sheet.paste(palm, (0, y + label_h))
        sheet.paste(pile, (palm.width + gap, y + label_h))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(args.out)
    print(f"plush_closeups: wrote {args.out}")


if __name__ == "__main__":
    main()
