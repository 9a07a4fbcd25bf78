"""Run one analysis in its own thread under a time budget, and stop it when asked.

The compiler is pure Python, so a runaway analysis (a macro loop without end, a
50 MB document) would keep a worker busy for as long as it likes.  A :class:`Job`
runs the work in a daemon thread; the work calls ``check()`` now and then
(cooperative stop), and a watchdog raises :class:`Stopped` inside the thread when
the budget is spent or the job was cancelled and the work did not notice (a loop
that never reaches a ``check``).  Either way the job's future resolves with the
reason, and whatever the work had written to its result object so far is kept.
"""

from __future__ import annotations

import ctypes
import threading
import time
from collections.abc import Callable
from concurrent.futures import Future

GRACE_S = 0.2
"""How long after the budget (or a cancel) the watchdog waits before it interrupts."""


class Stopped(BaseException):
    """Raised inside the work when the job is over budget or cancelled.

    A ``BaseException`` so that ``except Exception`` in the compiler does not eat it.
    """


class Job:
    """One guarded run of ``work(check)``; ``future`` resolves to the stop reason
    (``None`` when the work finished, ``"budget"`` or ``"cancelled"``)."""

    def __init__(self, work: Callable[[Callable[[], None]], None], budget_s: float) -> None:
        self.future: Future[str | None] = Future()
        self._work = work
        self._deadline = time.monotonic() + budget_s
        self._budget_s = budget_s
        self._reason: str | None = None
        self._lock = threading.Lock()
        self._running = False
        self._thread = threading.Thread(target=self._main, name="cncc-lsp-analysis", daemon=True)
        self._timer: threading.Timer | None = None

    def start(self) -> Job:
        self._running = True
        self._thread.start()
        self._timer = threading.Timer(self._budget_s + GRACE_S, self._interrupt, args=("budget",))
        self._timer.daemon = True
        self._timer.start()
        return self

    def check(self) -> None:
        """Raise :class:`Stopped` if the job should stop (call from the work)."""
        if self._reason is not None:
            raise Stopped(self._reason)
        if time.monotonic() > self._deadline:
            self._reason = "budget"
            raise Stopped("budget")

    def cancel(self) -> None:
        if self._reason is None:
            self._reason = "cancelled"
        timer = threading.Timer(GRACE_S, self._interrupt, args=("cancelled",))
        timer.daemon = True
        timer.start()

    @property
    def reason(self) -> str | None:
        return self._reason

    def _main(self) -> None:
        reason: str | None = None
        try:
            try:
                self._work(self.check)
            except Stopped:
                reason = self._reason or "budget"
            finally:
                with self._lock:
                    self._running = False
                    _clear_async_exc(self._thread)
        except Stopped:  # delivered while leaving: the work was done or stopped anyway
            reason = reason or self._reason
        except BaseException as exc:  # a bug in the work: report it through the future
            if not self.future.done():
                self.future.set_exception(exc)
            return
        finally:
            if self._timer is not None:
                self._timer.cancel()
        if not self.future.done():
            self.future.set_result(reason)

    def _interrupt(self, reason: str) -> None:
        with self._lock:
            if not self._running:
                return
            if self._reason is None:
                self._reason = reason
            _set_async_exc(self._thread, Stopped)


def _set_async_exc(thread: threading.Thread, exc: type[BaseException]) -> None:
    if thread.ident is not None:
        ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(thread.ident), ctypes.py_object(exc))


def _clear_async_exc(thread: threading.Thread) -> None:
    if thread.ident is not None:
        ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(thread.ident), None)
