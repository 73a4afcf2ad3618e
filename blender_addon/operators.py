"""Operators: Knit (a new knit object from the active surface) and Update (rebuild a knit).

Thin by design: `execute` gathers the settings and calls one function of `api`, which does
all the work and raises `knitwear.KnitError` for anything a user can get wrong. Nothing is
created before the core has succeeded, so a cancelled operator leaves the scene as it was.

Clicked in the interface (`invoke`), the same steps run modally: the core's job on a worker
thread (`core_thread`), the progress on the cursor, and Esc stops the core within a fraction
of a second, leaving the scene as it was. The interface takes no other input meanwhile, so
nothing the knit reads can change under it. The redo panel, scripts and headless runs call
`execute`, which knits in one go.
"""

import traceback
from collections.abc import Callable, Generator
from typing import Any

import bpy
import knitwear

from . import api, core_thread
from .properties import SETTING_NAMES, KnitSettingsMixin
from .settings_ui import draw_settings


class _Progress:
    """The window manager's progress indicator, where there is a window to show it in."""

    def __init__(self, context: bpy.types.Context) -> None:
        # Headless there is a window manager but nothing to draw the progress on.
        self._wm = None if bpy.app.background else context.window_manager
        if self._wm is not None:
            self._wm.progress_begin(0, 100)

    def update(self, fraction: float) -> None:
        if self._wm is not None:
            self._wm.progress_update(int(100 * fraction))

    def end(self) -> None:
        if self._wm is not None:
            self._wm.progress_end()


def _summary(outcome: api.KnitOutcome) -> str:
    text = (
        f"Knitted {outcome.stitches:,} stitches, {outcome.triangles:,} triangles "
        f"in {outcome.seconds:.2f} s"
    )
    notes = []
    if any(outcome.in_the_round):
        # A mesh's UV seam closes it round, or a NURBS surface is closed: no seam is sewn.
        notes.append("knitted in the round")
    if outcome.auto_detail:
        lv = outcome.levels
        saved = outcome.triangles_full_detail - outcome.triangles
        notes.append(
            f"auto detail: {lv['full']:,} full, {lv['mid']:,} reduced, {lv['far']:,} plain, "
            f"{lv['texture']:,} texture, {lv['culled']:,} unseen stitches; {saved:,} "
            f"triangles fewer than full detail ({outcome.triangles_full_detail:,}"
            + (
                f", of them {outcome.triangles_hidden:,} hidden behind other yarn)"
                if outcome.triangles_hidden
                else ")"
            )
        )
        stored = outcome.object.knitwear
        if lv["full"] == 0 and outcome.stitches:
            notes.append(
                "no stitch is close enough to the camera for full detail: move the camera "
                "closer, or set Detail to Full"
            )
        if outcome.hidden_pass is False:
            notes.append(
                "hidden yarn kept: fewer full-detail triangles than Cull From "
                f"({stored.cull_hidden_min_triangles:,}), where building them is quicker "
                "than finding them"
            )
        if outcome.texture_material:
            notes.append(f"the source wears '{outcome.texture_material}' for the texture")
    if outcome.lost_stitches:
        # Stitches in empty UV space between islands were never fabric: not a loss.
        notes.append(
            f"{outcome.lost_stitches:,} stitches of fabric lost where UV islands end part-way "
            "through them"
        )
    if outcome.clamped_stitches:
        notes.append(
            f"{outcome.clamped_stitches:,} stitches flattened: the surface curves more "
            "tightly than the yarn stands off it"
        )
    if outcome.uneven:
        spread = outcome.stitch_spread
        (w0, w1), (h0, h1) = spread["width"], spread["height"]
        notes.append(
            f"the UV map stretches {spread['stretched']:.0%} of the stitches more than 15% "
            f"off the gauge (widths {w0:.2f}-{w1:.2f}, heights {h0:.2f}-{h1:.2f} of it): "
            "unwrap with less stretch for an even knit"
        )
    if outcome.flat_clearance < api.MIN_CLEARANCE:
        notes.append(
            f"the yarn is too thick for its stitch: loops overlap (at best "
            f"{outcome.flat_clearance:.2f} yarn diameters apart); use a thinner yarn or a "
            "coarser gauge"
        )
    if notes:
        text += " (" + "; ".join(notes) + ")"
    return text


def _report_level(outcome: api.KnitOutcome) -> set[str]:
    """A warning where the result is visibly wrong (overlapping loops, a gauge the UV map
    stretches), else information."""
    wrong = outcome.flat_clearance < api.MIN_CLEARANCE or outcome.uneven
    return {"WARNING"} if wrong else {"INFO"}


def _failure(err: Exception) -> str:
    """The report of a failed knit: a `knitwear.KnitError`'s own message (the user can fix
    what it names); anything else is a bug, reported as one, its traceback on the console.
    Either way the steps have left the scene as it was."""
    if isinstance(err, knitwear.KnitError):
        return str(err)
    traceback.print_exception(err)
    return (
        f"Knitwear failed unexpectedly ({type(err).__name__}: {err}); nothing was changed. "
        "Please report it with the traceback from the system console"
    )


#: Seconds between the modal operators' looks at the core's worker thread.
POLL_SECONDS = 0.05


class _RunsCoreModally:
    """`invoke` and `modal` for an operator whose work is `api` steps (see the module
    docstring). The operator gives `_steps` (the steps for its settings) and `_finish` (its
    report once they are done). `invoke` sets ``_runner`` (a `core_thread.StepsOnThread`),
    ``_progress`` and ``_timer`` on the instance: not as class annotations, which Blender
    would read as operator properties."""

    def _steps(
        self, context: bpy.types.Context, progress: Callable[[float], None]
    ) -> Generator[api.CoreJob, Any, api.KnitOutcome]:
        raise NotImplementedError

    def _finish(self, context: bpy.types.Context, outcome: api.KnitOutcome) -> set[str]:
        raise NotImplementedError

    def invoke(self, context: bpy.types.Context, _event: bpy.types.Event) -> set[str]:
        if bpy.app.background or context.window is None:
            return self.execute(context)  # type: ignore[attr-defined]
        self._progress = _Progress(context)
        # `bpy.context`, not this call's `context`: the steps go on in later modal calls.
        self._runner = core_thread.StepsOnThread(self._steps(bpy.context, self._progress.update))
        try:
            self._runner.start()
        except Exception as err:
            self._progress.end()
            self.report({"ERROR"}, _failure(err))  # type: ignore[attr-defined]
            return {"CANCELLED"}
        wm = context.window_manager
        self._timer = wm.event_timer_add(POLL_SECONDS, window=context.window)
        wm.modal_handler_add(self)
        if context.workspace is not None:
            context.workspace.status_text_set("Knitwear: knitting... Esc to cancel")
        return {"RUNNING_MODAL"}

    def modal(self, context: bpy.types.Context, event: bpy.types.Event) -> set[str]:
        if event.type == "ESC" and event.value == "PRESS":
            self._runner.cancel()
        if event.type != "TIMER":
            # Every other input is held back while the core works: the scene it reads and
            # the objects the steps will write stay as they are.
            return {"RUNNING_MODAL"}
        try:
            if not self._runner.poll():
                return {"RUNNING_MODAL"}
        except knitwear.CancelledError:
            self._end(context)
            self.report({"INFO"}, "Knitting cancelled: nothing was changed")  # type: ignore[attr-defined]
            return {"CANCELLED"}
        except Exception as err:
            self._end(context)
            self.report({"ERROR"}, _failure(err))  # type: ignore[attr-defined]
            return {"CANCELLED"}
        except BaseException:
            self._end(context)
            raise
        self._end(context)
        return self._finish(context, self._runner.outcome)

    def _end(self, context: bpy.types.Context) -> None:
        context.window_manager.event_timer_remove(self._timer)
        self._progress.end()
        if context.workspace is not None:
            context.workspace.status_text_set(None)


def _make_active(context: bpy.types.Context, obj: bpy.types.Object) -> None:
    for other in context.selected_objects:
        other.select_set(False)
    try:
        obj.select_set(True)
    except RuntimeError:
        return  # the source's collection is excluded from this view layer
    context.view_layer.objects.active = obj


class OBJECT_OT_knitwear_knit(_RunsCoreModally, KnitSettingsMixin, bpy.types.Operator):
    """Cover the active NURBS surface or UV-mapped mesh with knitted yarn, as a new object"""

    bl_idname = "object.knitwear_knit"
    bl_label = "Knit this surface"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        if obj is None or obj.type not in {"SURFACE", "MESH"}:
            cls.poll_message_set("Select a NURBS surface or a mesh with a UV map")
            return False
        if context.mode != "OBJECT":
            # In Edit Mode the object's data lags behind the edit (mesh) or is being edited
            # (surface): knit what the user sees once they leave it.
            cls.poll_message_set("Switch to Object Mode to knit")
            return False
        if obj.knitwear.is_knit:
            cls.poll_message_set("The active object is already a knit: use Update Knit")
            return False
        if obj.knitwear_plush.is_plush:
            cls.poll_message_set("The active object is a plush: knit its source instead")
            return False
        return True

    def execute(self, context: bpy.types.Context) -> set[str]:
        settings = {name: getattr(self, name) for name in SETTING_NAMES}
        progress = _Progress(context)
        try:
            outcome = api.knit(
                context.active_object, context=context, progress=progress.update, **settings
            )
        except Exception as err:
            self.report({"ERROR"}, _failure(err))
            return {"CANCELLED"}
        finally:
            progress.end()
        return self._finish(context, outcome)

    def _steps(
        self, context: bpy.types.Context, progress: Callable[[float], None]
    ) -> Generator[api.CoreJob, Any, api.KnitOutcome]:
        settings = {name: getattr(self, name) for name in SETTING_NAMES}
        return api.knit_steps(
            context.active_object, context=context, progress=progress, **settings
        )

    def _finish(self, context: bpy.types.Context, outcome: api.KnitOutcome) -> set[str]:
        _make_active(context, outcome.object)
        self.report(_report_level(outcome), _summary(outcome))
        return {"FINISHED"}

    def draw(self, _context: bpy.types.Context) -> None:
        draw_settings(self.layout, self, "knitwear_redo")


class OBJECT_OT_knitwear_update(_RunsCoreModally, bpy.types.Operator):
    """Rebuild the active knit from its source surface with its current settings"""

    bl_idname = "object.knitwear_update"
    bl_label = "Update Knit"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        obj = context.active_object
        if obj is None or not obj.knitwear.is_knit:
            cls.poll_message_set("The active object is not a knit")
            return False
        if context.mode != "OBJECT":
            cls.poll_message_set("Switch to Object Mode to update the knit")
            return False
        return True

    def execute(self, context: bpy.types.Context) -> set[str]:
        progress = _Progress(context)
        try:
            outcome = api.update(context.active_object, context=context, progress=progress.update)
        except Exception as err:
            self.report({"ERROR"}, _failure(err))
            return {"CANCELLED"}
        finally:
            progress.end()
        return self._finish(context, outcome)

    def _steps(
        self, context: bpy.types.Context, progress: Callable[[float], None]
    ) -> Generator[api.CoreJob, Any, api.KnitOutcome]:
        return api.update_steps(context.active_object, context=context, progress=progress)

    def _finish(self, _context: bpy.types.Context, outcome: api.KnitOutcome) -> set[str]:
        self.report(_report_level(outcome), _summary(outcome))
        return {"FINISHED"}


def draw_object_menu(self: bpy.types.Menu, _context: bpy.types.Context) -> None:
    """Entries in Object menu of the 3D viewport (which also makes them searchable)."""
    layout = self.layout
    layout.separator()
    layout.operator(OBJECT_OT_knitwear_knit.bl_idname, icon="MOD_CLOTH")
    layout.operator(OBJECT_OT_knitwear_update.bl_idname, icon="FILE_REFRESH")
