"""Knits follow their animated sources: same topology on every frame, no jitter under rigid
motion, frame N alone equals frame N in a sequence, and renders of animated knits."""

from pathlib import Path
from types import ModuleType

import bpy
import numpy as np
from blender_scenes import SMALL, corner_verts, nurbs_patch, positions
from PIL import Image


def waving_cloth() -> bpy.types.Object:
    """A UV-mapped 1 m cloth whose shape key (a sine wave) is keyed 0 at frame 1, 1 at 20."""
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=12, y_subdivisions=12, size=1.0)
    cloth = bpy.context.active_object
    cloth.shape_key_add(name="Basis")
    wave = cloth.shape_key_add(name="Wave")
    co = np.empty(3 * len(wave.data), np.float32)
    wave.data.foreach_get("co", co)
    co = co.reshape(-1, 3)
    co[:, 2] = 0.15 * np.sin(2 * np.pi * co[:, 0]) * (0.5 + co[:, 1])
    wave.data.foreach_set("co", co.ravel())
    for frame, value in ((1, 0.0), (20, 1.0)):
        wave.value = value
        wave.keyframe_insert("value", frame=frame)
    bpy.context.scene.frame_set(1)
    return cloth


def knit_of(api: ModuleType, source: bpy.types.Object) -> bpy.types.Object:
    return api.knit_object(source, **SMALL)


def test_the_knit_follows_a_shape_key_with_fixed_topology(api: ModuleType) -> None:
    scene = bpy.context.scene
    knit = knit_of(api, waving_cloth())
    at_rest = positions(knit.data)
    triangles = corner_verts(knit.data)
    topology = knit.data["knitwear_topology"]
    moved = []
    for frame in range(1, 51):
        scene.frame_set(frame)
        p = positions(knit.data)
        assert np.isfinite(p).all()
        np.testing.assert_array_equal(corner_verts(knit.data), triangles)
        assert knit.data["knitwear_topology"] == topology
        moved.append(np.abs(p - at_rest).max())
    assert moved[0] == 0.0, "frame 1 is the pose it was knitted in: nothing moves"
    assert max(moved) > 0.05, f"the yarn did not follow the wave (moved {max(moved):.3f} m)"
    scene.frame_set(1)
    np.testing.assert_array_equal(positions(knit.data), at_rest)


def test_a_knit_shades_with_its_yarns_own_normals_which_follow_it(api: ModuleType) -> None:
    """A knit carries the core's shading normals (the swept tube's) as custom normals, and
    Blender shades with them, not with the faceted normals of its fibre triangles. Each
    frame writes them with the positions, in the same pass: they are the core's for that
    pose and move with the yarn (and Blender skips its own recompute)."""
    scene = bpy.context.scene
    knit = knit_of(api, waving_cloth())
    mesh = knit.data
    assert mesh.attributes["custom_normal"].domain == "POINT"
    shaded = {}
    for frame in (5, 15):
        scene.frame_set(frame)
        ours = np.empty((len(mesh.vertices), 3), np.float32)
        mesh.vertex_normals.foreach_get("vector", ours.ravel())  # what Blender shades with
        sampled = api.sample_source(knit, bpy.context, bpy.context.evaluated_depsgraph_get())
        core = api.bind(knit, sampled, scene).normals(sampled.surface)
        np.testing.assert_allclose(ours, core, atol=1e-6)
        # Not the normals Blender computes from the same triangles: those are the facets'.
        plain = mesh.copy()
        plain.attributes.remove(plain.attributes["custom_normal"])
        theirs = np.empty_like(ours)
        plain.vertex_normals.foreach_get("vector", theirs.ravel())
        bpy.data.meshes.remove(plain)
        apart = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", ours, theirs), -1, 1)))
        assert np.median(apart) > 5.0, np.percentile(apart, [10, 50, 90])
        shaded[frame] = ours
    assert np.abs(shaded[5] - shaded[15]).max() > 0.1, "the normals did not move with the yarn"


def test_a_knit_carries_its_fibres_directions_which_follow_it(api: ModuleType) -> None:
    """A knit carries the core's fibre directions (`yarn_tangent`, the yarn material's
    anisotropic tangent), and in a scene that renders with Cycles each frame rewrites them
    with the positions: they are the core's for that pose and turn with the yarn. EEVEE,
    which has no anisotropy, does not pay for them: its frames leave them as they were."""
    scene = bpy.context.scene
    knit = knit_of(api, waving_cloth())
    mesh = knit.data
    at_rest = np.empty((len(mesh.vertices), 3), np.float32)
    mesh.attributes["yarn_tangent"].data.foreach_get("vector", at_rest.ravel())
    scene.render.engine = "BLENDER_EEVEE_NEXT" if bpy.app.version < (4, 5) else "BLENDER_EEVEE"
    scene.frame_set(9)
    kept = np.empty_like(at_rest)
    mesh.attributes["yarn_tangent"].data.foreach_get("vector", kept.ravel())
    np.testing.assert_array_equal(kept, at_rest)
    scene.render.engine = "CYCLES"
    attribute = mesh.attributes["yarn_tangent"]
    assert (attribute.domain, attribute.data_type) == ("POINT", "FLOAT_VECTOR")
    carried = {}
    for frame in (5, 15):
        scene.frame_set(frame)
        ours = np.empty((len(mesh.vertices), 3), np.float32)
        mesh.attributes["yarn_tangent"].data.foreach_get("vector", ours.ravel())
        sampled = api.sample_source(knit, bpy.context, bpy.context.evaluated_depsgraph_get())
        core = np.empty_like(ours)
        api.bind(knit, sampled, scene).positions(sampled.surface, tangents_out=core)
        np.testing.assert_array_equal(ours, core)
        np.testing.assert_allclose(np.linalg.norm(ours, axis=1), 1.0, atol=1e-5)
        carried[frame] = ours
    assert np.abs(carried[5] - carried[15]).max() > 0.1, "the tangents did not turn with the yarn"


def test_following_equals_the_knit_bound_at_rest_posed_anew(
    api: ModuleType, addon: ModuleType
) -> None:
    """Frame 12 from the handler (which rebinds from frame 12's pose with the pinned values)
    equals the knit bound at frame 1 asked for frame 12's positions."""
    import knitwear

    scene = bpy.context.scene
    source = waving_cloth()
    knit = knit_of(api, source)
    settings = api.core_inputs.complete(api.settings_from(knit))
    at_rest = addon.sampling.sample_object(source, bpy.context)
    inputs = api.core_inputs
    bound_at_rest = knitwear.Knit(
        at_rest.surface, inputs.pattern_of(settings), **inputs.core_settings(settings, scene)
    )
    scene.frame_set(12)
    posed = addon.sampling.sample_object(source, bpy.context)
    np.testing.assert_array_equal(positions(knit.data), bound_at_rest.positions(posed.surface))


def test_a_rigid_motion_of_the_source_moves_the_knit_without_jitter(api: ModuleType) -> None:
    scene = bpy.context.scene
    source = waving_cloth()
    source.animation_data_clear()
    source.data.shape_keys.animation_data_clear()
    for frame, (loc, rot) in ((1, ((0, 0, 0), (0, 0, 0))), (10, ((2, 1, 0.5), (0.3, 0.2, 1.0)))):
        source.location, source.rotation_euler = loc, rot
        source.keyframe_insert("location", frame=frame)
        source.keyframe_insert("rotation_euler", frame=frame)
    scene.frame_set(1)
    knit = knit_of(api, source)
    local = positions(knit.data)
    for frame in (4, 7, 10):
        scene.frame_set(frame)
        # The yarn is bound in the source's space: a rigid motion moves the object, and the
        # yarn relative to the surface does not move at all.
        np.testing.assert_array_equal(positions(knit.data), local)
        np.testing.assert_allclose(
            np.array(knit.matrix_world), np.array(source.matrix_world), atol=1e-6
        )


def test_frame_n_alone_equals_frame_n_in_sequence(api: ModuleType, tmp_path: Path) -> None:
    scene = bpy.context.scene
    knit = knit_of(api, waving_cloth())
    name = knit.name
    path = tmp_path / "scene.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    for frame in range(1, 15):
        scene.frame_set(frame)
    in_sequence = positions(knit.data)

    # A farm machine: open the file and go straight to frame 14.
    bpy.ops.wm.open_mainfile(filepath=str(path))
    bpy.context.scene.frame_set(14)
    alone = positions(bpy.data.objects[name].data)
    np.testing.assert_array_equal(alone, in_sequence)


def test_a_knit_that_cannot_follow_never_breaks_a_frame_change(
    api: ModuleType, capsys: object
) -> None:
    scene = bpy.context.scene
    source = waving_cloth()
    knit = knit_of(api, source)
    before = positions(knit.data)
    bpy.data.objects.remove(source)
    scene.frame_set(10)  # must not raise
    np.testing.assert_array_equal(positions(knit.data), before)
    assert "did not follow" in capsys.readouterr().out


def test_follow_can_be_switched_off(api: ModuleType) -> None:
    knit = knit_of(api, waving_cloth())
    knit.knitwear.follow_source = False
    before = positions(knit.data)
    bpy.context.scene.frame_set(15)
    np.testing.assert_array_equal(positions(knit.data), before)


def test_a_static_nurbs_knit_stays_put_across_frames(api: ModuleType) -> None:
    knit = knit_of(api, nurbs_patch())
    before = positions(knit.data)
    bpy.context.scene.frame_set(5)
    np.testing.assert_array_equal(positions(knit.data), before)


def test_an_animation_renders_headless_frame_by_frame(api: ModuleType, tmp_path: Path) -> None:
    scene = bpy.context.scene
    source = waving_cloth()
    source.hide_render = True
    api.knit_object(source, **SMALL, color_mode="STRIPES", color_count=2)
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = 1.4
    camera.location = (0.0, -2.0, 1.5)
    camera.rotation_euler = (0.93, 0.0, 0.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.display.render_aa = "OFF"
    scene.display.shading.color_type = "VERTEX"
    scene.render.resolution_x = scene.render.resolution_y = 48
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = str(tmp_path / "frame_")
    scene.frame_start, scene.frame_end = 1, 100
    assert bpy.ops.render.render(animation=True) == {"FINISHED"}
    frames = sorted(tmp_path.glob("frame_*.png"))
    assert len(frames) == 100
    first, last = (np.asarray(Image.open(f), dtype=np.float32) for f in (frames[0], frames[-1]))
    assert np.abs(first - last).mean() > 1.0, "the rendered knit did not move with the wave"


def test_an_update_with_a_new_topology_rebinds_the_follower(api: ModuleType) -> None:
    scene = bpy.context.scene
    knit = knit_of(api, waving_cloth())
    scene.frame_set(5)  # binds
    api.update_knit(knit, courses=SMALL["courses"] + 2)  # new topology at frame 5
    rest = positions(knit.data)
    triangles = corner_verts(knit.data)
    scene.frame_set(9)
    p = positions(knit.data)
    assert p.shape == rest.shape and np.isfinite(p).all() and np.abs(p - rest).max() > 0
    np.testing.assert_array_equal(corner_verts(knit.data), triangles)
    scene.frame_set(5)
    np.testing.assert_array_equal(positions(knit.data), rest)


def test_a_plush_cannot_be_knitted(api: ModuleType, addon: ModuleType) -> None:
    import knitwear
    import pytest

    plush = addon.plush.knit_plush(waving_cloth(), courses=6, wales=6)
    bpy.context.view_layer.objects.active = plush
    assert not bpy.ops.object.knitwear_knit.poll()
    with pytest.raises(knitwear.SurfaceError):
        api.knit_object(plush, **SMALL)
