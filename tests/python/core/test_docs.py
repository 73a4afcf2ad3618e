"""The docs stay true: every link in the README, the changelog and the manual (`docs/`) reaches
a file of this repository (and a heading, where it names one), every repository path they name
in backticks exists, the README stays short enough to read first, the `stats` page lists
exactly the keys a real knit and a real plush return, and every Python block without `bpy`
runs as written (the blocks with `bpy` run in headless Blender: tests/python/blender/test_docs.py).
"""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import knitwear
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[3]
PAGES = sorted([ROOT / "README.md", ROOT / "CHANGELOG.md", *(ROOT / "docs").glob("*.md")])
#: The README is the front page: what it is, versions, install and two quick starts. The rest
#: belongs in the manual.
README_MAX_BYTES = 8 * 1024
#: Top-level folders whose paths the docs name in backticks; `../shared` is outside the
#: repository, so naming it points a reader at a file they do not have.
PATH_ROOTS = ("src/", "scripts/", "tests/", "docs/", "examples/", "benchmarks/",
              "blender_addon/", "python/", ".ci/", "../shared")

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
CODE_SPAN = re.compile(r"`([^`\n]+)`")
BLOCK = re.compile(r"^```([^\n]*)\n(.*?)^```", re.S | re.M)


def _name(page: Path) -> str:
    return str(page.relative_to(ROOT))


def slug(heading: str) -> str:
    """The anchor GitHub gives a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = heading.strip().lower().replace("`", "")
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(page: Path) -> set[str]:
    text = BLOCK.sub("", page.read_text())
    return {slug(m[1]) for m in re.finditer(r"^#+ (.+)$", text, re.M)}


def test_slugs_are_githubs() -> None:
    assert slug("Detail: model what the camera sees") == "detail-model-what-the-camera-sees"
    assert slug("The `stats` keys") == "the-stats-keys"
    assert slug("Plush (warp-knit pile)") == "plush-warp-knit-pile"


@pytest.mark.parametrize("page", PAGES, ids=_name)
def test_every_link_reaches_a_file_and_heading(page: Path) -> None:
    broken = []
    for target in LINK.findall(BLOCK.sub("", page.read_text())):
        if re.match(r"[a-z]+:", target):
            continue  # an address on the web, not a file here
        path, _, anchor = target.partition("#")
        dest = (page.parent / path).resolve() if path else page
        if not dest.exists():
            broken.append(f"{target}: no such file")
        elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
            broken.append(f"{target}: no heading #{anchor} in {dest.name}")
    assert not broken, f"{_name(page)}: " + "; ".join(broken)


@pytest.mark.parametrize("page", PAGES, ids=_name)
def test_every_repository_path_named_exists(page: Path) -> None:
    missing = []
    for span in CODE_SPAN.findall(page.read_text()):
        token = span.split()[0] if span.split() else ""
        if not token.startswith(PATH_ROOTS) or re.search(r"[*<>{}|$]|\.\.\.", token[2:]):
            continue
        path = re.split(r"[:#]", token.rstrip(".,;)"), maxsplit=1)[0]
        # `../shared` may exist beside a developer's clone, never in a reader's.
        if path.startswith("../") or not (ROOT / path).exists():
            missing.append(path)
    assert not missing, f"{_name(page)} names paths that are not in the repository: {missing}"


def test_the_readme_is_a_front_page() -> None:
    size = len((ROOT / "README.md").read_bytes())
    assert size <= README_MAX_BYTES, f"README.md is {size} bytes: move detail into docs/"


def _documented_keys(section: str) -> set[str]:
    keys: set[str] = set()
    for row in re.findall(r"^\| ((?:`\w+`(?:, )?)+) \|", section, re.M):
        keys.update(re.findall(r"`(\w+)`", row))
    return keys


def test_the_stats_page_lists_every_key() -> None:
    page = (ROOT / "docs" / "stats.md").read_text()
    knit_section, plush_section = page.split("\n## Knit", 1)[1].split("\n## Plush", 1)
    u, v = np.meshgrid(np.linspace(0, 1, 8), np.linspace(0, 1, 8))
    positions = np.stack([0.05 * u, 0.05 * v, np.zeros_like(u)], -1).astype(np.float32)
    normals = np.zeros_like(positions)
    normals[..., 2] = 1
    surface = knitwear.GridSurface(positions, normals)
    knit = knitwear.knit(surface, knitwear.Pattern.preset("stockinette"), measure_clearance=True)
    plush = knitwear.plush(surface, courses=8, wales=8)
    assert _documented_keys(knit_section) == set(knit.stats), "docs/stats.md, Knit"
    assert _documented_keys(plush_section) == set(plush.stats), "docs/stats.md, Plush"


def _python_blocks(page: Path) -> list[str]:
    return [body for lang, body in BLOCK.findall(page.read_text()) if lang == "python"]


BLENDER_FREE = [p for p in PAGES if any("bpy" not in b for b in _python_blocks(p))]


@pytest.mark.parametrize("page", BLENDER_FREE, ids=_name)
def test_the_python_blocks_run_as_written(page: Path, tmp_path: Path) -> None:
    """A page's blocks without `bpy` run in order, as one script, in a fresh Python with the
    core installed (build/site), in an empty folder: what a reader pasting them would get."""
    script = "\n\n".join(b for b in _python_blocks(page) if "bpy" not in b)
    env = dict(os.environ, PYTHONPATH=str(ROOT / "build" / "site"))
    run = subprocess.run(
        [sys.executable, "-c", script], cwd=tmp_path, env=env, capture_output=True, text=True,
        timeout=600,
    )
    assert run.returncode == 0, f"{_name(page)}:\n{run.stderr[-3000:]}"


def test_the_api_reference_is_current_and_whole() -> None:
    """docs/api.md is what scripts/api_reference.py makes of the stub today, and every public
    name in the stub has a docstring to show there."""
    spec = importlib.util.spec_from_file_location(
        "api_reference", ROOT / "scripts" / "api_reference.py"
    )
    assert spec and spec.loader
    reference = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(reference)
    page, missing = reference.render()
    assert not missing, f"no docstring in python/knitwear/_core.pyi for: {missing}"
    assert (ROOT / "docs" / "api.md").read_text() == page, "run scripts/api_reference.py"


def test_the_swatch_page_is_current_and_its_charts_knit_again() -> None:
    """docs/swatches.md is what scripts/swatch_page.py makes today, every swatch it shows is
    there, and every chart it prints reads back as the same pattern."""
    spec = importlib.util.spec_from_file_location(
        "swatch_page", ROOT / "scripts" / "swatch_page.py"
    )
    assert spec and spec.loader
    swatch_page = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(swatch_page)
    page = swatch_page.render()
    assert (ROOT / "docs" / "swatches.md").read_text() == page, "run scripts/swatch_page.py"
    charts = [body for info, body in BLOCK.findall(page) if info == "text"]
    assert len(charts) == len(knitwear.Pattern.presets())
    for name, chart in zip(knitwear.Pattern.presets(), charts, strict=True):
        again = knitwear.Pattern.from_chart(chart)
        assert again.chart() == knitwear.Pattern.preset(name).chart(), name
