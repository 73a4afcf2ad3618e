"""Datablocks a step creates, removed again if the step fails by any exception.

The operators promise that a knit or an update that fails leaves the blend file as it was.
The core's errors come before anything is created; this covers what fails after (a Blender
API that changed under the add-on, a full disk, a bug): whatever objects, meshes, materials,
node groups and images appeared while the block ran are removed, objects first (they use
the rest), and the exception goes on.
"""

from collections.abc import Iterator
from contextlib import contextmanager

import bpy

#: The kinds of datablock a knit creates, in the order they are removed.
KINDS = ("objects", "meshes", "curves", "materials", "node_groups", "images")


@contextmanager
def removed_on_failure() -> Iterator[None]:
    """Run the block; if it raises, remove every datablock of `KINDS` it created."""
    before = {kind: {idb.session_uid for idb in getattr(bpy.data, kind)} for kind in KINDS}
    try:
        yield
    except BaseException:
        for kind in KINDS:
            collection = getattr(bpy.data, kind)
            for idb in [i for i in collection if i.session_uid not in before[kind]]:
                collection.remove(idb)
        raise
