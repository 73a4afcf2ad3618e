"""Every failure a user can cause is an ERROR report (operator) or a `knitwear.KnitError`
(API), and leaves the blend file exactly as it was."""

import math
from collections.abc import Callable
from types import ModuleType
from typing import Any

import bpy
import pytest
from blender_scenes import SMALL, data_counts, mesh_without_uvs, nurbs_patch, snapshot, uv_mesh


def nan_vertex_mesh() -> bpy.types.Object:
    obj = uv_mesh()
    obj.data.vertices[3].co = (math.nan, 0.0, 0.0)
    obj.data.update()
    return obj


def cube_whose_uv_maps_were_removed() -> bpy.types.Object:
    """A cube whose UV maps a script removed (`uv_layers.remove` tags nothing, so the
    evaluated cube still had its map, and was knitted over it). Only Blender's internal
    UV selection attributes are left."""
    bpy.ops.mesh.primitive_cube_add(size=0.2)
    obj = bpy.context.active_object
    bpy.context.view_layer.update()
    while obj.data.uv_layers:
        obj.data.uv_layers.remove(obj.data.uv_layers[0])
    assert any(a.name.startswith(".uv_select") for a in obj.data.attributes)
    return obj


def nurbs_patch_500_m() -> bpy.types.Object:
    """Blender's NURBS patch scaled to about 500 m: at a knitting gauge, some 10^10 stitches,
    refused before the surface is sampled densely for them."""
    obj = nurbs_patch()
    obj.scale = (500.0, 500.0, 500.0)
    bpy.context.view_layer.update()
    return obj


def default_cube() -> bpy.types.Object:
    """Blender's 2 m default cube: a new user's first try, 2.7 million stitches at a real
    gauge. The refusal must say why: the gauge is real and the cube is 2 m."""
    bpy.ops.mesh.primitive_cube_add(size=2.0)
    return bpy.context.active_object


# (source, settings, core error class name, words the message must contain)
CASES: dict[str, tuple[Callable[[], bpy.types.Object], dict[str, Any], str, str]] = {
    "no uv map": (mesh_without_uvs, SMALL, "SurfaceError", "UV map"),
    "uv maps removed": (cube_whose_uv_maps_were_removed, SMALL, "SurfaceError", "has no UV map"),
    "nan vertex": (nan_vertex_mesh, SMALL, "SurfaceError", ""),
    "absurd stitch count": (
        uv_mesh,
        SMALL | {"courses": 10**6, "wales": 10**6},
        "BudgetError",
        "",
    ),
    "absurd count on a surface": (
        nurbs_patch,
        SMALL | {"courses": 10**6, "wales": 10**6},
        "BudgetError",
        "",
    ),
    "the default cube at the default gauge": (
        default_cube,
        {"size_mode": "GAUGE"},
        "BudgetError",
        "knits at a real gauge (20 stitches per 10 cm) and 'Cube' measures 2 x 2 x 2 m",
    ),
    "a 500 m surface at a knitting gauge": (
        nurbs_patch_500_m,
        SMALL | {"size_mode": "GAUGE"},
        "BudgetError",
        "stitches would need",
    ),
    "broken chart": (
        nurbs_patch,
        SMALL | {"pattern": "CUSTOM", "pattern_chart": "kkpp;kkxp"},
        "PatternError",
        "column 3",
    ),
    "broken colour chart": (
        nurbs_patch,
        SMALL | {"color_mode": "CHART", "color_chart": "01;0z"},
        "PatternError",
        "",
    ),
    "missing image": (
        nurbs_patch,
        SMALL | {"color_mode": "IMAGE", "color_image_name": "no such image"},
        "ParameterError",
        "no such image",
    ),
}


def _blend_state(source: bpy.types.Object) -> tuple[dict[str, int], dict[str, Any], str]:
    return data_counts(), snapshot(source), bpy.context.active_object.name


@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_operator_reports_error_and_changes_nothing(
    case: tuple[Callable[[], bpy.types.Object], dict[str, Any], str, str],
) -> None:
    make_source, settings, _error, words = case
    source = make_source()
    before = _blend_state(source)
    # Headless, an ERROR report from an operator called from Python raises RuntimeError
    # carrying the report's message (the operator itself returned CANCELLED).
    with pytest.raises(RuntimeError, match="Error") as raised:
        bpy.ops.object.knitwear_knit(**settings)
    assert words in str(raised.value)
    assert _blend_state(source) == before


@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_api_raises_knit_error_and_changes_nothing(
    case: tuple[Callable[[], bpy.types.Object], dict[str, Any], str, str],
    api: ModuleType,
    core: ModuleType,
) -> None:
    make_source, settings, error, words = case
    source = make_source()
    before = _blend_state(source)
    with pytest.raises(getattr(core, error)) as raised:
        api.knit_object(source, **settings)
    assert isinstance(raised.value, core.KnitError)
    assert words in str(raised.value)
    assert _blend_state(source) == before


def test_failed_update_keeps_the_knit(api: ModuleType, core: ModuleType) -> None:
    knit = api.knit_object(nurbs_patch(), **SMALL)
    vertices = len(knit.data.vertices)
    with pytest.raises(core.PatternError):
        api.update_knit(knit, pattern="CUSTOM", pattern_chart="zz")
    assert len(knit.data.vertices) == vertices
    assert knit.knitwear.pattern == "stockinette", "failed settings must not be stored"


def test_update_without_source(api: ModuleType, core: ModuleType) -> None:
    source = nurbs_patch()
    knit = api.knit_object(source, **SMALL)
    bpy.data.objects.remove(source)
    bpy.context.view_layer.objects.active = knit
    with pytest.raises(RuntimeError, match="no source"):
        bpy.ops.object.knitwear_update()
    with pytest.raises(core.SurfaceError):
        api.update_knit(knit)


def test_unknown_setting_is_a_type_error(api: ModuleType) -> None:
    with pytest.raises(TypeError, match="colour_mode"):
        api.knit_object(nurbs_patch(), colour_mode="STRIPES")
