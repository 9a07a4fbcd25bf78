"""A controller's own error texts for cncc's diagnostics (a dialect's ``[errors]`` table).

Keys are diagnostic codes (``E0505``), optionally refined by a word of cncc's message
(``E0503:cancelled`` is used only when the message contains "cancelled"; refined keys
win over the plain code).  ``{0}`` in a text is the detail the emitter passed (or the
first single capital letter of cncc's message), ``{lower}`` the same in lower case.
Other keys (no ``E``/``W``/``N`` code shape) are looked up by name by the front ends.

:class:`ControllerSink` forwards to another sink with the message rewritten as
``"<controller text> (<cncc's message>)"``: the controller's text first, so that a
user can grep for it, and cncc's explanation after it.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink, Related, Severity
from cncc.source import Span

_DETAIL = re.compile(r"\b([A-Z])\b")
_CODE = re.compile(r"^[EWN]\d{4}")


class ControllerTexts:
    def __init__(self, table: Mapping[str, object]) -> None:
        self.plain: dict[str, str] = {}
        self.refined: dict[str, list[tuple[str, str]]] = {}
        for key, text in table.items():
            if not _CODE.match(key):
                continue
            code, _, word = key.partition(":")
            if word:
                self.refined.setdefault(code, []).append((word, str(text)))
            else:
                self.plain[code] = str(text)

    def __bool__(self) -> bool:
        return bool(self.plain or self.refined)

    def text(self, code: str, message: str, detail: str = "") -> str | None:
        """The controller's text for ``code`` given cncc's ``message``, or None."""
        text = next((t for w, t in self.refined.get(code, ()) if w in message), None)
        text = text if text is not None else self.plain.get(code)
        if text is None or "{" not in text:
            return text
        if not detail:
            m = _DETAIL.search(message)
            detail = m.group(1) if m else "?"
        return text.format(detail, lower=detail.lower())

    def message(self, code: str, message: str, detail: str = "") -> str:
        text = self.text(code, message, detail)
        return message if text is None else f"{text} ({message})"


class ControllerSink(DiagnosticSink):
    """Forwards to ``inner`` with the controller's error texts; counts the errors it passed on."""

    def __init__(self, inner: DiagnosticSink, texts: ControllerTexts) -> None:
        super().__init__()
        self.inner, self.texts, self.errors = inner, texts, 0

    def emit(self, code: str, span: Span, message: str, related: tuple[Related, ...] = (),
             severity: Severity | None = None, detail: str = "") -> None:
        message = self.texts.message(code, message, detail)
        info = dg.CODES.get(code)
        if (severity or (info.severity if info else Severity.ERROR)) is Severity.ERROR:
            self.errors += 1
        self.inner.emit(code, span, message, related, severity)


def controller_sink(inner: DiagnosticSink, table: Mapping[str, object] | None) -> DiagnosticSink:
    """``inner`` wrapped with the texts of ``table`` (a dialect's ``[errors]``), or ``inner`` itself."""
    texts = ControllerTexts(table or {})
    return ControllerSink(inner, texts) if texts else inner
