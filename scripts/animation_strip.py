"""The manual's animation strip (docs/charts/animation_strip.png): `examples/animate.py`'s
knitted sleeve rendered over its 24 frames, and six of them side by side, each labelled with
its frame, so a reader sees the knit follow the bending arm without playing a video.

    .venv/bin/python scripts/animation_strip.py          # about a minute on 2 cores
"""

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

from PIL import Image, ImageDraw

ROOT = Path(__file__).resolve().parent.parent
#: Frames shown: straight, bending, bent (the middle of 1-24 is frame 12), and back.
FRAMES = (1, 5, 9, 12, 17, 24)
SIZE = (320, 240)
LABEL_H = 22
STRIP_NAME = "animation_strip.png"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "charts" / STRIP_NAME)
    parser.add_argument("--zip", type=Path, help="extension zip (default: newest dist/*.zip)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="knitwear-strip-") as tmp:
        command = [sys.executable, str(ROOT / "examples" / "animate.py"), "--out", tmp,
                   "--frames", "1", "24", "--size", *map(str, SIZE), "--lens", "50"]
        if args.zip:
            command += ["--zip", str(args.zip)]
        subprocess.run(command, check=True)
        strip = Image.new("RGB", (SIZE[0] * len(FRAMES), SIZE[1] + LABEL_H), (20, 20, 22))
        draw = ImageDraw.Draw(strip)
        for i, frame in enumerate(FRAMES):
            tile = Image.open(Path(tmp) / f"frame_{frame:04d}.png").convert("RGB")
            strip.paste(tile, (i * SIZE[0], LABEL_H))
            draw.text((i * SIZE[0] + 8, 5), f"frame {frame}", fill=(230, 230, 230))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    strip.save(args.out)
    print(f"animation_strip: wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
