"""Frame-change handlers that update some objects per frame and never break a render."""

import traceback
from collections.abc import Callable, Iterator
from contextlib import contextmanager

import bpy
import knitwear
from bpy.app.handlers import persistent

FrameHandler = Callable[[bpy.types.Scene, bpy.types.Depsgraph | None], None]

#: How many `paused` blocks are open.
_paused = 0


@contextmanager
def paused() -> Iterator[None]:
    """Frame changes inside the block run none of these handlers. For the add-on's own steps
    through the frame range (sampling an animated camera's views or a source's poses,
    finding whether something animates), which put the frame back after: otherwise every
    knit and plush already in the scene would follow each step, and each would add its
    per-frame cost, up to 25 times, to the click (a 700k-triangle sleeve: 1 s a knit).
    Nothing they show changes, since the frame they showed is the one restored."""
    global _paused
    _paused += 1
    try:
        yield
    finally:
        _paused -= 1


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
        if busy or _paused:
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
