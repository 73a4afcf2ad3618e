"""World transforms the knit must reproduce exactly: a zero scale (a flat object), a shear
from a non-uniformly scaled parent, and a surface far from the world origin (issue 18)."""

import importlib
from types import ModuleType

import bpy
import numpy as np
from blender_scenes import SMALL, positions
from mathutils import Matrix, Vector

#: A gauge, so that the stitch count follows the surface's size in the world.
BY_GAUGE = {"size_mode": "GAUGE", "gauge_stitches": 60.0, "gauge_rows": 80.0,
            "ring_segments": 4, "samples_per_loop": 8}


def _plane(size: float = 0.2) -> bpy.types.Object:
    bpy.ops.mesh.primitive_plane_add(size=size)
    return bpy.context.active_object


def _world(obj: bpy.types.Object) -> np.ndarray:
    """``obj``'s vertices in world space, float64."""
    local = positions(obj.data).astype(np.float64)
    m = np.array(obj.matrix_world, dtype=np.float64)
    return local @ m[:3, :3].T + m[:3, 3]


def test_a_plane_scaled_to_zero_along_its_normal_knits_as_the_flat_plane_it_is(
    api: ModuleType,
) -> None:
    """Scale z = 0 used to give NaN normals ("normal of vertex 0 is NaN"); a plane in xy is
    the same surface at any z scale."""
    flat, upright = _plane(), _plane()
    flat.scale = (1.5, 0.5, 0.0)
    upright.scale = (1.5, 0.5, 1.0)
    bpy.context.view_layer.update()
    a = api.knit(flat, **SMALL)
    b = api.knit(upright, **SMALL)
    assert a.stitches == b.stitches > 0
    got = positions(a.object.data)
    assert np.isfinite(got).all()
    np.testing.assert_array_equal(got, positions(b.object.data))
    np.testing.assert_allclose(np.array(a.object.matrix_world), np.eye(4), atol=0)
    # The yarn stands on both sides of the plane, as it does on an unscaled one.
    assert got[:, 2].min() < 0 < got[:, 2].max()


def test_an_object_scaled_to_zero_along_two_axes_is_refused(api: ModuleType) -> None:
    import knitwear

    line = _plane()
    line.scale = (1.0, 0.0, 0.0)
    bpy.context.view_layer.update()
    objects = len(bpy.data.objects)
    try:
        api.knit(line, **SMALL)
    except knitwear.SurfaceError as err:
        assert "scaled to zero along two axes" in str(err)
    else:
        raise AssertionError("a line was knitted")
    assert len(bpy.data.objects) == objects


def test_a_sheared_parent_knits_as_the_surface_with_its_transform_applied(
    api: ModuleType,
) -> None:
    """A mesh turned 45 degrees under a parent scaled (1, 3, 1) is a sheared parallelogram in
    the world: it used to get the parent's scale along its own axes (the wrong place, five
    times the stitches). It must knit as the same mesh with its world transform applied."""
    parent = bpy.data.objects.new("Parent", None)
    bpy.context.scene.collection.objects.link(parent)
    parent.scale = (1.0, 3.0, 1.0)
    parent.location = (0.3, -0.2, 0.1)
    child = _plane()
    child.parent = parent
    child.rotation_euler = (0.0, 0.0, np.pi / 4)
    bpy.context.view_layer.update()
    applied = _plane()
    applied.data = child.data.copy()
    applied.data.transform(child.matrix_world)
    bpy.context.view_layer.update()

    sheared = api.knit(child, **BY_GAUGE)
    reference = api.knit(applied, **BY_GAUGE)
    assert sheared.stitches == reference.stitches
    a, b = _world(sheared.object), _world(reference.object)
    assert a.shape == b.shape
    # The same yarn in the world, up to float32 rounding of the two frames.
    np.testing.assert_allclose(a, b, atol=2e-5)
    # And on the surface: inside the applied plane's world bounding box, give or take a yarn.
    corners = _world(applied)
    reach = 2 * float(np.abs(positions(reference.object.data)[:, 2]).max())
    assert (a >= corners.min(axis=0) - reach).all() and (a <= corners.max(axis=0) + reach).all()


#: A plane whose corners (+-12.5 cm) float32 holds exactly at 1e4 and 1e6 too, so that the
#: far sources are the same surface as the near one.
EXACT_SIZE = 0.25


def _far_plane(offset: float) -> bpy.types.Object:
    """The `EXACT_SIZE` plane with its mesh data ``offset`` along x from its object's
    origin."""
    plane = _plane(EXACT_SIZE)
    plane.data.transform(Matrix.Translation((offset, 0.0, 0.0)))
    bpy.context.view_layer.update()
    return plane


def test_a_surface_far_from_the_origin_is_as_precise_as_one_at_it(
    api: ModuleType, capsys: object
) -> None:
    """At 1e4 the knit had 54 distinct x values for 40k vertices (float32 steps of 1 mm);
    knitted about the surface's centre it is the knit at the origin, moved."""
    settings = SMALL | {"courses": 40, "wales": 40}
    near = api.knit(_plane(EXACT_SIZE), **settings)
    expected = positions(near.object.data)
    follow = importlib.import_module(f"{api.__package__}.follow")
    for offset in (1e4, 1e6):
        far = api.knit(_far_plane(offset), **settings)
        got = positions(far.object.data)
        np.testing.assert_array_equal(got, expected)
        assert len(np.unique(got[:, 0])) == len(np.unique(expected[:, 0])) > 1000
        np.testing.assert_array_equal(
            np.array(far.object.matrix_world.translation), (offset, 0.0, 0.0)
        )
        # It still follows its source: moved up 1 cm by its object, the yarn moves with it.
        source = far.object.knitwear.source
        source.location.z = 0.01
        bpy.context.view_layer.update()
        follow.follow(far.object)
        np.testing.assert_array_equal(positions(far.object.data), expected)
        assert far.object.matrix_world.translation == Vector((offset, 0.0, 0.01))
    assert "Knitwear" not in capsys.readouterr().out
