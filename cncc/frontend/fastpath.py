"""The plain-block fast path of the front end.

CAM output is mostly blocks like ``N120 G01 X12.5 Y-3.25 Z-1. F800``.  For a
straight-line program (no macro statements, calls or jumps anywhere), lines that
match :data:`CAM_LINE` in that canonical word order are lowered here directly to
``Rapid``/``Linear`` commands, without building syntax nodes, when the modal state
makes the meaning unambiguous (no canned cycle, motion mode G00/G01, a feed already
programmed, feed per minute, program not ended).  Every other line goes through the
grammar and the interpreter as usual.

``tests/frontend/test_fastpath.py`` checks that both paths lower every test program
and generated programs to identical commands and diagnostics.

With :class:`Checkpoints` (the language server's incremental analysis) the run can
start at a line with a given interpreter, and it shows the interpreter, its state
written back, to a callback at the first line at or after every ``every``-th line.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterator
from dataclasses import dataclass

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.parser import MAX_LINE_CHARS, ParseOptions, Parser
from cncc.ir import PROGRAMMED, Arc, Command, FeedRate, Linear, Plane
from cncc.ir.fastnew import new_rapid, new_span
from cncc.source import SourceFile, Span

_NUM = r"([-+]?[\d.]{1,12}+)"  # longer numbers take the general path, which refuses overflowing ones
CAM_LINE = re.compile(
    rf"(?:N\d+ *)?(?:G0*([0-3]) *)?(?:X{_NUM} *)?(?:Y{_NUM} *)?(?:Z{_NUM} *)?(?:I{_NUM} *)?(?:J{_NUM} *)?"
    rf"(?:F([\d.]{{1,12}}+) *)?(;?) *\r?"
)
CAM_LINES = re.compile("^" + CAM_LINE.pattern + "$", re.MULTILINE)
"""A plain motion block in canonical order.  The number pattern is loose on purpose
(it is fast): a value that ``float()`` rejects (``1.2.3``, ``.``) sends the line to
the general path, which reports it."""

_MOTION_OF = {"0": "rapid", "1": "linear", "2": "arc_cw", "3": "arc_ccw"}
_CODE_OF = {"rapid": "G00", "linear": "G01", "arc_cw": "G02", "arc_ccw": "G03"}


def _control_codes(dialect: Dialect) -> re.Pattern[str]:
    """Codes that call, return or jump (M98, M99, G65, G66 ...), on upper-case text."""
    return dialect.derived("fastpath.control_codes", _build_control_codes)


def _build_control_codes(dialect: Dialect) -> re.Pattern[str]:
    from cncc.frontend.macro.executor import EXEC_OPS

    alts = [r"M[ \t]*0*[12]8\d\d(?![\d.])"]
    for c in dialect.codes.values():
        if c.op in EXEC_OPS:
            whole, frac = divmod(c.tenths, 10)
            alts.append(f"{c.letter}[ \t]*0*{whole}" + (rf"\.{frac}" if frac else r"(?![\d.])"))
    return re.compile("|".join(alts))


@dataclass(slots=True)
class Checkpoints:
    """Where :func:`lower_straight` starts, and whom it shows its state every ``every`` lines.

    ``on_line(line, offset, it)`` is called at the start of a plain line (0-based ``line`` at
    character ``offset``) once ``line`` reaches the next multiple of ``every``, before that line
    runs, with the interpreter's state complete (the fast path's cached state written back)."""

    on_line: Callable[[int, int, Interpreter], None]
    every: int = 256
    interp: Interpreter | None = None  # resume with this interpreter ...
    start: int = 0  # ... at this line start (an offset) ...
    line: int = 0  # ... which is this 0-based line


def is_straight_line(text: str, dialect: Dialect) -> bool:
    """True when the program has no macro syntax, calls or jumps at all, and the
    dialect reads plain blocks the Fanuc way (``fast_path = false`` in a dialect
    file turns the fast path off, e.g. for unsigned single-quadrant arc centres).

    Conservative: a comment that merely contains a keyword sends the program down
    the general path, which is always correct, only slower.
    """
    if not dialect.raw.get("fast_path", True):
        return False
    if "#" in text or "[" in text or "=" in text or "<" in text:
        return False
    upper = text.upper()
    if any(kw in upper for kw in dialect.lexicon.executor_marks):  # the dialect's macro statements
        return False
    return _control_codes(dialect).search(upper) is None


def lower_straight(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, opts: InterpOptions,
                   checkpoints: Checkpoints | None = None) -> Iterator[Command]:
    """Lower a straight-line program, taking the fast path where it applies.

    The interpreter's state is cached in locals while consecutive lines take the
    fast path, and written back before any line goes through the general path.
    """
    parser = Parser(dialect, sink, ParseOptions(strict=opts.strict))
    cp = checkpoints
    it = cp.interp if cp is not None and cp.interp is not None else Interpreter(dialect, sink, src.source_id, opts)
    pos = cp.start if cp is not None else 0
    line_no = cp.line if cp is not None else 0
    return lower_lines(parser, it, src, pos, line_no, cp)


@dataclass(slots=True)
class Resume:
    """Where :func:`lower_lines` stopped after ``streak`` plain lines in a row (``stopped``), so
    that a caller (:mod:`cncc.frontend.fastbatch`) can take over at ``pos`` / ``line_no``."""

    streak: int = 0  # stop before the next plain line once this many went in a row (0: never)
    stopped: bool = False
    pos: int = 0
    line_no: int = 0


def lower_lines(  # noqa: C901 - one inlined hot loop: a call per line would cost a third of its time
    parser: Parser, it: Interpreter, src: SourceFile, pos: int, line_no: int, cp: Checkpoints | None = None,
    resume: Resume | None = None,
) -> Iterator[Command]:
    """The lines of ``src`` from offset ``pos`` (0-based line ``line_no``) through ``it``; with
    ``resume``, stop (state written back) before a plain line once ``resume.streak`` plain lines
    in a row took the fast path."""
    dialect = parser.dialect
    text = src.text
    sid = src.source_id
    finditer = CAM_LINES.finditer
    semicolon_ok = dialect.block_end == ";"
    new = object.__new__
    sp_id, sp_start, sp_end = _SPAN_SET
    l_span, l_frame, l_start, l_end, l_feed, l_motion, l_origin = _LINEAR_SET
    n = len(text)
    streak_limit = resume.streak if resume is not None else 0
    streak = 0
    next_cp = line_no if cp is not None else n + 1  # the next line to show the state at
    every = max(1, cp.every) if cp is not None else 1
    stale = True
    dirty = False  # the locals hold modes not yet written back to the interpreter
    feed_prog: float | None = None
    # cached interpreter state (valid while ``stale`` is False)
    ok = False
    cur = ""
    inc = False
    feed_mm_min = 0.0
    path = it.modal.path
    frame = it.frame
    k_int = k_pt = 1.0
    p = it.pos
    for m in finditer(text, pos):
        start = m.start()
        if start >= n:
            break
        if streak >= streak_limit > 0 and start == pos and not stale and resume is not None:
            it.pos = p
            if dirty:
                _write_back(it, cur, feed_prog)
            resume.stopped, resume.pos, resume.line_no = True, pos, line_no
            return
        if start != pos:  # the lines in between do not match: general path
            streak = 0
            if not stale:
                it.pos = p
            if dirty:
                _write_back(it, cur, feed_prog)
                dirty = False
            yield from _general(parser, it, src, pos, start, line_no)
            line_no += text.count("\n", pos, start)
            pos = start
            stale = True
        if line_no >= next_cp and cp is not None:
            if not stale:
                it.pos = p
            if dirty:
                _write_back(it, cur, feed_prog)
                dirty = False
            stale = True
            cp.on_line(line_no, pos, it)
            next_cp = (line_no // every + 1) * every
        end = m.end()
        line_no += 1
        if stale:
            modal = it.modal
            ok = not (it.ended or modal.cycle or modal.per_rev or it.frame.polar is not None)  # G16: polar words
            cur = modal.motion
            inc = modal.incremental
            frame = it.frame
            rd = it.reader
            k_pt = rd.mm_per_unit
            k_int = rd.liu_length_mm if rd.liu_rule else k_pt
            feed_prog = modal.feed
            feed_mm_min = -1.0 if feed_prog is None else feed_prog * k_pt
            path = modal.path
            p = it.pos
            holding = not inc and True in frame.held_axes[:3]  # absolute words release them (ops._release_named)
            stale = False
        if ok and end - pos <= MAX_LINE_CHARS:
            g, xs, ys, zs, is_, js, fs, semi = m.groups()
            motion = cur if g is None else _MOTION_OF[g]
            if ((xs is not None or ys is not None or zs is not None) and (semicolon_ok or not semi)
                    and (fs is not None or feed_mm_min > 0.0 or motion == "rapid")
                    and (motion == "linear" or motion == "rapid" if is_ is None and js is None
                         else (motion == "arc_cw" or motion == "arc_ccw") and zs is None
                         and frame.plane is Plane.XY)):
                try:  # every number first: one that float() rejects sends the line to the general path
                    x, y, z = p[0], p[1], p[2]
                    if xs is not None:
                        v = float(xs) * (k_pt if "." in xs else k_int)
                        x = x + v if inc else v
                    if ys is not None:
                        v = float(ys) * (k_pt if "." in ys else k_int)
                        y = y + v if inc else v
                    if zs is not None:
                        v = float(zs) * (k_pt if "." in zs else k_int)
                        z = z + v if inc else v
                    f_new = float(fs) if fs is not None else -1.0
                    if f_new == 0.0 and motion != "rapid":
                        raise ValueError("F0 on a feed move: the general path reports it")
                    ci, cj = p[0], p[1]
                    if is_ is not None:
                        ci += float(is_) * (k_pt if "." in is_ else k_int)
                    if js is not None:
                        cj += float(js) * (k_pt if "." in js else k_int)
                    if (is_ is not None or js is not None) and ci == p[0] and cj == p[1]:
                        raise ValueError("zero-radius arc: the general path reports it")
                except ValueError:
                    pass
                else:
                    if motion != cur:
                        cur = motion
                        dirty = True
                    q = (x, y, z, p[3], p[4], p[5])
                    if fs is not None:
                        feed_prog = f_new
                        feed_mm_min = f_new * k_pt
                        dirty = True
                        yield FeedRate(new_span(sid, m.start(7) - 1, m.end(7)), frame, feed_mm_min, False)
                    if holding:
                        held = frame.held_axes
                        named = [k for k, text in ((0, xs), (1, ys), (2, zs)) if text is not None and held[k]]
                        if named:
                            it.release_axes(named)
                            frame = it.frame
                            holding = True in frame.held_axes[:3]
                    span = new(Span)
                    sp_id(span, sid)
                    sp_start(span, pos)
                    sp_end(span, end)
                    if motion == "linear":
                        cmd = new(Linear)
                        l_span(cmd, span)
                        l_frame(cmd, frame)
                        l_start(cmd, p)
                        l_end(cmd, q)
                        l_feed(cmd, feed_mm_min)
                        l_motion(cmd, path)
                        l_origin(cmd, PROGRAMMED)
                        yield cmd
                    elif motion == "rapid":
                        yield new_rapid(span, frame, p, q, path)
                    else:
                        yield Arc(span, frame, p, q, (ci, cj, p[2], p[3], p[4], p[5]),
                                  -1 if motion == "arc_cw" else 1, Plane.XY, feed_mm_min, path)
                    p = q
                    pos = end + 1
                    streak += 1
                    continue
        streak = 0
        if end > pos:
            if not stale:
                it.pos = p
            if dirty:
                _write_back(it, cur, feed_prog)
                dirty = False
            for block in parser.blocks_of_line(src, pos, end, line_no):
                yield from it.execute(block)
            stale = True
        pos = end + 1
    if not stale:
        it.pos = p
    if dirty:
        _write_back(it, cur, feed_prog)
    if pos < n:
        yield from _general(parser, it, src, pos, n, line_no)


def _general(parser: Parser, it: Interpreter, src: SourceFile, pos: int, stop: int, line_no: int) -> Iterator[Command]:
    """Lower the lines in ``src.text[pos:stop]`` through the grammar and the interpreter."""
    text = src.text
    while pos < stop:
        nl = text.find("\n", pos, stop)
        end = stop if nl < 0 else nl
        line_no += 1
        if end > pos:
            for block in parser.blocks_of_line(src, pos, end, line_no):
                yield from it.execute(block)
        pos = end + 1


def _write_back(it: Interpreter, motion: str, feed: float | None) -> None:
    """Store the modes the fast path changed into the interpreter's modal state."""
    it.modal = it.modal.with_(motion=motion, feed=feed)
    it.group_codes["motion"] = _CODE_OF[motion]


_SPAN_SET = tuple(getattr(Span, f).__set__ for f in ("source_id", "start", "end"))
_LINEAR_SET = tuple(getattr(Linear, f).__set__ for f in ("span", "frame", "start", "end", "feed_mm_min", "motion",
                                                         "origin"))
