"""Run one analysis in its own thread under a time budget, and stop it when asked.

The compiler is pure Python, so a runaway analysis (a macro loop without end, a
50 MB document) would keep a worker busy for as long as it likes.  A :class:`Job`
runs the work in a daemon thread; the work calls ``check()`` now and then
(cooperative stop), and a watchdog raises :class:`Stopped` inside the thread when
the budget is spent or the job was cancelled and the work did not notice (a loop
that never reaches a ``check``).  Either way the job's future resolves with the
reason, and whatever the work had written to its result object so far is kept.

Jobs have two priorities.  A *foreground* job (the fast diagnostics of an edit)
holds the :class:`Gate` while it runs; a *background* job (the machine checks that
follow) waits at each of its ``check()`` calls while any foreground job runs, so it
never competes with a fresh edit for the interpreter lock.  The time spent waiting
does not count against the background job's budget.
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


class Gate:
    """Counts running foreground jobs; background jobs wait while there are any."""

    def __init__(self) -> None:
        self._busy = 0
        self._cv = threading.Condition()

    def enter(self) -> None:
        with self._cv:
            self._busy += 1

    def leave(self) -> None:
        with self._cv:
            self._busy -= 1
            if self._busy <= 0:
                self._busy = 0
                self._cv.notify_all()

    @property
    def busy(self) -> bool:
        return self._busy > 0

    def wait_idle(self, stop: Callable[[], bool], slice_s: float = 0.05) -> float:
        """Block while a foreground job runs (or until ``stop()``); returns the seconds waited."""
        if self._busy <= 0:
            return 0.0
        t0 = time.monotonic()
        with self._cv:
            while self._busy > 0 and not stop():
                self._cv.wait(slice_s)
        return time.monotonic() - t0


class Job:
    """One guarded run of ``work(check)``; ``future`` resolves to the stop reason
    (``None`` when the work finished, ``"budget"`` or ``"cancelled"``).

    With a ``gate``, a foreground job holds it while it runs and a ``background``
    job waits for it at every ``check()``."""

    def __init__(self, work: Callable[[Callable[[], None]], None], budget_s: float,
                 gate: Gate | None = None, background: bool = False,
                 prelude: Callable[[], None] | None = None) -> None:
        self.future: Future[str | None] = Future()
        self._prelude = prelude  # run first, never interrupted by force (imports of C extensions)
        self._shielded = prelude is not None
        self._gate = gate
        self._background = background
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
        if self._gate is not None and not self._background:
            self._gate.enter()
        self._thread.start()
        if self._background:  # its deadline moves while it waits for the gate
            threading.Thread(target=self._watch, name="cncc-lsp-watchdog", daemon=True).start()
        else:
            self._timer = threading.Timer(self._budget_s + GRACE_S, self._interrupt, args=("budget",))
            self._timer.daemon = True
            self._timer.start()
        return self

    def check(self) -> None:
        """Raise :class:`Stopped` if the job should stop (call from the work)."""
        if self._background and self._gate is not None and self._gate.busy:
            self._deadline += self._gate.wait_idle(lambda: self._reason is not None)
        if self._reason is not None:
            raise Stopped(self._reason)
        if time.monotonic() > self._deadline:
            self._reason = "budget"
            raise Stopped("budget")

    def cancel(self, grace_s: float = GRACE_S) -> None:
        """Stop the job: at its next ``check()``, or by force after ``grace_s``."""
        if self._reason is None:
            self._reason = "cancelled"
        if grace_s <= 0.0:
            self._interrupt("cancelled")
            return
        timer = threading.Timer(grace_s, self._interrupt, args=("cancelled",))
        timer.daemon = True
        timer.start()

    @property
    def reason(self) -> str | None:
        return self._reason

    def _main(self) -> None:
        reason: str | None = None
        error: BaseException | None = None
        try:
            if self._prelude is not None:
                try:
                    self._prelude()
                finally:
                    self._shielded = False
            self._work(self.check)
        except Stopped:
            reason = self._reason or "budget"
        except BaseException as exc:  # a bug in the work: report it through the future
            error = exc
        while True:  # no forced stop can arrive once _running is False
            try:
                with self._lock:
                    self._running = False
                    _clear_async_exc(self._thread)
                break
            except Stopped:  # delivered while leaving: the work was done or stopped anyway
                reason = reason or self._reason or "budget"
        if self._timer is not None:
            self._timer.cancel()
        if self._gate is not None and not self._background:
            self._gate.leave()
        if self.future.done():
            return
        if error is not None:
            self.future.set_exception(error)
        else:
            self.future.set_result(reason)

    def _watch(self) -> None:
        """Watchdog of a background job: its deadline moves while it waits for the gate."""
        while self._running:
            time.sleep(0.05)
            if self._gate is not None and self._gate.busy:
                continue
            if time.monotonic() > self._deadline + GRACE_S:
                self._interrupt("budget")
                return

    def _interrupt(self, reason: str) -> None:
        with self._lock:
            if not self._running:
                return
            if self._reason is None:
                self._reason = reason
            if self._shielded:  # stopped at the first check() after the prelude
                return
            _set_async_exc(self._thread, Stopped)


def _set_async_exc(thread: threading.Thread, exc: type[BaseException]) -> None:
    if thread.ident is not None:
        ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(thread.ident), ctypes.py_object(exc))


def _clear_async_exc(thread: threading.Thread) -> None:
    if thread.ident is not None:
        ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(thread.ident), None)
