"""The add-on's knit properties are the core's settings table (`knitwear.settings()`): the
same label, tooltip, default (the add-on's own where the table declares one) and hard range,
on the stored settings and on the Knit operator's redo panel alike."""

from types import ModuleType

import bpy
import numpy as np
import pytest

#: What Blender stores for an unbounded end.
INT_MAX = 2**31 - 1
FLOAT_MAX = float(np.finfo(np.float32).max)


def _rna(owner: str) -> bpy.types.bpy_prop_collection:
    if owner == "stored":
        return bpy.types.Object.bl_rna.properties["knitwear"].fixed_type.properties
    if owner == "plush stored":
        return bpy.types.Object.bl_rna.properties["knitwear_plush"].fixed_type.properties
    if owner == "plush operator":
        return bpy.ops.object.knitwear_plush.get_rna_type().properties
    return bpy.ops.object.knitwear_knit.get_rna_type().properties


def _as_stored(value: object, kind: str) -> object:
    if kind == "float":
        return float(np.float32(value))
    return value


@pytest.mark.parametrize("owner", ["stored", "operator", "plush stored", "plush operator"])
def test_every_knit_setting_is_the_cores(core: ModuleType, owner: str) -> None:
    props = _rna(owner)
    table = core.settings("plush" if owner.startswith("plush") else "knit")
    assert len(table) >= 13
    for s in table:
        prop = props[s["property"]]
        assert prop.name == s["label"], s["name"]
        assert prop.description == s["doc"], s["name"]
        assert prop.default == _as_stored(s["addon_default"], s["type"]), s["name"]
        if s["type"] == "bool":
            assert prop.type == "BOOLEAN", s["name"]
            continue
        assert prop.type == ("INT" if s["type"] == "int" else "FLOAT"), s["name"]
        unbounded = INT_MAX if s["type"] == "int" else FLOAT_MAX
        lo = -unbounded if s["min"] is None else _as_stored(s["min"], s["type"])
        hi = unbounded if s["max"] is None else _as_stored(s["max"], s["type"])
        assert (prop.hard_min, prop.hard_max) == (lo, hi), s["name"]


def test_the_add_ons_own_defaults_are_the_declared_ones(core: ModuleType) -> None:
    """kappa 0.005 (hand-knitted) and culling on are the add-on's, declared in the table."""
    by_property = {s["property"]: s for s in core.settings()}
    stored = _rna("stored")
    assert stored["kappa"].default == pytest.approx(0.005)
    assert by_property["kappa"]["default"] == 0.0
    assert stored["cull_hidden"].default is True and by_property["cull_hidden"]["default"] is False
    assert stored["cull_hidden_samples"].default == 2
