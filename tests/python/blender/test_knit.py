"""Knitting NURBS surfaces and UV-mapped meshes through the operator and the scripting API."""

from collections.abc import Callable
from types import ModuleType

import bpy
import numpy as np
import pytest
from blender_scenes import (
    SMALL,
    SOURCES,
    colors,
    corner_verts,
    data_counts,
    nurbs_patch,
    nurbs_sphere,
    positions,
    snapshot,
)


def knit_with_operator(**settings: object) -> bpy.types.Object:
    assert bpy.ops.object.knitwear_knit(**settings) == {"FINISHED"}
    return bpy.context.active_object


@pytest.mark.parametrize("make_source", SOURCES.values(), ids=SOURCES.keys())
def test_operator_builds_exactly_the_core_result(
    make_source: Callable[[], bpy.types.Object], api: ModuleType
) -> None:
    source = make_source()
    before = snapshot(source)
    counts = data_counts()
    expected = api.knit_result(source, **SMALL)  # the core's output, nothing built
    assert data_counts() == counts, "sampling left temporary data behind"

    knit = knit_with_operator(**SMALL)

    assert knit is not source
    assert knit.name == f"{source.name}.knit"
    assert knit.knitwear.is_knit and knit.knitwear.source == source
    assert knit.users_collection[0] == source.users_collection[0]
    assert knit.matrix_world == source.matrix_world
    mesh = knit.data
    assert (len(mesh.vertices), len(mesh.polygons)) == (
        len(expected.vertices),
        len(expected.triangles),
    )
    assert len(mesh.polygons) > 0
    np.testing.assert_array_equal(positions(mesh), expected.vertices)
    np.testing.assert_array_equal(corner_verts(mesh), expected.triangles.ravel())
    col = colors(mesh)
    assert col.shape == (len(mesh.vertices), 4)
    np.testing.assert_array_equal(col, expected.colors)
    assert mesh.color_attributes.active_color.name == "Col"
    assert mesh.attributes.default_color_name == "Col"
    assert [m.name for m in mesh.materials] == ["Knitwear Yarn"]

    assert snapshot(source) == before
    grown = {"objects": 1, "meshes": 1, "materials": 1}
    assert data_counts() == {k: v + grown.get(k, 0) for k, v in counts.items()}


def test_operator_and_api_agree(api: ModuleType) -> None:
    source = nurbs_patch()
    settings = SMALL | {"pattern": "rib_2x2", "color_mode": "STRIPES", "seed": 7}
    by_operator = knit_with_operator(**settings)
    by_api = api.knit_object(source, **settings)
    assert by_api is not by_operator
    np.testing.assert_array_equal(positions(by_api.data), positions(by_operator.data))
    np.testing.assert_array_equal(corner_verts(by_api.data), corner_verts(by_operator.data))
    np.testing.assert_array_equal(colors(by_api.data), colors(by_operator.data))
    # Both store what they were given, which is what the redo panel and Update edit.
    assert api.settings_from(by_api) == api.settings_from(by_operator)
    assert by_operator.knitwear.pattern == "rib_2x2"
    assert by_operator.knitwear.seed == 7


def test_live_loops_reach_the_core(api: ModuleType) -> None:
    """Live Loops (off: the knit is finished with a cast-on and a bind-off) reaches the core:
    the patch, open in v, loses exactly its two edge pieces and keeps the same fabric."""
    source = nurbs_patch()
    finished = api.knit_result(source, **SMALL)
    live = api.knit_result(source, **(SMALL | {"live_loops": True}))
    assert finished.stats["yarn_pieces"] == live.stats["yarn_pieces"] + 2
    n = len(live.centerline_points)
    np.testing.assert_array_equal(finished.centerline_points[:n], live.centerline_points)
    knit = knit_with_operator(**(SMALL | {"live_loops": True}))
    assert knit.knitwear.live_loops is True
    assert len(knit.data.vertices) == len(live.vertices)


def test_material_is_shared(api: ModuleType) -> None:
    a = api.knit_object(nurbs_patch(), **SMALL)
    b = api.knit_object(nurbs_sphere(), **SMALL)
    assert a.data.materials[0] is b.data.materials[0]
    assert len([m for m in bpy.data.materials if m.name.startswith("Knitwear Yarn")]) == 1


def test_mesh_is_valid(api: ModuleType) -> None:
    knit = api.knit_object(nurbs_sphere(), **SMALL)
    assert knit.data.validate(verbose=True) is False, "validate() had something to fix"


def test_classic_mesh_route_gives_the_same_mesh(
    api: ModuleType, addon: ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    source = nurbs_patch()
    fast = api.knit_object(source, **SMALL)

    def missing_internal_names(*_args: object) -> None:
        raise KeyError(".corner_vert")

    monkeypatch.setattr(addon.mesh_build, "_fill_fast", missing_internal_names)
    classic = api.knit_object(source, **SMALL)
    np.testing.assert_array_equal(positions(classic.data), positions(fast.data))
    np.testing.assert_array_equal(corner_verts(classic.data), corner_verts(fast.data))
    np.testing.assert_array_equal(colors(classic.data), colors(fast.data))
    assert len(classic.data.edges) == len(fast.data.edges)
    assert classic.data.validate(verbose=True) is False


def test_update_rebuilds_in_place(api: ModuleType) -> None:
    source = nurbs_patch()
    knit = knit_with_operator(**SMALL)
    mesh_name = knit.data.name
    triangles_before = len(knit.data.polygons)

    knit.knitwear.courses = 2 * SMALL["courses"]
    assert bpy.ops.object.knitwear_update() == {"FINISHED"}
    expected = api.knit_result(source, **api.settings_from(knit))
    assert knit.data.name == mesh_name and data_counts()["meshes"] == 1
    assert len(knit.data.polygons) == len(expected.triangles) > triangles_before
    np.testing.assert_array_equal(positions(knit.data), expected.vertices)

    api.update_knit(knit, pattern="seed", color_mode="STRIPES")
    assert knit.knitwear.pattern == "seed"
    np.testing.assert_array_equal(
        positions(knit.data), api.knit_result(source, **api.settings_from(knit)).vertices
    )


def test_update_rewrites_in_place_when_only_colours_change(api: ModuleType) -> None:
    source = nurbs_patch()
    knit = api.knit_object(source, **SMALL)
    mesh = knit.data
    other_user = bpy.data.objects.new("Instance", mesh)
    bpy.context.scene.collection.objects.link(other_user)

    api.update_knit(knit, seed=7, color_mode="STRIPES", fluffiness=1.0)
    assert knit.data == mesh, "same topology: the mesh datablock is rewritten in place"
    expected = api.knit_result(source, **api.settings_from(knit))
    np.testing.assert_array_equal(positions(mesh), expected.vertices)
    np.testing.assert_array_equal(colors(mesh), expected.colors)
    np.testing.assert_array_equal(corner_verts(mesh), expected.triangles.ravel())

    # A new stitch count changes the topology: a new mesh takes the old one's place for every
    # user, keeping its name and material.
    name, material = mesh.name, mesh.materials[0]
    api.update_knit(knit, courses=SMALL["courses"] + 3)
    assert other_user.data == knit.data and knit.data.name == name
    assert list(knit.data.materials) == [material]
    expected = api.knit_result(source, **api.settings_from(knit))
    np.testing.assert_array_equal(positions(knit.data), expected.vertices)
    np.testing.assert_array_equal(corner_verts(knit.data), expected.triangles.ravel())
    assert knit.data.validate(verbose=True) is False
    assert data_counts()["meshes"] == 1


def test_update_follows_the_source(api: ModuleType) -> None:
    source = nurbs_patch()
    knit = api.knit_object(source, **SMALL)
    source.location = (1.0, 2.0, 3.0)
    source.rotation_euler = (0.0, 0.0, 0.5)
    bpy.context.view_layer.update()
    api.update_knit(knit)
    assert knit.matrix_world == source.matrix_world


def test_scale_is_baked_so_yarn_stays_round(api: ModuleType) -> None:
    plain = nurbs_patch()
    scaled = nurbs_patch()
    scaled.scale = (2.0, 1.0, 1.0)
    scaled.location = (3.0, 0.0, 0.0)
    bpy.context.view_layer.update()
    settings = SMALL | {"yarn_radius": 0.01}
    a = api.knit_object(plain, **settings)
    b = api.knit_object(scaled, **settings)
    # The knit sits on the source (same location and rotation) at unit scale...
    assert tuple(b.matrix_world.to_scale()) == pytest.approx((1.0, 1.0, 1.0))
    assert tuple(b.matrix_world.translation) == pytest.approx(tuple(scaled.location))
    # ... and its mesh carries the scale: twice as long along the patch's x only.
    ext_a = np.ptp(positions(a.data), axis=0)
    ext_b = np.ptp(positions(b.data), axis=0)
    assert ext_b[0] / ext_a[0] == pytest.approx(2.0, rel=0.05)
    assert ext_b[1] / ext_a[1] == pytest.approx(1.0, rel=0.05)


def test_gauge_is_in_real_units(api: ModuleType, core: ModuleType) -> None:
    """20 stitches per 10 cm on a 5 cm patch is about 10 stitches across, whatever the unit
    scale: a 0.05-unit patch in metres, or a 0.1-unit patch with 1 unit = 0.5 m."""
    gauge = {"size_mode": "GAUGE", "gauge_stitches": 20.0, "gauge_rows": 28.0}
    small = nurbs_patch()
    small.scale = (0.05, 0.05, 0.05)
    bpy.context.view_layer.update()
    in_metres = api.knit(small, **(SMALL | gauge))

    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.context.scene.unit_settings.scale_length = 0.5
    larger = nurbs_patch()
    larger.scale = (0.1, 0.1, 0.1)
    bpy.context.view_layer.update()
    in_half_metres = api.knit(larger, **(SMALL | gauge))

    assert in_metres.stitches == in_half_metres.stitches
    # The dome is a little longer than 5 cm each way: 10-13 wales, 14-18 courses.
    assert 10 * 14 <= in_metres.stitches <= 13 * 18


def test_image_colours(api: ModuleType) -> None:
    image = bpy.data.images.new("halves", 8, 8)
    pixels = np.zeros((8, 8, 4), dtype=np.float32)
    pixels[..., 3] = 1.0
    pixels[:, :4, 0] = 1.0  # left half red
    pixels[:, 4:, 1] = 1.0  # right half green
    image.pixels.foreach_set(pixels.ravel())
    knit = api.knit_object(
        nurbs_patch(),
        **SMALL,
        color_mode="IMAGE",
        color_image_name=image.name,
        color_variation=0.0,
    )
    col = colors(knit.data)
    red = np.mean(col[:, 0] > 2 * col[:, 1])
    green = np.mean(col[:, 1] > 2 * col[:, 0])
    assert red > 0.2 and green > 0.2, (red, green)
    assert red + green > 0.95


def test_poll(api: ModuleType) -> None:
    bpy.ops.object.camera_add()
    assert not bpy.ops.object.knitwear_knit.poll()
    assert not bpy.ops.object.knitwear_update.poll()
    source = nurbs_patch()
    assert bpy.ops.object.knitwear_knit.poll()
    bpy.ops.object.mode_set(mode="EDIT")
    assert not bpy.ops.object.knitwear_knit.poll(), "knitting needs Object Mode"
    bpy.ops.object.mode_set(mode="OBJECT")
    knit = api.knit_object(source, **SMALL)
    bpy.context.view_layer.objects.active = knit
    assert not bpy.ops.object.knitwear_knit.poll(), "a knit is not a source"
    assert bpy.ops.object.knitwear_update.poll()


def test_knitspeak_in_the_chart_field_knits_like_the_preset(api: ModuleType) -> None:
    source = nurbs_patch()
    preset = api.knit_result(source, **SMALL, pattern="rib_2x2")
    # The first stitch of a row sits at the right edge: "p2, k2" charts as kkpp.
    text = "Rnd 1: *P2, k2; rep from *."
    written = api.knit_result(source, **SMALL, pattern="CUSTOM", pattern_chart=text)
    np.testing.assert_array_equal(written.vertices, preset.vertices)
    import knitwear

    with pytest.raises(knitwear.PatternError, match="c4q"):
        api.knit_result(source, **SMALL, pattern="CUSTOM", pattern_chart="Row 1: k2, c4q.")
