"""Headless Blender (the PyPI `bpy` module) with the Knitwear extension installed as a user
installs it: the built zip, through Blender's own extension installer, into a throw-away
user-resources folder. `bpy` can be imported only once per process, so this happens once per
session; every test then starts from an empty scene.

The zip is `dist/knitwear-*.zip` (scripts/bootstrap.sh builds it); set KNITWEAR_EXTENSION_ZIP
to test another build.
"""

import importlib
import importlib.util
import os
import shutil
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parents[3]

# Must be set before `bpy` is imported: Blender reads it once, at start-up.
_USER_RESOURCES = Path(tempfile.mkdtemp(prefix="knitwear-blender-tests-"))
os.environ["BLENDER_USER_RESOURCES"] = str(_USER_RESOURCES)

import bpy  # noqa: E402  (after BLENDER_USER_RESOURCES, on purpose)
from blender_scenes import ADDON_MODULE  # noqa: E402  (imports bpy)


def _extension_zip() -> Path:
    override = os.environ.get("KNITWEAR_EXTENSION_ZIP")
    if override:
        return Path(override)
    zips = sorted((ROOT / "dist").glob("knitwear-*.zip"), key=lambda p: p.stat().st_mtime)
    if not zips:
        raise pytest.UsageError("no dist/knitwear-*.zip: run scripts/bootstrap.sh first")
    return zips[-1]


def _ensure_enabled() -> None:
    # Loading the home file keeps enabled add-ons, but a test that disabled it may have
    # failed half-way: put it back rather than let later tests fail for the wrong reason.
    if ADDON_MODULE not in bpy.context.preferences.addons:
        bpy.ops.preferences.addon_enable(module=ADDON_MODULE)


@pytest.fixture(scope="session")
def addon() -> Iterator[ModuleType]:
    """The installed, enabled add-on package (`bl_ext.user_default.knitwear`)."""
    assert importlib.util.find_spec("knitwear") is None, (
        "the knitwear core is importable before the extension is installed: the tests would "
        "not exercise the bundled wheel (is build/site on PYTHONPATH?)"
    )
    zip_path = _extension_zip()
    result = bpy.ops.extensions.package_install_files(
        filepath=str(zip_path), repo="user_default", enable_on_install=True
    )
    assert result == {"FINISHED"}, f"installing {zip_path} failed: {result}"
    assert ADDON_MODULE in bpy.context.preferences.addons
    yield importlib.import_module(ADDON_MODULE)
    shutil.rmtree(_USER_RESOURCES, ignore_errors=True)


@pytest.fixture(scope="session")
def core(addon: ModuleType) -> ModuleType:
    """The `knitwear` core, as the extension imports it: from its bundled wheel."""
    import knitwear

    site = _USER_RESOURCES / "extensions" / ".local"
    origin = Path(knitwear.__file__).resolve()
    assert origin.is_relative_to(site.resolve()), (
        f"knitwear was imported from {origin}, not from the extension's wheel under {site}"
    )
    assert sys.modules["knitwear"] is knitwear
    return knitwear


@pytest.fixture(scope="session")
def api(addon: ModuleType) -> ModuleType:
    return importlib.import_module(f"{ADDON_MODULE}.api")


@pytest.fixture(autouse=True)
def empty_scene(addon: ModuleType) -> Iterator[bpy.types.Context]:
    """Each test starts from an empty scene with the add-on enabled.

    `read_factory_settings` would also reset the preferences and with them the installed
    extension; `read_homefile(use_empty=True)` resets the data only (the user resources
    folder is empty, so the home file is the factory startup file).
    """
    bpy.ops.wm.read_homefile(use_empty=True)
    _ensure_enabled()
    yield bpy.context
    _ensure_enabled()
