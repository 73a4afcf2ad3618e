"""A knit's core job on a worker thread, so that the interface stays live and Esc can stop it.

`api.knit_steps` and `api.update_steps` do their Blender work (sampling, then building the
mesh) on the main thread and yield the jobs only the core runs. `StepsOnThread` runs each
job on a worker thread while a modal operator polls it from a timer; `cancel` asks the core
to stop (`knitwear.cancel`: every running call raises `knitwear.CancelledError` within a
fraction of a second). A cancelled knit closes its steps before they create anything, so the
scene is left as it was.
"""

import threading
from collections.abc import Generator
from typing import Any

import knitwear

from .api import CoreJob


class StepsOnThread:
    """Drives knit steps with each core job on a worker thread (see the module docstring).

    `start` runs the steps up to their first core job and starts it; `poll` (from the main
    thread, e.g. a modal operator's timer) carries the steps on once the job has returned, and
    says whether they are done; `outcome` is then their result. Both raise what the steps
    raise, and `knitwear.CancelledError` once `cancel` was asked for.
    """

    def __init__(self, steps: Generator[CoreJob, Any, Any]) -> None:
        self._steps = steps
        self._thread: threading.Thread | None = None
        self._value: Any = None
        self._error: BaseException | None = None
        self._cancel_asked = False
        self.done = False
        self.outcome: Any = None
        #: Whether a cancel stopped the core inside its job (not merely between steps).
        self.stopped_in_core = False

    def start(self) -> None:
        self._advance()

    def cancel(self) -> None:
        """Ask the running core job, and the steps, to stop; `poll` then raises
        `knitwear.CancelledError`."""
        self._cancel_asked = True
        knitwear.cancel()

    @property
    def working(self) -> bool:
        """Whether the core job is running now."""
        return self._thread is not None and self._thread.is_alive()

    def poll(self) -> bool:
        """Carry the steps on if the core job has returned; whether they are done."""
        if self.done:
            return True
        if self.working:
            if self._cancel_asked:
                # Again on every poll: a cancel that came before the job entered the core
                # would otherwise be lost (`knitwear.cancel` stops the calls running then).
                knitwear.cancel()
            return False
        if self._cancel_asked:
            self.stopped_in_core = isinstance(self._error, knitwear.CancelledError)
            # The steps are closed where they wait for the job: before they create anything.
            self._steps.close()
            self.done = True
            raise knitwear.CancelledError("cancelled: nothing was changed")
        self._advance()
        return self.done

    def _advance(self) -> None:
        value, error = self._value, self._error
        self._value, self._error, self._thread = None, None, None
        try:
            job = self._steps.throw(error) if error is not None else self._steps.send(value)
        except StopIteration as finished:
            self.done, self.outcome = True, finished.value
            return
        except BaseException:
            self.done = True
            raise
        self._thread = threading.Thread(
            target=self._run, args=(job,), name="knitwear core", daemon=True
        )
        self._thread.start()

    def _run(self, job: CoreJob) -> None:
        try:
            self._value = job()
        except BaseException as e:  # noqa: BLE001 - handed back to the steps on the main thread
            self._error = e
