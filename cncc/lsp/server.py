"""The language server: pygls wiring, document state, debounced analyses.

Every open document has a :class:`DocState`.  An edit schedules an analysis after a
short pause (``debounce_ms``); a newer edit cancels the pending one and stops a
running one.  Analyses run in guarded threads (:mod:`cncc.lsp.guard`) so the event
loop keeps answering requests while the compiler works, and an analysis that runs
past its budget is stopped with its partial results published.  Requests read the
latest analysis; lexical features (hover, completion, go-to) read the text itself.

An analysis has two phases.  The first (:mod:`cncc.lsp.analysis`) is published as
soon as it ends.  The second (:mod:`cncc.lsp.machine_check`: soft limits, step
rates, the planner's times) runs after it as a background job, which yields to any
first phase and which a new edit stops at once; when it ends, the merged
diagnostics of both phases are published again for the same version.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import os
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar
from urllib.parse import unquote, urlparse

from lsprotocol import types as lsp
from pygls.lsp.server import LanguageServer

from cncc import __version__
from cncc.lsp.guard import Gate, Job
from cncc.lsp.positions import LineIndex

if TYPE_CHECKING:  # the compiler side is imported on first use (or by the warm-up thread)
    from cncc.dialects import Dialect
    from cncc.lsp import convert
    from cncc.lsp.analysis import Analysis
    from cncc.lsp.config import Settings
    from cncc.source import SourceMap

T = TypeVar("T")
_log = logging.getLogger(__name__)
GUESS_HEAD_CHARS = 200_000  # what cncc.lsp.config.guess_dialect reads of a document (its sample)

WARM_UP_MODULES = ("cncc.lsp.handlers", "cncc.lsp.analysis", "cncc.lsp.machine_check", "cncc.frontend",
                   "cncc.frontend.fastpath", "cncc.frontend.macro.executor", "cncc.passes.expand_cycles",
                   "cncc.passes.arc_check", "cncc.backends.nominal", "cncc.driver")
"""What the first analysis needs, imported in a background thread once the client has said
``initialized`` (numpy and the planner are left to the second phase's own warm-up)."""


@dataclass(slots=True)
class DocState:
    uri: str
    version: int | None = None
    analysis: Analysis | None = None
    job: Job | None = None
    pending: asyncio.Task[None] | None = None
    machine_job: Job | None = None  # the second phase of the current analysis
    machine_task: asyncio.Task[None] | None = None
    ready: asyncio.Event = field(default_factory=asyncio.Event)
    config_error: str | None = None


class CnccServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__("cncc", __version__, text_document_sync_kind=lsp.TextDocumentSyncKind.Incremental)
        self.client_settings: dict[str, Any] = {}
        self._guesses: dict[str, tuple[Settings, str, str]] = {}  # uri -> (settings, text head, dialect)
        self.docs: dict[str, DocState] = {}
        self.root: str | None = None
        self.gate = Gate()  # background jobs wait while a first phase runs

    def warm_up(self) -> None:
        """Import the compiler side in a daemon thread (the first analysis then starts at once);
        an import that fails is left to the request that needs it, which reports it."""
        import threading

        def work() -> None:
            import importlib

            for name in WARM_UP_MODULES:
                with contextlib.suppress(Exception):
                    importlib.import_module(name)

        threading.Thread(target=work, name="cncc-lsp-warm-up", daemon=True).start()

    # ---- settings and dialects
    def doc_path(self, uri: str) -> str:
        parsed = urlparse(uri)
        return unquote(parsed.path) if parsed.scheme == "file" else ""

    def settings_for(self, uri: str) -> tuple[Settings, str | None]:
        from cncc.lsp.config import Settings, find_config, read_config

        path = self.doc_path(uri)
        settings = Settings(root=self.root or "")
        error = None
        if path:
            found = find_config(os.path.dirname(path), self.root)
            if found is not None:
                data, error = read_config(found)
                settings = settings.merged(data, root=os.path.dirname(found))
        if self.client_settings:
            settings = settings.merged(self.client_settings)
        return settings, error

    def dialect_name(self, uri: str, text: str, settings: Settings) -> str:
        """The document's dialect (:func:`cncc.lsp.config.guess_dialect`); the guess reads the
        head of the text only, so it is kept until that head or the settings change."""
        from cncc.lsp.config import guess_dialect

        head = text[:GUESS_HEAD_CHARS]
        got = self._guesses.get(uri)
        if got is not None and got[0] == settings and (got[1] == head or number_edit(got[1], head)):
            self._guesses[uri] = (settings, head, got[2])
            return got[2]
        name = guess_dialect(self.doc_path(uri) or uri, text, settings.dialect)
        if len(text) > GUESS_HEAD_CHARS:
            self._guesses[uri] = (settings, head, name)
        return name

    def dialect_of(self, uri: str, text: str) -> Dialect:
        from cncc.dialects import DialectError
        from cncc.lsp.config import DEFAULT_DIALECT, Settings, open_dialect

        settings, _ = self.settings_for(uri)
        try:
            return open_dialect(self.dialect_name(uri, text, settings), settings)
        except DialectError:
            return open_dialect(DEFAULT_DIALECT, Settings())

    # ---- analyses
    def state(self, uri: str) -> DocState:
        st = self.docs.get(uri)
        if st is None:
            st = self.docs[uri] = DocState(uri)
        return st

    def schedule(self, uri: str, version: int | None) -> None:
        st = self.state(uri)
        st.version = version
        st.ready.clear()
        if st.pending is not None and not st.pending.done():
            st.pending.cancel()
        if st.job is not None:
            st.job.cancel()
        self.stop_machine_phase(st)
        st.pending = asyncio.ensure_future(self._debounced(uri))

    def stop_machine_phase(self, st: DocState) -> None:
        """Stop the second phase now (it must not slow down the analysis of a new edit)."""
        if st.machine_task is not None and not st.machine_task.done():
            st.machine_task.cancel()
        if st.machine_job is not None:
            st.machine_job.cancel(grace_s=0.0)
            st.machine_job = None

    async def _debounced(self, uri: str) -> None:
        t_change = time.perf_counter()
        from cncc import diagnostics as dg
        from cncc.lsp.analysis import Request, analyze, new_analysis
        from cncc.lsp.incremental import resume
        from cncc.lsp.machine_check import wanted

        def incremental(old: Analysis, a: Analysis, check: Callable[[], None]) -> bool:
            try:
                return resume(old, a, check)
            except Exception:  # a bug in the resume must not cost the diagnostics: run in full
                import logging

                logging.getLogger(__name__).exception("incremental analysis failed; running in full")
                a.dialect = a.machine = None
                return False
        from cncc.source import Span

        settings, error = self.settings_for(uri)
        await asyncio.sleep(settings.debounce_ms / 1000.0)
        doc = self.workspace.get_text_document(uri)
        text = doc.source
        st = self.state(uri)
        req = Request(uri, self.doc_path(uri), st.version, text, self.dialect_name(uri, text, settings), settings)
        t_req = time.perf_counter()
        before = st.analysis if st.analysis is not None and st.analysis.request.uri == uri else None
        a = new_analysis(req, before)
        a.index.encoding = _encoding(self)
        marks = [t_req, time.perf_counter()]

        def work(check: Callable[[], None]) -> None:
            marks.append(time.perf_counter())
            if before is None or not incremental(before, a, check):
                analyze(a, check)
            marks.append(time.perf_counter())

        job = Job(work, settings.budget_s, gate=self.gate)
        st.job = job.start()
        try:
            reason = await asyncio.wrap_future(job.future)
        except asyncio.CancelledError:
            job.cancel()
            raise
        except Exception as exc:  # a compiler bug: say so in the document, keep serving
            a.diagnostics = [dg.Diagnostic(dg.BAD_OPTION, dg.Severity.ERROR, Span(0, 0, 0),
                                           f"cncc internal error while analysing: {type(exc).__name__}: {exc}")]
            reason = None
        if st.job is job:
            st.job = None
        if reason == "cancelled" or st.version != req.version:
            return
        a.stopped = reason
        if error:
            a.diagnostics.append(dg.Diagnostic(dg.BAD_OPTION, dg.Severity.WARNING, Span(0, 0, 0), error))
        st.analysis = a
        st.ready.set()
        self.publish(a)
        _log.info("%s v%s: %s in %.1f ms (%.1f ms since the change; steps %s)", uri, req.version,
                  f"lines {a.resumed[0] + 1}-{a.resumed[1]} re-run" if a.resumed else "full analysis",
                  a.elapsed_s * 1000, (time.perf_counter() - t_change) * 1000,
                  " ".join(f"{(t - t_change) * 1000:.1f}" for t in marks))
        if wanted(a):
            st.machine_task = asyncio.ensure_future(self._machine_phase(uri, a, before))

    async def _machine_phase(self, uri: str, a: Analysis, before: Analysis | None = None) -> None:
        from cncc import diagnostics as dg
        from cncc.lsp.machine_check import MachineCheck, machine_phase, region_first, warm_up
        from cncc.source import Span

        st = self.state(uri)
        if before is not None and a.region is not None:  # the changed region's checks first
            box: list[MachineCheck | None] = []
            quick = Job(lambda check: box.append(region_first(a, before, check)), a.request.settings.budget_s,
                        gate=self.gate, background=True, prelude=warm_up).start()
            st.machine_job = quick
            try:
                reason = await asyncio.wrap_future(quick.future)
            except asyncio.CancelledError:
                quick.cancel(grace_s=0.0)
                raise
            except Exception:  # a bug in the quick step: the full phase below still runs
                reason = "failed"
            if st.analysis is not a or reason == "cancelled":
                return
            if reason is None and box and box[0] is not None:
                a.machine_check = box[0]
                self.publish(a)
        m = MachineCheck()
        job = Job(lambda check: machine_phase(a, m, check), a.request.settings.budget_s, gate=self.gate,
                  background=True, prelude=warm_up)
        st.machine_job = job.start()
        try:
            reason = await asyncio.wrap_future(job.future)
        except asyncio.CancelledError:
            job.cancel(grace_s=0.0)
            raise
        except Exception as exc:  # a compiler bug: say so in the document, keep serving
            m.diagnostics.append(dg.Diagnostic(dg.BAD_OPTION, dg.Severity.ERROR, Span(0, 0, 0),
                                               f"cncc internal error in the machine checks: "
                                               f"{type(exc).__name__}: {exc}"))
            reason = None
        if st.machine_job is job:
            st.machine_job = None
        if reason == "cancelled" or st.analysis is not a:
            return
        m.stopped = reason
        a.machine_check = m
        if m.line_time_s is not None:
            a.line_time_s = m.line_time_s
        self.publish(a)

    def publish(self, a: Analysis) -> None:
        from cncc import diagnostics as dg
        from cncc.lsp import convert
        from cncc.source import Span

        settings = a.request.settings
        index, uri = a.index, a.request.uri
        items = convert.diagnostics(index, uri, a.diagnostics, settings.max_diagnostics, files_of(a.sources, index))
        m = a.machine_check
        if m is not None:
            items += convert.diagnostics(index, uri, m.diagnostics, settings.max_diagnostics - len(items),
                                         files_of(m.sources, index))
        if a.stopped:
            line = index.line_of(a.reached)
            items.append(convert.diagnostic(index, uri, dg.Diagnostic(
                dg.ANALYSIS_STOPPED, dg.Severity.NOTE, Span(0, a.reached, a.reached),
                f"analysis stopped after {settings.budget_s:g} s at line {line + 1} ({a.stopped}); "
                "the lines below were not checked")))
        if m is not None and m.stopped:
            items.append(convert.diagnostic(index, uri, dg.Diagnostic(
                dg.ANALYSIS_STOPPED, dg.Severity.NOTE, Span(0, 0, 0),
                f"machine checks stopped after {settings.budget_s:g} s while {m.step} ({m.stopped}); "
                "raise budget_s to see them all")))
        self.text_document_publish_diagnostics(
            lsp.PublishDiagnosticsParams(uri=a.request.uri, diagnostics=items, version=a.request.version))
        caps = self.client_capabilities.workspace
        if caps is not None and caps.inlay_hint is not None and caps.inlay_hint.refresh_support:
            self.workspace_inlay_hint_refresh(None)

    async def current(self, uri: str, wait_s: float = 5.0) -> Analysis | None:
        """The analysis of the document's current version (waiting for it a while)."""
        st = self.docs.get(uri)
        if st is None:
            return None
        if not st.ready.is_set():
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(st.ready.wait(), wait_s)
        return st.analysis

    async def guarded(self, work: Callable[[Callable[[], None]], T], budget_s: float) -> T | None:
        """Run ``work(check)`` in a guarded thread; None if it was stopped."""
        box: list[T] = []
        job = Job(lambda check: box.append(work(check)), budget_s).start()
        reason = await asyncio.wrap_future(job.future)
        return box[0] if box and reason is None else None

    def text_and_index(self, uri: str) -> tuple[str, LineIndex]:
        text = self.workspace.get_text_document(uri).source
        return text, LineIndex(text, _encoding(self))


_NUMBER_CHARS = frozenset("0123456789.+- \t")
_VALUE_LETTERS = frozenset("XYZABCUVWIJKRFQxyzabcuvwijkrfq")


def number_edit(old: str, new: str) -> bool:
    """Whether ``new`` differs from ``old`` only inside the number of an axis, arc or feed word
    (``X12.5`` -> ``X12.55``): no dialect guess reads those values."""
    from cncc.lsp.incremental import changed_range

    prefix, suffix = changed_range(old, new)
    a, b = old[prefix:len(old) - suffix], new[prefix:len(new) - suffix]
    if len(a) > 32 or len(b) > 32 or not _NUMBER_CHARS.issuperset(a) or not _NUMBER_CHARS.issuperset(b):
        return False
    i = prefix
    while i > 0 and new[i - 1] in "0123456789.+-":
        i -= 1
    return i > 0 and new[i - 1] in _VALUE_LETTERS and " " not in a + b and "\t" not in a + b


def files_of(sources: SourceMap | None, index: LineIndex) -> convert.Files:
    """Where the diagnostics' other source ids (called programs) are: their URI and lines."""
    cache: dict[int, tuple[str, LineIndex] | None] = {}

    def find(source_id: int) -> tuple[str, LineIndex] | None:
        if source_id not in cache:
            src = sources.get(source_id) if sources is not None and source_id > 0 else None
            if src is None or not os.path.isabs(src.name):
                cache[source_id] = None
            else:
                cache[source_id] = (Path(src.name).as_uri(), LineIndex(src.text, index.encoding))
        return cache[source_id]

    return find


def _encoding(server: LanguageServer) -> str:
    try:
        enc = server.workspace.position_encoding
    except RuntimeError:
        return "utf-16"
    return str(enc or "utf-16").lower().replace("utf16", "utf-16").replace("utf8", "utf-8").replace("utf32", "utf-32")


def build() -> CnccServer:
    from cncc.lsp import features

    server = CnccServer()
    features.register(server)
    return server
