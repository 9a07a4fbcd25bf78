"""Diagnostics as text, gcc style: ``file:line:col: error: message [E0201]``,
the source line and a caret under the span, then related spans as notes.

The first line of each diagnostic matches the problem matchers written for gcc
(``^(.*):(\\d+):(\\d+):\\s+(warning|error|note):\\s+(.*)$``); a diagnostic without a
position starts with ``cncc:`` as gcc's driver messages do.  Colours follow
``-fdiagnostics-color`` (:mod:`cncc.colors`).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from cncc.colors import Palette
from cncc.diagnostics import Diagnostic
from cncc.source import SourceMap, Span

PLAIN = Palette()


def _location(sources: SourceMap, span: Span, pal: Palette) -> tuple[str, str]:
    src = sources.get(span.source_id)
    if src is None:
        return "cncc", ""
    pos = src.position(min(span.start, len(src.text)))
    line = src.line_text(pos.line)
    shown = line.expandtabs(1)
    if len(shown) > 200:
        lo = max(0, pos.column - 80)
        shown = shown[lo: lo + 160]
        col = pos.column - lo
    else:
        col = pos.column
    width = max(1, min(span.end - span.start, len(shown) - col + 1))
    printable = "".join(ch if ch.isprintable() else "?" for ch in shown)
    caret = " " * (col - 1) + pal.paint("caret", "^" + "~" * (width - 1))
    return f"{src.name}:{pos.line}:{pos.column}", f"  {printable}\n  {caret}\n"


def render(diag: Diagnostic, sources: SourceMap, pal: Palette = PLAIN) -> Iterator[str]:
    where, excerpt = _location(sources, diag.span, pal)
    label = diag.severity.label
    yield (f"{pal.paint('locus', where + ':')} {pal.paint(label, label + ':')} {diag.message} "
           f"[{pal.paint(label, diag.code)}]\n")
    yield excerpt
    for rel in diag.related:
        rwhere, rexcerpt = _location(sources, rel.span, pal)
        yield f"{pal.paint('locus', rwhere + ':')} {pal.paint('note', 'note:')} {rel.message}\n"
        yield rexcerpt


def by_position(diags: Iterable[Diagnostic]) -> list[Diagnostic]:
    """Diagnostics without a position first (as reported), then per file in file order, by position.

    The sort is stable: diagnostics at the same place keep the order the stages reported them in.
    """
    return sorted(diags, key=lambda d: (d.span.source_id, d.span.start) if d.span.source_id >= 0 else (-1, 0))
