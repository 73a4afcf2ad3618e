"""The layer check (`scripts/check_layers.py`) passes on this tree and catches what it is
for: a module using one below it in `src/lib.rs`'s table, a file circle, an add-on circle,
and a module missing from the table."""

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[3]

LIB = """//! | stage | module | what |
//! |---|---|---|
//! | surface | [`surface`] | a |
//! | skeleton | [`skeleton`] | b |
pub mod surface;
pub mod skeleton;
"""


def _check_layers() -> ModuleType:
    spec = importlib.util.spec_from_file_location(
        "check_layers", ROOT / "scripts" / "check_layers.py"
    )
    assert spec and spec.loader
    module = importlib.util.module_from_spec(spec)
    sys.modules["check_layers"] = module
    spec.loader.exec_module(module)
    return module


def _tree(tmp: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        path = tmp / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return tmp


def test_this_tree_keeps_its_layers() -> None:
    assert _check_layers().check(ROOT) == []


def test_a_clean_tree_passes(tmp_path: Path) -> None:
    tree = {
        "src/lib.rs": LIB,
        "src/surface.rs": "pub struct S;\n",
        "src/skeleton/mod.rs": "mod a;\nmod b;\n",
        "src/skeleton/a.rs": "use crate::surface::S;\nuse super::b::B;\n",
        "src/skeleton/b.rs": "pub struct B; // crate::skeleton::a in a comment\n",
    }
    assert _check_layers().check(_tree(tmp_path, tree)) == []


def test_a_back_arrow_a_circle_and_a_missing_row_fail(tmp_path: Path) -> None:
    tree = _tree(
        tmp_path,
        {
            "src/lib.rs": LIB + "pub mod extra;\n",
            "src/extra.rs": "\n",
            "src/surface.rs": "use crate::skeleton::a::A;\n",
            "src/skeleton/mod.rs": "mod a;\nmod b;\n",
            "src/skeleton/a.rs": "use super::b::B;\npub struct A;\n",
            "src/skeleton/b.rs": "use super::{a::A};\npub struct B;\n",
            "blender_addon/api.py": "from . import texture\n",
            "blender_addon/texture.py": "from .api import knit\n",
        },
    )
    problems = "\n".join(_check_layers().check(tree))
    assert "`surface` uses `skeleton`" in problems
    assert "circle in src/: skeleton::a, skeleton::b" in problems
    assert "circle in blender_addon/: api, texture" in problems
    assert "declares `extra` but its layer table has no row" in problems
