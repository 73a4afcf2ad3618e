"""The link that keeps a knit's source evaluated wherever the knit is: a no-op Geometry Nodes
modifier on the knit that reads the source with an Object Info node."""

import bpy

from . import blender_compat

#: The modifier on each knit that keeps its source evaluated in every depsgraph (below).
LINK_MODIFIER = "Knitwear Source Link"
#: Its node group, shared by all knits (dot-prefixed: hidden in the UI).
LINK_GROUP = ".knitwear source link"


def _link_group() -> bpy.types.GeometryNodeTree:
    group = bpy.data.node_groups.get(LINK_GROUP)
    if group is not None and group.bl_idname == "GeometryNodeTree":
        return group
    group = bpy.data.node_groups.new(LINK_GROUP, "GeometryNodeTree")
    interface = group.interface
    interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    interface.new_socket("Source", in_out="INPUT", socket_type="NodeSocketObject")
    interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, links = group.nodes, group.links
    group_in, group_out = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    links.new(group_in.outputs[0], group_out.inputs[0])  # the knit passes through untouched
    info = nodes.new("GeometryNodeObjectInfo")  # ...and depends on the source's geometry
    links.new(group_in.outputs[1], info.inputs["Object"])
    return group


def link_source(obj: bpy.types.Object) -> None:
    """Make knit ``obj`` depend on its source's geometry in every depsgraph.

    A source hidden from renders (as a knit's source usually is) is left out of the render
    depsgraph unless something depends on it, and then a render would see it undeformed. A
    Geometry Nodes modifier that passes the knit through unchanged while reading the source
    with an Object Info node is such a dependency. It is plain Blender data, so a file renders
    the same on a machine without the extension.
    """
    modifier = obj.modifiers.get(LINK_MODIFIER)
    if modifier is None or modifier.type != "NODES":
        modifier = obj.modifiers.new(LINK_MODIFIER, "NODES")
        modifier.show_expanded = False
    group = _link_group()
    modifier.node_group = group
    identifier = group.interface.items_tree["Source"].identifier
    blender_compat.set_node_input(modifier, identifier, obj.knitwear.source)
