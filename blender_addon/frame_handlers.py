"""Frame-change handlers that update some objects per frame and never break a render."""

import traceback
from collections.abc import Callable

import bpy
import knitwear
from bpy.app.handlers import persistent

FrameHandler = Callable[[bpy.types.Scene, bpy.types.Depsgraph | None], None]


def per_object(
    objects: Callable[[bpy.types.Scene], list[bpy.types.Object]],
    update: Callable[[bpy.types.Object, bpy.types.Depsgraph | None], None],
    failed: str,
) -> FrameHandler:
    """A persistent ``frame_change_post`` handler that calls ``update(obj, depsgraph)`` for each
    of ``objects(scene)``.

    Writing mesh data can make Blender call frame handlers again: a re-entry guard ignores
    those calls. A `knitwear.KnitError` of one object is printed (``failed`` says what did not
    happen) and the others still update; anything else is printed with its traceback: a frame
    handler must never break a render.
    """
    busy = False

    @persistent
    def handler(scene: bpy.types.Scene, depsgraph: bpy.types.Depsgraph | None = None) -> None:
        nonlocal busy
        if busy:
            return
        busy = True
        try:
            for obj in objects(scene):
                try:
                    update(obj, depsgraph)
                except knitwear.KnitError as err:
                    print(f"Knitwear: '{obj.name}' {failed}: {err}")
        except Exception:  # noqa: BLE001  (a frame handler must never break a render)
            print(f"Knitwear: error in a frame handler ({failed}; please report it):")
            traceback.print_exc()
        finally:
            busy = False

    return handler
