"""What every benchmark does first: install the built extension into a throw-away Blender
user folder, and time things as medians.

`start_blender` must run before anything imports `bpy`: Blender reads BLENDER_USER_RESOURCES
once, at the first import.
"""

import os
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def median_seconds(run: Callable[[], object], repeats: int) -> float:
    """Median wall-clock seconds of ``repeats`` calls of ``run``."""
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        run()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def start_blender(zip_arg: Path | None) -> None:
    """Import bpy with a fresh user folder and install the extension from ``zip_arg`` (default:
    the newest dist/knitwear-*.zip), as Install from Disk does."""
    os.environ["BLENDER_USER_RESOURCES"] = tempfile.mkdtemp(prefix="knitwear-bench-")
    import bpy

    zips = sorted((ROOT / "dist").glob("knitwear-*.zip"), key=lambda p: p.stat().st_mtime)
    zip_path = zip_arg or (zips[-1] if zips else None)
    if zip_path is None:
        sys.exit("bench: no dist/knitwear-*.zip; run scripts/bootstrap.sh first")
    result = bpy.ops.extensions.package_install_files(
        filepath=str(zip_path), repo="user_default", enable_on_install=True
    )
    if result != {"FINISHED"}:
        sys.exit(f"bench: installing {zip_path} failed: {result}")
