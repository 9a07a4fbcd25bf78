"""Code actions as text edits: insert a feed, repair an arc centre, convert a selection.

Each function returns ``(title, edits)`` with edits as ``(start, end, new_text)``
character offsets; the server turns them into a ``WorkspaceEdit``.

* **Insert a feed** where a feed move has no F (E0211) or runs on the dialect's
  default feed (N0212): the last positive F programmed above, else the dialect
  default when it is positive; no action when neither is known (an ``F0`` would
  only trade one error for another).
* **Repair an arc centre** (E0208): the arc-check pass's repair (centre moved onto
  the chord's bisector keeping the start radius) written back as I/J/K words.
* **Convert a selection** to another dialect: the compiled commands of the selected
  blocks, emitted by the G-code backend for that dialect.  Every axis and feed word
  written in a selected block is written again (the emitter alone would drop a word
  whose value equals the position it believes in force); a selection with an error
  in it is refused (:func:`refusal`), since its broken blocks produce no commands
  and would silently disappear.
"""

from __future__ import annotations

import bisect
from collections.abc import Sequence

from cncc.dialects import CodeDef, Dialect
from cncc.ir import Arc, Command, Plane
from cncc.lsp.positions import LineIndex
from cncc.lsp.scan import Comments, code_part, tokens

Edit = tuple[int, int, str]
CENTER_LETTERS = {Plane.XY: ("I", "J"), Plane.ZX: ("K", "I"), Plane.YZ: ("J", "K")}


def number_text(value: float, decimals: int = 4) -> str:
    """A number always written with a decimal point (so no least-input-unit reading)."""
    text = f"{value:.{decimals}f}".rstrip("0")
    if text in ("-0.", "-0"):
        text = "0."
    return text


def block_end_offset(index: LineIndex, dialect: Dialect, line: int) -> int:
    """Where a new word goes: right after the last word of the line's block."""
    base = index.line_start(line)
    text = index.line_text(line)
    last = None
    for tok in tokens(text, base, Comments.of(dialect)):
        last = tok
    if last is not None:
        return last.end
    pieces = code_part(text, Comments.of(dialect))
    end = pieces[0][1] if pieces else 0
    return base + len(text[:end].rstrip(" \t;"))


def insert_feed(index: LineIndex, dialect: Dialect, offset: int) -> tuple[str, list[Edit]] | None:
    """Append the feed in force above (a positive number) to the block at ``offset``; None
    when no positive feed is known."""
    line = index.line_of(offset)
    comments = Comments.of(dialect)
    feed: str | None = None
    for ln in range(line - 1, max(-1, line - 20_000), -1):
        text = index.line_text(ln)
        if "F" not in text and "f" not in text:
            continue
        found = [t for t in tokens(text, 0, comments)
                 if t.kind == "word" and t.text == "F" and (t.number or 0.0) > 0.0]
        if found:
            feed = found[-1].value
            break
    if feed is None:
        if dialect.default_feed_mm_min <= 0.0:
            return None
        feed = number_text(dialect.default_feed_mm_min, 1)
    at = block_end_offset(index, dialect, line)
    return f"Insert feed F{feed}", [(at, at, f" F{feed}")]


def repair_arc(index: LineIndex, dialect: Dialect, arc: Arc) -> tuple[str, list[Edit]] | None:
    """Rewrite the centre words of ``arc``'s block to the repaired centre."""
    plane = arc.plane
    if plane not in CENTER_LETTERS:
        return None
    letters = CENTER_LETTERS[plane]
    scale = arc.frame.units.mm_per_unit
    values = ((arc.center[plane.first] - arc.start[plane.first]) / scale,
              (arc.center[plane.second] - arc.start[plane.second]) / scale)
    line = index.line_of(arc.span.start)
    base = index.line_start(line)
    toks = [t for t in tokens(index.line_text(line), base, Comments.of(dialect))
            if t.kind == "word" and arc.span.start <= t.start < max(arc.span.end, t.start + 1)]
    if any(t.text == "R" for t in toks):
        return None
    edits: list[Edit] = []
    missing = []
    for letter, value in zip(letters, values, strict=True):
        word = next((t for t in toks if t.text == letter), None)
        new = f"{letter}{number_text(value)}"
        if word is not None:
            edits.append((word.start, word.end, new))
        else:
            missing.append(new)
    if missing:
        at = block_end_offset(index, dialect, line)
        feed = next((t for t in toks if t.text == "F"), None)
        if feed is not None:
            at = feed.start
            edits.append((at, at, " ".join(missing) + " "))
        else:
            edits.append((at, at, " " + " ".join(missing)))
    shown = " ".join(f"{a}{number_text(v)}" for a, v in zip(letters, values, strict=True))
    return f"Repair arc centre ({shown})", edits


PREAMBLE_OPS = frozenset({"plane_xy", "plane_zx", "plane_yz", "metric", "inch", "absolute", "incremental",
                          "feed_per_min", "feed_per_rev", "inverse_time"})
"""Ops of the modes the G-code emitter states before a program (its preamble)."""


def convert_selection(index: LineIndex, commands: Sequence[Command], first_line: int, last_line: int,
                      source: Dialect, target: Dialect) -> tuple[str, list[Edit]] | None:
    """Replace whole lines ``first_line..last_line`` by their commands emitted for ``target``.

    The emitter writes a whole program: ``%`` lines, and a preamble that states the plane,
    units, distance and feed modes it then relies on.  Inside a document, only the preamble
    codes whose mode differs from the one in force above the selection are kept (the emitter
    writes absolute coordinates, so under G91 the selection starts with the target's G90),
    and after the selection the target's codes restore the modes the document has in force
    there (the selection's own G91, say)."""
    from cncc.lsp.complete import modal_context

    lo = index.line_start(first_line)
    hi = index.line_end(last_line)
    chosen = [c for c in commands if lo <= c.span.start < hi or (c.span.start <= lo < c.span.end)]
    if not chosen:
        return None
    lines = [ln.rstrip("\n") for ln in _emit(chosen, target, explicit_words(index, source, first_line, last_line))
             if ln.strip() != "%"]
    state = {g: c.op for g, c in modal_context(index, source, first_line).items()}
    at = next((i for i, ln in enumerate(lines) if _mode_words(ln, target, only=True)), None)
    if at is not None:
        planes = {_PLANE_OPS[c.frame.plane] for c in chosen if c.frame.plane in _PLANE_OPS}
        kept = [(w, c) for w, c in _mode_words(lines[at], target, only=True)
                if state.get(c.group, c.op) != c.op and (c.group != "plane" or c.op in planes)]
        lines[at:at + 1] = [" ".join(w for w, _ in kept)] if kept else []
    for ln in lines:  # the modes in force at the end of the replacement
        for _w, c in _mode_words(ln, target, only=False):
            state[c.group] = c.op
    after = {g: c.op for g, c in modal_context(index, source, last_line + 1).items()}
    restore = []
    for group, op in state.items():
        want = after.get(group)
        if want is not None and want != op and group in _MODE_GROUPS:
            back = next((c for c in target.codes.values() if c.op == want), None)
            if back is not None:
                restore.append(back.name)
    if restore:
        lines.append(" ".join(restore))
    return f"Convert selection to {target.name} ({target.title})", [(lo, hi, "\n".join(lines))]


def refusal(errors: Sequence[tuple[int, str]], lo: int, hi: int) -> str | None:
    """Why a selection ``lo..hi`` (offsets) cannot be converted: the first error in it, given
    as (offset, message) pairs; None when it has none."""
    for at, message in sorted(errors):
        if lo <= at <= hi:
            return f"the selection has an error (converting it would drop that block): {message}"
    return None


def explicit_words(index: LineIndex, dialect: Dialect, first_line: int, last_line: int
                   ) -> dict[int, frozenset[str]]:
    """Line start offset -> the axis and feed letters written on that line."""
    comments = Comments.of(dialect)
    out: dict[int, frozenset[str]] = {}
    for line in range(first_line, last_line + 1):
        letters = frozenset(t.text for t in tokens(index.line_text(line), 0, comments)
                            if t.kind == "word" and t.value and t.text in "XYZABCF")
        if letters:
            out[index.line_start(line)] = letters
    return out


def _emit(cmds: Sequence[Command], target: Dialect, explicit: dict[int, frozenset[str]]) -> list[str]:
    """The emitter's lines for ``cmds``, writing again every axis and feed word that the source
    block of a command wrote (``explicit``: by the offset of the block's line)."""
    from cncc.backends.gcode.emit import AXES, GcodeEmitter
    from cncc.ir import Vec6

    starts = sorted(explicit)

    def written(em: GcodeEmitter) -> frozenset[str]:
        at = bisect.bisect_right(starts, em.span.start) - 1
        return explicit[starts[at]] if at >= 0 and em.span.source_id == 0 else frozenset()

    class KeepWords(GcodeEmitter):
        def _axes(self, start: Vec6, end: Vec6, always: tuple[int, ...] = ()) -> list[str]:
            keep = written(self)
            forced = tuple(i for i, letter in enumerate(AXES) if letter in keep)
            return super()._axes(start, end, tuple(sorted({*always, *forced})))

        def _feed_word(self, feed_mm_min: float) -> str:
            if "F" in written(self):
                self.feed = None
            return super()._feed_word(feed_mm_min)

    return list(KeepWords(target).emit(cmds))


_MODE_GROUPS = frozenset({"plane", "units", "distance", "feed_mode"})
# The emitter writes a plane code before a command whose plane differs from the one it believes
# in force, so its preamble plane matters only for commands in that very plane.
_PLANE_OPS = {Plane.XY: "plane_xy", Plane.ZX: "plane_zx", Plane.YZ: "plane_yz"}


def _mode_words(line: str, target: Dialect, only: bool) -> list[tuple[str, CodeDef]]:
    """The mode codes (plane, units, distance, feed mode) of an emitted ``line``; with ``only``,
    empty unless the line has nothing else (the emitter's preamble)."""
    from cncc.dialects import code_tenths

    out = []
    for w in line.split():
        cdef = None
        if len(w) > 1 and w[0] in "Gg":
            try:
                cdef = target.code("G", code_tenths(w[1:]))
            except ValueError:
                cdef = None
        if cdef is not None and cdef.op in PREAMBLE_OPS and cdef.group in _MODE_GROUPS:
            out.append((w, cdef))
        elif only:
            return []
    return out
