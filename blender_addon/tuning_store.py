"""Where the core keeps its tunings between sessions: this extension's user folder.

A cable or lace pattern's first knit tunes its loop shapes, which takes seconds to tens of
seconds; the core keeps the result on disk when it has a folder for it, so the next Blender
(a reopened scene, a farm node rendering one frame) knits at once, bit-identically. A folder
named by the KNITWEAR_TUNING_STORE environment variable (a farm's shared one) wins.
"""

import os

import bpy
import knitwear

#: What the core had before `register`, given back by `unregister`.
_before: list[str | None] = []


def register() -> None:
    if os.environ.get("KNITWEAR_TUNING_STORE"):
        return
    try:
        folder = bpy.utils.extension_path_user(__package__, path="tuning", create=True)
    except (ValueError, OSError):
        # Not installed as an extension (no user folder): the core keeps tunings in memory.
        return
    _before.append(knitwear.tuning_store())
    knitwear.set_tuning_store(folder)


def unregister() -> None:
    if _before:
        knitwear.set_tuning_store(_before.pop())
