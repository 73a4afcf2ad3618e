"""A knit or an update that fails after the core, by any exception (a Blender API that changed,
a full disk, a bug), leaves the blend file as it was (issue 21, item 2): each step after the
core is made to fail in turn."""

from collections.abc import Callable
from types import ModuleType
from typing import Any

import bpy
import numpy as np
import pytest
from blender_scenes import SMALL, data_counts, nurbs_patch, snapshot


class Forced(RuntimeError):
    """The failure a test forces (not a KnitError: the operators' cleanup must not rely on
    the error being one of the core's)."""


def fail_once(monkeypatch: pytest.MonkeyPatch, owner: object, name: str) -> None:
    """Make ``owner.name`` raise `Forced` the first time it is called, then work again (the
    cleanup may call it)."""
    real = getattr(owner, name)
    calls = []

    def failing(*args: Any, **kwargs: Any) -> Any:
        calls.append(1)
        if len(calls) == 1:
            raise Forced(f"{name} failed")
        return real(*args, **kwargs)

    monkeypatch.setattr(owner, name, failing)


def steps(api: ModuleType, build: str) -> dict[str, Callable[[], tuple[object, str]]]:
    """Each step after the core, as (module or namespace, attribute)."""
    return {
        "mesh": lambda: (api.mesh_build, build),
        "material": lambda: (api.material, "assign"),
        "store": lambda: (api, "_store"),
        "source link": lambda: (api.source_link, "link_source"),
        "texture": lambda: (api, "_texture_where_needed"),
    }


STEPS = ["mesh", "material", "store", "source link", "texture"]


def positions(obj: bpy.types.Object) -> np.ndarray:
    out = np.empty(3 * len(obj.data.vertices), np.float32)
    obj.data.vertices.foreach_get("co", out)
    return out


@pytest.mark.parametrize("step", STEPS)
def test_a_knit_failing_at_any_step_leaves_nothing(
    step: str, api: ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    source = nurbs_patch()
    before = (data_counts(), snapshot(source), len(bpy.data.node_groups))
    fail_once(monkeypatch, *steps(api, "new_mesh")[step]())
    with pytest.raises(Forced):
        api.knit_object(source, **SMALL)
    assert (data_counts(), snapshot(source), len(bpy.data.node_groups)) == before
    # Through the operator too: an ERROR report that calls it a bug (headless, an operator's
    # ERROR report raises RuntimeError with its text).
    fail_once(monkeypatch, *steps(api, "new_mesh")[step]())
    with pytest.raises(RuntimeError, match="failed unexpectedly .*Forced.*nothing was changed"):
        bpy.ops.object.knitwear_knit(**SMALL)
    assert (data_counts(), snapshot(source), len(bpy.data.node_groups)) == before


@pytest.mark.parametrize("change", [{"seed": 7}, {"courses": 12}], ids=["in place", "new mesh"])
@pytest.mark.parametrize("step", STEPS)
def test_an_update_failing_at_any_step_keeps_the_knit(
    step: str, change: dict[str, Any], api: ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    knit = api.knit_object(nurbs_patch(), **SMALL)
    mesh_name = knit.data.name
    before = (
        data_counts(),
        len(bpy.data.node_groups),
        positions(knit).tobytes(),
        api.settings_from(knit),
        api.bound_of(knit),
        [tuple(r) for r in knit.matrix_world],
    )
    fail_once(monkeypatch, *steps(api, "fill_mesh")[step]())
    with pytest.raises(Forced):
        api.update_knit(knit, **change)
    after = (
        data_counts(),
        len(bpy.data.node_groups),
        positions(knit).tobytes(),
        api.settings_from(knit),
        api.bound_of(knit),
        [tuple(r) for r in knit.matrix_world],
    )
    assert after == before
    assert knit.data.name == mesh_name
    assert knit.data.materials[0].name == "Knitwear Yarn"
    # And the knit still updates.
    assert api.update(knit, **change).object is knit
