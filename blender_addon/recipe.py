"""Knits saved as their recipe: a .blend that keeps a knit's source, settings and pins, not its
yarn, and rebuilds the yarn when it opens.

A knit's mesh is most of a file's size (hundreds of MB for a garment), yet everything it is
made from is already in the file: the source object, the settings and the values pinned at
knit time (counts, yarn radius, stitch size, detail levels, seen triangles), from which
`api.bind` rebuilds exactly its topology in any pose. With **Save as Recipe** on, saving
swaps the knit's mesh for an empty placeholder that holds its name and materials: the real
mesh, with no users while Blender writes, is not written, and it is put back at once. Opening
the file with the extension installed rebuilds the mesh from the source as it evaluates then
(the frame the file opens at), bit for bit the mesh the knit had there; without the
extension the knit opens empty. Blender's autosave writes the whole mesh.

A knit that cannot be rebuilt on opening (its source is gone) is reported on the console and
left empty; opening the file never fails because of it.
"""

import traceback

import bpy
import knitwear
from bpy.app.handlers import persistent

from . import api, mesh_build

#: Custom property on a placeholder mesh: the knit is saved as its recipe.
RECIPE_PROPERTY = "knitwear_recipe"
#: Appended to a knit mesh's name while a placeholder holds it for a save.
_ASIDE = " (kept aside while saving)"

#: (placeholder, real mesh, its name) of the save in progress.
_aside: list[tuple[bpy.types.Mesh, bpy.types.Mesh, str]] = []


def _recipe_meshes() -> list[bpy.types.Mesh]:
    """The meshes of knits saved as recipes, each once, that have yarn to leave out."""
    meshes: list[bpy.types.Mesh] = []
    for obj in bpy.data.objects:
        mesh = obj.data
        if (
            obj.type == "MESH"
            and obj.knitwear.is_knit
            and obj.knitwear.save_as_recipe
            and mesh is not None
            and not mesh.library
            and RECIPE_PROPERTY not in mesh
            and mesh not in meshes
        ):
            meshes.append(mesh)
    return meshes


@persistent
def _before_save(*_args: object) -> None:
    _put_back()  # a save that failed before this build had no `save_post_fail`
    for mesh in _recipe_meshes():
        name = mesh.name
        mesh.name = name + _ASIDE
        placeholder = bpy.data.meshes.new(name)
        for material in mesh.materials:
            placeholder.materials.append(material)
        placeholder[RECIPE_PROPERTY] = 1
        # Every user of the mesh now uses the placeholder: the mesh has none, and Blender
        # does not write data that nothing uses.
        mesh.user_remap(placeholder)
        _aside.append((placeholder, mesh, name))


@persistent
def _put_back(*_args: object) -> None:
    while _aside:
        placeholder, mesh, name = _aside.pop()
        placeholder.user_remap(mesh)
        bpy.data.meshes.remove(placeholder)
        mesh.name = name


def rebuild(obj: bpy.types.Object, context: bpy.types.Context | None = None) -> None:
    """Build knit ``obj``'s mesh from its source and stored settings and pins, in the
    source's pose now. Raises `knitwear.KnitError` when it cannot (then nothing is changed)."""
    context = context or bpy.context
    depsgraph = context.evaluated_depsgraph_get()
    sampled = api.sample_source(obj, context, depsgraph)
    knit = api.bind(obj, sampled, context.scene)
    result = knit.build(sampled.surface)
    mesh_build.fill_mesh(obj.data, result)
    if obj.knitwear.follow_source and obj.matrix_world != sampled.matrix:
        obj.matrix_world = sampled.matrix


@persistent
def _after_load(*_args: object) -> None:
    try:
        waiting = [
            obj
            for obj in bpy.context.scene.objects
            if obj.type == "MESH"
            and obj.knitwear.is_knit
            and obj.data is not None
            and RECIPE_PROPERTY in obj.data
        ]
        for obj in waiting:
            try:
                rebuild(obj)
            except knitwear.KnitError as err:
                print(f"Knitwear: '{obj.name}', saved as its recipe, cannot be rebuilt: {err}")
    except Exception:  # noqa: BLE001  (opening a file must never fail because of a knit)
        print("Knitwear: error rebuilding knits saved as recipes (please report it):")
        traceback.print_exc()


def _handlers() -> list[tuple[list, object]]:
    handlers = bpy.app.handlers
    out: list[tuple[list, object]] = [
        (handlers.save_pre, _before_save),
        (handlers.save_post, _put_back),
        (handlers.load_post, _after_load),
    ]
    failed = getattr(handlers, "save_post_fail", None)  # Blender 4.3+
    if failed is not None:
        out.append((failed, _put_back))
    return out


def register() -> None:
    for handlers, handler in _handlers():
        if handler not in handlers:
            handlers.append(handler)


def unregister() -> None:
    for handlers, handler in reversed(_handlers()):
        if handler in handlers:
            handlers.remove(handler)
