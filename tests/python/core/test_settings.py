"""One source per setting: the core's settings table (`knitwear.settings()`, declared in
`src/settings.rs`) is what the pyo3 signatures, the `.pyi` stub and the core's range checks
say. These fail when a default or a range is changed in one place and not the others."""

import ast
import importlib.util
import inspect
from pathlib import Path
from typing import Any

import knitwear
import numpy as np
import pytest

STUB = Path(__file__).resolve().parents[3] / "python" / "knitwear" / "_core.pyi"

SETTINGS = knitwear.settings()
KEYWORDED = [s for s in SETTINGS if s["core_keyword"] is not None]
PLUSH = knitwear.settings("plush")
PLUSH_KEYWORDED = [s for s in PLUSH if s["core_keyword"] is not None]


def _stub_defaults(owner: str, function: str) -> dict[str, Any]:
    """Keyword defaults of ``owner.function`` (or module-level ``function``) in the stub."""
    tree = ast.parse(STUB.read_text())
    scope: list[ast.stmt] = tree.body
    if owner:
        scope = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == owner).body
    fn = next(n for n in scope if isinstance(n, ast.FunctionDef) and n.name == function)
    args = fn.args
    return {
        a.arg: ast.literal_eval(d)
        for a, d in zip(args.kwonlyargs, args.kw_defaults, strict=True)
        if d is not None
    }


def _same(a: Any, b: Any) -> bool:
    return type(a) is type(b) and a == b


@pytest.mark.parametrize("table", [SETTINGS, PLUSH], ids=["knit", "plush"])
def test_each_table_is_whole(table: list[dict[str, Any]]) -> None:
    names = [s["property"] for s in table]
    assert len(names) == len(set(names))
    for s in table:
        assert s["label"] and s["doc"], s["name"]
        assert s["type"] in {"int", "float", "bool"}
        if s["addon_default"] != s["default"]:
            assert s["addon_why"], f"{s['name']}: the add-on's own default says why"
    with pytest.raises(knitwear.ParameterError, match="knit"):
        knitwear.settings("sweater")


def test_the_table_is_whole() -> None:
    names = [s["property"] for s in SETTINGS]
    assert len(names) == len(set(names))
    for s in SETTINGS:
        assert s["label"] and s["doc"], s["name"]
        assert s["type"] in {"int", "float", "bool"}
        if s["addon_default"] != s["default"]:
            assert s["addon_why"], f"{s['name']}: the add-on's own default says why"
    by_name = {s["name"]: s for s in SETTINGS}
    # The decisions the table records (issue "One source per setting").
    assert by_name["kappa"]["default"] == 0.0 and by_name["kappa"]["addon_default"] == 0.005
    assert by_name["hidden_supersampling"]["property"] == "cull_hidden_samples"


@pytest.mark.parametrize("callable_", [knitwear.Knit, knitwear.knit, knitwear.knit_texture])
def test_signatures_default_as_the_table_says(callable_: Any) -> None:
    params = inspect.signature(callable_).parameters
    checked = 0
    for s in KEYWORDED:
        if s["core_keyword"] not in params:
            assert callable_ is knitwear.knit_texture, s["name"]  # detail keywords
            continue
        got = params[s["core_keyword"]].default
        assert _same(got, s["default"]), f"{s['core_keyword']}: {got!r} != {s['default']!r}"
        checked += 1
    assert checked >= 9


@pytest.mark.parametrize(("owner", "function"), [("Knit", "__new__"), ("", "knit_texture")])
def test_the_stub_defaults_as_the_table_says(owner: str, function: str) -> None:
    defaults = _stub_defaults(owner, function)
    checked = 0
    for s in KEYWORDED:
        if s["core_keyword"] in defaults:
            got = defaults[s["core_keyword"]]
            assert _same(got, s["default"]), f"{s['core_keyword']}: {got!r} != {s['default']!r}"
            checked += 1
    assert checked >= 9


def test_the_plush_signature_and_stub_default_as_the_table_says() -> None:
    """`plush` spells some defaults and leaves the rest to the core (None); either way it is
    the table's default."""
    params = inspect.signature(knitwear.plush).parameters
    stub = _stub_defaults("", "plush")
    for s in PLUSH_KEYWORDED:
        for where, got in (("signature", params[s["core_keyword"]].default), ("stub", None)):
            if where == "stub":
                got = stub.get(s["core_keyword"])
            assert got is None or _same(got, s["default"]), f"{where} {s['name']}: {got!r}"
    assert params["slices"].default == 8 and params["piles_per_stitch"].default == 1


@pytest.mark.parametrize(
    "setting", [s for s in PLUSH_KEYWORDED if s["name"] not in {"seed"}], ids=lambda s: s["name"]
)
def test_the_plush_core_refuses_just_outside_the_declared_range(setting: dict[str, Any]) -> None:
    step = 1 if setting["type"] == "int" else 1e-3
    outside = [setting["min"] - step if setting["min"] != 0 else -step]
    if setting["max"] is not None:
        outside.append(setting["max"] + step)
    for value in outside:
        value = int(value) if setting["type"] == "int" else float(value)
        kwargs = {setting["core_keyword"]: value}
        if setting["name"] not in {"courses", "wales"}:
            kwargs |= {"courses": 2, "wales": 2}
        with pytest.raises((knitwear.ParameterError, OverflowError)):
            knitwear.plush(_sheet(), **kwargs)


def _sheet() -> knitwear.GridSurface:
    u, v = np.meshgrid(np.linspace(0, 0.02, 4), np.linspace(0, 0.02, 4))
    pos = np.stack([u, v, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1
    return knitwear.GridSurface(pos, nrm)


def _camera() -> knitwear.Camera:
    """An orthographic view straight down onto `_sheet` (any view will do: the range is
    checked before it is used)."""
    matrix = np.diag([50.0, 50.0, -1.0, 1.0]).astype(np.float32)
    return knitwear.Camera(matrix, np.array([0, 0, -1, 0], np.float32), (64, 64))


@pytest.mark.parametrize(
    "setting", [s for s in KEYWORDED if s["type"] != "bool" and s["name"] != "seed"]
)
def test_the_core_refuses_just_outside_the_declared_range(setting: dict[str, Any]) -> None:
    """Just past either end is a ParameterError naming the setting; the table's range is the
    one the core enforces."""
    pattern = knitwear.Pattern.preset("stockinette")
    step = 1 if setting["type"] == "int" else 1e-3
    outside = []
    if setting["min"] is not None:
        outside.append(setting["min"] - step if setting["min"] != 0 else -step)
    if setting["max"] is not None:
        outside.append(setting["max"] + step)
    assert outside, setting["name"]
    for value in outside:
        value = int(value) if setting["type"] == "int" else float(value)
        kwargs = {setting["core_keyword"]: value, "courses": 2, "wales": 2}
        if setting["name"] in {"courses", "wales"}:
            kwargs = {setting["core_keyword"]: value}
        error = (knitwear.ParameterError, OverflowError)
        # The detail settings are used only with a camera, and refused out of range with or
        # without one (issue 22: 17 visibility samples passed where no camera was given).
        detail = {"hidden_supersampling", "frustum_margin", "cull_hidden_min_triangles"}
        for extra in [{}, {"camera": _camera()}] if setting["name"] in detail else [{}]:
            with pytest.raises(error) as raised:
                knitwear.Knit(_sheet(), pattern, **kwargs, **extra)
            if isinstance(raised.value, knitwear.ParameterError):
                assert setting["name"] in str(raised.value) or setting["core_keyword"] in str(
                    raised.value
                ), str(raised.value)


def test_the_settings_reference_is_current() -> None:
    spec = importlib.util.spec_from_file_location(
        "settings_table", STUB.parents[2] / "scripts" / "settings_table.py"
    )
    assert spec and spec.loader
    table = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(table)
    readme = table.PAGE.read_text()
    assert table.updated(readme) == readme, "run scripts/settings_table.py"
    for s in SETTINGS + PLUSH:
        assert s["doc"] in readme, s["name"]


def test_knits_help_gives_every_settings_meaning_default_and_range() -> None:
    """`help(knitwear.knit)` is a reference: each setting's doc, default and range with its
    unit, from the same functions that write docs/settings.md."""
    from knitwear import settings_text

    doc = " ".join((knitwear.knit.__doc__ or "").split())
    for s in SETTINGS:
        assert " ".join(s["doc"].split()) in doc, s["name"]
        said = f"Default {settings_text.default(s)}; {settings_text.value_range(s)}."
        assert " ".join(said.split()) in doc, s["name"]
    assert list(inspect.signature(knitwear.knit).parameters) == list(
        inspect.signature(knitwear.Knit).parameters
    )
