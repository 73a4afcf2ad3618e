"""Esc while knitting (issue 18): the operators run the core's job on a worker thread
(`core_thread.StepsOnThread`) and Esc calls its `cancel`. Headless there is no window to
press Esc in, so these drive the same runner the modal operators poll from their timer, and
cancel it as Esc does."""

import importlib
import time
from types import ModuleType

import bpy
import pytest
from blender_scenes import ADDON_MODULE, SMALL, data_counts, nurbs_patch, snapshot

#: Enough stitches that the core is still working when the cancel comes (seconds of work).
LARGE = {"size_mode": "COUNTS", "courses": 400, "wales": 400, "detail_mode": "FULL"}


@pytest.fixture
def core_thread(addon: ModuleType) -> ModuleType:
    return importlib.import_module(f"{ADDON_MODULE}.core_thread")


def drive(runner: object, cancel_once_working: bool = False) -> None:
    """Poll ``runner`` as the modal operator's timer does, until it is done or raises."""
    runner.start()  # type: ignore[attr-defined]
    while True:
        if cancel_once_working and runner.working:  # type: ignore[attr-defined]
            runner.cancel()  # type: ignore[attr-defined]
            cancel_once_working = False
        if runner.poll():  # type: ignore[attr-defined]
            return
        time.sleep(0.01)


def test_esc_stops_the_core_and_leaves_the_scene_as_it_was(
    api: ModuleType, core: ModuleType, core_thread: ModuleType
) -> None:
    source = nurbs_patch()
    before = (data_counts(), snapshot(source), bpy.context.scene.frame_current)
    runner = core_thread.StepsOnThread(api.knit_steps(source, **LARGE))
    with pytest.raises(core.CancelledError, match="nothing was changed"):
        drive(runner, cancel_once_working=True)
    assert runner.stopped_in_core, "the core ran its job to the end instead of stopping"
    assert (data_counts(), snapshot(source), bpy.context.scene.frame_current) == before
    # And the next knit runs normally.
    assert len(api.knit_object(source, **SMALL).data.vertices) > 0


def test_esc_during_an_update_keeps_the_knit(
    api: ModuleType, core: ModuleType, core_thread: ModuleType
) -> None:
    knit = api.knit_object(nurbs_patch(), **SMALL)
    vertices = len(knit.data.vertices)
    runner = core_thread.StepsOnThread(api.update_steps(knit, **LARGE))
    with pytest.raises(core.CancelledError):
        drive(runner, cancel_once_working=True)
    assert runner.stopped_in_core
    assert len(knit.data.vertices) == vertices
    assert knit.knitwear.courses == SMALL["courses"], "cancelled settings must not be stored"


def test_on_a_thread_the_knit_is_the_one_a_click_makes(
    api: ModuleType, core_thread: ModuleType
) -> None:
    source = nurbs_patch()
    runner = core_thread.StepsOnThread(api.knit_steps(source, **SMALL))
    drive(runner)
    threaded = runner.outcome.object
    inline = api.knit_object(source, **SMALL)
    assert threaded.name != inline.name
    assert len(threaded.data.vertices) == len(inline.data.vertices) > 0
    a = [tuple(v.co) for v in threaded.data.vertices[:200]]
    b = [tuple(v.co) for v in inline.data.vertices[:200]]
    assert a == b


def test_a_refusal_on_the_thread_is_the_same_knit_error(
    api: ModuleType, core: ModuleType, core_thread: ModuleType
) -> None:
    source = nurbs_patch()
    before = data_counts()
    runner = core_thread.StepsOnThread(
        api.knit_steps(source, **(SMALL | {"pattern": "CUSTOM", "pattern_chart": "kk;kz"}))
    )
    with pytest.raises(core.PatternError):
        drive(runner)
    assert data_counts() == before


def test_the_modal_operator_cancels_on_esc_and_reports_it(
    api: ModuleType, core_thread: ModuleType
) -> None:
    """The operators' `modal`, fed the events Blender would feed it (its timer, and Esc
    pressed once the core is working), with a window manager whose timer it removes."""
    from types import SimpleNamespace

    operators = importlib.import_module(f"{ADDON_MODULE}.operators")
    source = nurbs_patch()
    before = data_counts()
    runner = core_thread.StepsOnThread(api.knit_steps(source, **LARGE))
    runner.start()

    class FakeOperator(operators._RunsCoreModally):
        """What `modal` reads of an operator instance: what `invoke` set, and `report`."""

        def __init__(self) -> None:
            self._runner, self._progress, self._timer = (
                runner,
                operators._Progress(bpy.context),
                None,
            )
            self.reports: list[tuple[set[str], str]] = []

        def report(self, level: set[str], text: str) -> None:
            self.reports.append((level, text))

    op = FakeOperator()
    removed = []
    context = SimpleNamespace(
        window_manager=SimpleNamespace(event_timer_remove=removed.append), workspace=None
    )
    timer = SimpleNamespace(type="TIMER", value="NOTHING")
    esc = SimpleNamespace(type="ESC", value="PRESS")
    click = SimpleNamespace(type="LEFTMOUSE", value="PRESS")
    assert op.modal(context, click) == {"RUNNING_MODAL"}
    while not runner.working:
        assert op.modal(context, timer) == {"RUNNING_MODAL"}
        time.sleep(0.01)
    op.modal(context, esc)
    while (answer := op.modal(context, timer)) == {"RUNNING_MODAL"}:
        time.sleep(0.01)
    assert answer == {"CANCELLED"}
    assert op.reports == [({"INFO"}, "Knitting cancelled: nothing was changed")]
    assert removed == [None], "the operator's timer must be removed"
    assert data_counts() == before
