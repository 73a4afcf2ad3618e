"""What differs between the Blender versions the extension runs on, in one place.

Blender 4.5 shades with a mesh's free custom normals, a float vector per vertex in the
"custom_normal" attribute, and then computes none of its own; to 4.2 that attribute is just
data (`FREE_CUSTOM_NORMALS`).

Blender 5.2 moved a Geometry Nodes modifier's inputs out of its ID properties
(``modifier["Socket_1"] = value``, now a `TypeError`) into
``modifier.properties.inputs.Socket_1.value``. Blender 4.2 to 5.0 have only the former.
"""

from typing import Any

import bpy

#: Whether this Blender shades with the "custom_normal" point attribute (4.5 and later).
FREE_CUSTOM_NORMALS: bool = bpy.app.version >= (4, 5, 0)


def _interface_inputs(modifier: bpy.types.NodesModifier) -> Any | None:
    """The modifier's input values as Blender 5.2+ keeps them, or None before 5.2."""
    properties = getattr(modifier, "properties", None)
    return getattr(properties, "inputs", None)


def set_node_input(modifier: bpy.types.NodesModifier, identifier: str, value: Any) -> None:
    """Set the Geometry Nodes modifier's input ``identifier`` (a socket identifier such as
    "Socket_1") to ``value``."""
    inputs = _interface_inputs(modifier)
    if inputs is None:
        modifier[identifier] = value
    else:
        getattr(inputs, identifier).value = value


def node_input_values(modifier: bpy.types.NodesModifier) -> list[Any]:
    """The values of the Geometry Nodes modifier's inputs (other kinds of data they hold,
    such as the "_use_attribute" switches, may come along before 5.2)."""
    inputs = _interface_inputs(modifier)
    if inputs is None:
        return list(modifier.values())
    values = []
    for prop in inputs.bl_rna.properties:
        item = getattr(inputs, prop.identifier, None) if prop.type == "POINTER" else None
        if item is not None and prop.identifier != "rna_type" and hasattr(item, "value"):
            values.append(item.value)
    return values
