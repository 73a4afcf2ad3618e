"""The map is true: the crate's modules use only the modules above them in `src/lib.rs`'s
layer table, no two source files of the crate or of the add-on import each other round a
circle, and every module of the crate has its row in the table.

`python scripts/check_layers.py` prints each offence and exits 1 if there is one (run by
`scripts/test.sh`). Doc-comment links (`[`crate::knit::KnitStats`]`) are not imports and are
left out: only code is read.
"""

import re
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

#: The binding layer sits on top of everything and is not part of the table.
BINDINGS = "python"


def table_order(src: Path) -> list[str]:
    """Modules in the order of `src/lib.rs`'s layer table, top (used by all) first."""
    order = []
    for line in (src / "lib.rs").read_text().splitlines():
        if line.startswith("//! |") and "[`" in line:
            order += re.findall(r"\[`(\w+)`\]", line.split("|")[2])
    return order


def declared_modules(src: Path) -> list[str]:
    text = (src / "lib.rs").read_text()
    return [m for m in re.findall(r"^pub mod (\w+);", text, re.M)]


def code_of(path: Path) -> str:
    """The file without comments (line comments and block comments; strings kept)."""
    text = re.sub(r"/\*.*?\*/", "", path.read_text(), flags=re.S)
    return "\n".join(line.split("//")[0] for line in text.splitlines())


def module_path(path: Path, src: Path) -> tuple[str, ...]:
    """`src/skeleton/contact.rs` -> ("skeleton", "contact"); `src/skeleton/mod.rs` ->
    ("skeleton",)."""
    parts = list(path.relative_to(src).with_suffix("").parts)
    if parts[-1] == "mod":
        parts.pop()
    return tuple(parts)


def rust_uses(
    path: Path, src: Path, files: dict[tuple[str, ...], Path]
) -> set[tuple[str, ...]]:
    """The crate's source files that `path`'s code names (`crate::a::b`, `super::c`)."""
    code = code_of(path)
    here = module_path(path, src)
    # A file's own module is its path; `super` of a mod.rs is its parent's parent.
    own = here if path.name != "mod.rs" and path.name != "lib.rs" else here + ("",)
    paths: list[list[str]] = []
    # Expand `use a::{b, c::d}` one level, which is all this crate uses.
    for prefix, group in re.findall(r"\b((?:crate|super)(?:::\w+)*)::\{([^}]*)\}", code):
        for item in group.split(","):
            item = item.strip()
            if item:
                paths.append(prefix.split("::") + item.split("::"))
    for m in re.findall(r"\b((?:crate|super)(?:::(?:super|\w+))+)", code):
        paths.append(m.split("::"))
    used = set()
    for p in paths:
        if p[0] == "crate":
            base: list[str] = []
            rest = p[1:]
        else:
            base = list(own[:-1])
            rest = p[1:]
            while rest and rest[0] == "super":
                base = base[:-1]
                rest = rest[1:]
        full = base + [x for x in rest if re.fullmatch(r"[a-z_][a-z0-9_]*", x)]
        # The longest prefix that is a file of the crate.
        for k in range(len(full), 0, -1):
            if tuple(full[:k]) in files:
                target = tuple(full[:k])
                if target != here:
                    used.add(target)
                break
    return used


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one node (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10_000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def addon_imports(addon: Path) -> dict[str, set[str]]:
    """The add-on's modules (dotted, relative to the add-on: ``plush.api``) and the modules
    of the add-on each imports (``from . import x``, ``from .x import y``, ``from .. import
    x`` in a subpackage). A package's ``__init__`` registers its modules and is left out."""
    modules = {
        ".".join(p.relative_to(addon).with_suffix("").parts): p
        for p in addon.rglob("*.py")
        if p.name != "__init__.py"
    }
    packages = {".".join(p.relative_to(addon).parts) for p in addon.rglob("*") if p.is_dir()}
    graph: dict[str, set[str]] = defaultdict(set)

    def resolve(base: list[str], name: str) -> str | None:
        dotted = ".".join([*base, name])
        return dotted if dotted in modules or dotted in packages else None

    for me, path in sorted(modules.items()):
        package = me.split(".")[:-1]
        graph.setdefault(me, set())
        for dots, rest, names in re.findall(
            r"^\s*from (\.+)([\w.]*) import \(?([\w, \n]+?)\)?(?:#.*)?$",
            path.read_text(),
            re.M,
        ):
            base = package[: len(package) - (len(dots) - 1)] if len(dots) > 1 else package
            if rest:
                target = resolve(base, rest)
                if target:
                    graph[me].add(target)
                continue
            for name in re.findall(r"\w+", names):
                target = resolve(base, name)
                if target and target != me:
                    graph[me].add(target)
    return graph


def check(root: Path) -> list[str]:
    """Every offence against the layer table and every import circle under ``root``."""
    src, addon = root / "src", root / "blender_addon"
    problems: list[str] = []
    order = table_order(src)
    declared = declared_modules(src)
    for m in declared:
        if m not in order:
            problems.append(f"src/lib.rs declares `{m}` but its layer table has no row for it")
    for m in order:
        if m not in declared:
            problems.append(f"src/lib.rs's layer table names `{m}`, which is not a module")
    rank = {m: i for i, m in enumerate(order)}

    files = {module_path(p, src): p for p in src.rglob("*.rs")}
    file_graph: dict[str, set[str]] = defaultdict(set)
    for mod, path in sorted(files.items()):
        if not mod or mod[0] == BINDINGS:
            continue
        for target in rust_uses(path, src, files):
            if not target or target[0] == BINDINGS:
                continue
            a, b = mod[0], target[0]
            if a != b and a in rank and b in rank and rank[b] >= rank[a]:
                problems.append(
                    f"{path.relative_to(root)}: `{a}` uses `{b}`, which is not above it in "
                    "src/lib.rs's layer table"
                )
            file_graph["::".join(mod)].add("::".join(target))
    for comp in cycles(file_graph):
        problems.append("an import circle in src/: " + ", ".join(comp))
    if addon.is_dir():
        for comp in cycles(addon_imports(addon)):
            problems.append("an import circle in blender_addon/: " + ", ".join(comp))
    return problems


def main() -> int:
    problems = check(ROOT)
    order = table_order(ROOT / "src")
    for p in problems:
        print(p)
    if not problems:
        print(f"layers: {len(order)} modules in order, no circles")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
