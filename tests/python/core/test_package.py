"""The extension zip holds what its manifest promises (docs/install.md): the wheels the
manifest lists, the very wheel the tests ran, and exactly the platforms those wheels run on,
with the README's Install section and docs/install.md saying which."""

from __future__ import annotations

import re
import tomllib
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
MANIFEST = ROOT / "blender_addon" / "blender_manifest.toml"

#: Blender's platform names and the wheel platform tags that serve them.
PLATFORM_TAGS = {
    "linux-x64": r"(manylinux|musllinux)_\d+_\d+_x86_64|manylinux\d+_x86_64",
    "linux-arm64": r"(manylinux|musllinux)_\d+_\d+_aarch64|manylinux\d+_aarch64",
    "windows-x64": r"win_amd64",
    "windows-arm64": r"win_arm64",
    "macos-x64": r"macosx_\d+_\d+_(x86_64|universal2)",
    "macos-arm64": r"macosx_\d+_\d+_(arm64|universal2)",
}


def platforms_of(wheel: str) -> set[str]:
    """The Blender platforms a wheel file name's platform tag serves."""
    tag = wheel.removesuffix(".whl").split("-")[-1]
    return {p for p, pattern in PLATFORM_TAGS.items()
            if any(re.fullmatch(pattern, t) for t in tag.split("."))}


def test_platform_tags_are_read_as_blender_names_them() -> None:
    assert platforms_of("k-0.1.0-cp311-abi3-manylinux_2_34_x86_64.whl") == {"linux-x64"}
    assert platforms_of("k-0.1.0-cp311-abi3-manylinux_2_28_aarch64.whl") == {"linux-arm64"}
    assert platforms_of("k-0.1.0-cp311-abi3-win_amd64.whl") == {"windows-x64"}
    assert platforms_of("k-0.1.0-cp311-abi3-macosx_11_0_arm64.whl") == {"macos-arm64"}
    assert platforms_of("k-0.1.0-cp311-abi3-macosx_10_12_universal2.whl") == {
        "macos-x64", "macos-arm64"}
    assert platforms_of("k-0.1.0-cp311-abi3-any.whl") == set()


@pytest.fixture(scope="module")
def manifest() -> dict:
    with MANIFEST.open("rb") as f:
        return tomllib.load(f)


def test_the_manifest_lists_exactly_the_platforms_of_its_wheels(manifest: dict) -> None:
    wheels = [Path(w).name for w in manifest["wheels"]]
    served: set[str] = set()
    for w in wheels:
        # One abi3 wheel serves every CPython from 3.11, Blender 4.2's Python, on.
        assert "-cp311-abi3-" in w, w
        assert platforms_of(w), f"{w}: no platform Blender knows"
        served |= platforms_of(w)
    assert served == set(manifest["platforms"]), (wheels, manifest["platforms"])
    assert manifest["blender_version_min"] == "4.2.0"


def test_the_zip_holds_the_manifest_and_the_wheel_the_tests_ran(manifest: dict) -> None:
    """`dist/` holds the zip `scripts/bootstrap.sh` built from this manifest, bundling the
    wheel it built into `build/wheels` (the one unpacked into `build/site` for these tests)."""
    zips = sorted((ROOT / "dist").glob(f"knitwear-{manifest['version']}.zip"))
    assert len(zips) == 1, zips
    built = sorted((ROOT / "build" / "wheels").glob("knitwear-*.whl"))
    assert len(built) == 1, built
    with zipfile.ZipFile(zips[0]) as z:
        assert z.read("blender_manifest.toml") == MANIFEST.read_bytes()
        inside = sorted(n for n in z.namelist() if n.endswith(".whl"))
        assert inside == sorted(w.removeprefix("./") for w in manifest["wheels"])
        assert z.read(f"wheels/{built[0].name}") == built[0].read_bytes()


def test_the_docs_name_the_platforms_and_the_glibc(manifest: dict) -> None:
    readme = (ROOT / "README.md").read_text()
    install = readme.split("## Install", 1)[1].split("\n## ", 1)[0]
    page = (ROOT / "docs" / "install.md").read_text()
    for platform in manifest["platforms"]:
        assert f"`{platform}`" in page, platform
    for wheel in manifest["wheels"]:
        glibc = re.search(r"manylinux_(\d+)_(\d+)_", wheel)
        if glibc:
            assert f"glibc {glibc[1]}.{glibc[2]}" in page, wheel
            assert f"glibc {glibc[1]}.{glibc[2]}" in install, wheel
