"""Every Python block of the README and the manual that uses `bpy` runs as written, in a fresh
headless Blender with the extension installed from the built zip, as a reader's would be
(the blocks without `bpy` run in tests/python/core/test_docs.py).

A block runs as a Blender with the extension installed would run it: a separate run installs
the zip and saves the preferences, and the block's run first reads them (the Blender
application does at start-up; the `bpy` module starts from factory preferences). Its scene is
Blender's default startup scene (its camera included), plus a 20 cm UV-mapped plane for each
object it names as `bpy.data.objects["Name"]` and an image for each `..._image_name="Name"`
it names. The one substitution made: the placeholder `/path/to/knitwear-0.1.0.zip` becomes the
zip under test. A block that installs the extension itself runs alone, in a fresh user folder;
the tutorial's install and render blocks also run one after the other, as written.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path
from types import ModuleType

import pytest
from conftest import _extension_zip

ROOT = Path(__file__).resolve().parents[3]
PAGES = sorted([ROOT / "README.md", *(ROOT / "docs").glob("*.md")])
BLOCK = re.compile(r"^```([^\n]*)\n(.*?)^```", re.S | re.M)
PLACEHOLDER_ZIP = "/path/to/knitwear-0.1.0.zip"


def _blocks() -> list[tuple[str, str]]:
    found = []
    for page in PAGES:
        blocks = [b for lang, b in BLOCK.findall(page.read_text()) if lang == "python"]
        for i, body in enumerate(b for b in blocks if "bpy" in b):
            found.append((f"{page.relative_to(ROOT)}#{i + 1}", body))
    return found


BLOCKS = _blocks()

_STAGE = """
import bpy
for name in {objects!r}:
    bpy.ops.mesh.primitive_plane_add(size=0.2)
    bpy.context.active_object.name = name
for name in {images!r}:
    bpy.data.images.new(name, 64, 64)
bpy.ops.object.select_all(action="DESELECT")
"""

_INSTALL = """
import bpy
assert bpy.ops.extensions.package_install_files(
    filepath={zip!r}, repo="user_default", enable_on_install=True) == {{"FINISHED"}}
bpy.ops.wm.save_userpref()
"""
_READ_PREFERENCES = """
import bpy
bpy.ops.wm.read_userpref()
"""


def _run(code: str, folder: Path, user: Path, name: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, BLENDER_USER_RESOURCES=str(user))
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=folder, env=env,
        capture_output=True, text=True, check=False, timeout=600,
    )
    assert done.returncode == 0, f"{name}:\n{done.stdout[-2000:]}\n{done.stderr[-4000:]}"
    return done


def test_every_page_with_bpy_blocks_is_found() -> None:
    pages = {name.split("#")[0] for name, _ in BLOCKS}
    assert {"docs/blender.md", "docs/first-script.md"} <= pages, pages


@pytest.mark.parametrize(("name", "body"), BLOCKS, ids=[n for n, _ in BLOCKS])
def test_the_bpy_block_runs_as_written(name: str, body: str, tmp_path: Path) -> None:
    zip_path = str(_extension_zip().resolve())
    code = body.replace(PLACEHOLDER_ZIP, zip_path)
    user = Path(tempfile.mkdtemp(prefix="docs-", dir=tmp_path))
    prelude = ""
    if "package_install_files" not in body:
        _run(_INSTALL.format(zip=zip_path), tmp_path, user, f"installing for {name}")
        prelude = _READ_PREFERENCES
    objects = re.findall(r'bpy\.data\.objects\["([^"]+)"\]', body)
    images = re.findall(r'_image_name="([^"]+)"', body)
    _run(prelude + _STAGE.format(objects=objects, images=images) + "\n" + code, tmp_path, user,
         name)
    for png in re.findall(r'"([\w-]+\.png)"', body):
        assert (tmp_path / png).stat().st_size > 0, f"{name} wrote no {png}"


def test_the_tutorial_installs_once_then_renders(tmp_path: Path) -> None:
    """docs/first-script.md as a reader follows it: the install block in one run, the render
    block in a later one, sharing only the user folder the first names."""
    install, render = [b for n, b in BLOCKS if n.startswith("docs/first-script.md")][:2]
    user = tmp_path / "blender-user"  # the folder both blocks default to, in their own cwd
    zip_path = str(_extension_zip().resolve())
    _run(install.replace(PLACEHOLDER_ZIP, zip_path), tmp_path, user, "install")
    env = {k: v for k, v in os.environ.items() if k != "BLENDER_USER_RESOURCES"}
    done = subprocess.run(
        [sys.executable, "-c", render], cwd=tmp_path, env=env,
        capture_output=True, text=True, check=False, timeout=600,
    )
    assert done.returncode == 0, done.stderr[-4000:]
    assert "knitted Plane.knit" in done.stdout, done.stdout[-2000:]
    assert (tmp_path / "first-knit.png").stat().st_size > 0


def test_the_scripting_keywords_are_all_listed(addon: ModuleType) -> None:
    """docs/blender.md's list of `api.knit_object` keywords names every setting it takes."""
    from bl_ext.user_default.knitwear import properties

    text = (ROOT / "docs" / "blender.md").read_text()
    listed = text.split("- `api.knit_object(", 1)[1].split("\n- `api.update_knit", 1)[0]
    named = set(re.findall(r"`(\w+)`", listed)) | {
        f"color_{i}" for i in range(1, 5) if "`color_1` ... `color_4`" in listed
    }
    missing = sorted(set(properties.SETTING_NAMES) - named)
    assert not missing, f"docs/blender.md leaves out these api.knit_object keywords: {missing}"
