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
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from cncc.dialects import Dialect
from cncc.diagnostics import DiagnosticSink
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.parser import MAX_LINE_CHARS, ParseOptions, Parser
from cncc.ir import Arc, Command, FeedRate, Plane
from cncc.ir.fastnew import new_linear, new_rapid, new_span
from cncc.source import SourceFile

_NUM = r"([-+]?(?:\d+\.?\d*|\.\d+))"
CAM_LINE = re.compile(
    rf"(?:N\d+[ \t]*)?(?:G0*([0-3])(?![\d.])[ \t]*)?(?:X{_NUM}[ \t]*)?(?:Y{_NUM}[ \t]*)?(?:Z{_NUM}[ \t]*)?"
    rf"(?:I{_NUM}[ \t]*)?(?:J{_NUM}[ \t]*)?(?:F((?:\d+\.?\d*|\.\d+))[ \t]*)?(;?)[ \t]*\r?"
)
"""A plain motion block in canonical order; the numbers must end the word."""

_MOTION_OF = {"0": "rapid", "1": "linear", "2": "arc_cw", "3": "arc_ccw"}
_CODE_OF = {"rapid": "G00", "linear": "G01", "arc_cw": "G02", "arc_ccw": "G03"}
_CALL_HINT = re.compile(r"[MG]0*(?:9[89]|6[5-7]|22|800)(?![\d.])")
_KEYWORDS = ("GOTO", "WHILE", "IF", "WAT", "OUT", "FILE", "MSG", "STAF", "SUB", "CALL", "REPEAT", "ELSE", "BREAK",
             "CONTINUE")


def is_straight_line(text: str) -> bool:
    """True when the program has no macro syntax, calls or jumps at all."""
    if "#" in text or "[" in text or "=" in text or "<" in text:
        return False
    upper = text.upper()
    if any(kw in upper for kw in _KEYWORDS):
        return False
    return _CALL_HINT.search(upper) is None


def lower_straight(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, opts: InterpOptions) -> Iterator[Command]:
    """Lower a straight-line program, taking the fast path where it applies."""
    parser = Parser(dialect, sink, ParseOptions(strict=opts.strict))
    it = Interpreter(dialect, sink, src.source_id, opts)
    text = src.text
    sid = src.source_id
    fullmatch = CAM_LINE.fullmatch
    semicolon_ok = dialect.block_end == ";"
    n = len(text)
    pos = 0
    line_no = 0
    while pos < n:
        nl = text.find("\n", pos)
        end = n if nl < 0 else nl
        line_no += 1
        m = fullmatch(text, pos, end) if end - pos <= MAX_LINE_CHARS else None
        if m is not None:
            g, xs, ys, zs, is_, js, fs, semi = m.groups()
            if (xs is not None or ys is not None or zs is not None) and (semicolon_ok or not semi):
                modal = it.modal
                if not (it.ended or modal.cycle or modal.per_rev or (modal.feed is None and fs is None)):
                    motion = modal.motion if g is None else _MOTION_OF[g]
                    arc = motion == "arc_cw" or motion == "arc_ccw"
                    if (arc and (zs is not None or (is_ is None and js is None) or it.frame.plane is not Plane.XY)) or (
                            not arc and (is_ is not None or js is not None)) or motion not in _MOTION_OF.values():
                        motion = ""  # not for the fast path
                    if motion:
                        if motion != modal.motion:
                            it.modal = modal = modal.with_(motion=motion)
                            it.group_codes["motion"] = _CODE_OF[motion]
                        rd = it.reader
                        p = it.pos
                        x, y, z = p[0], p[1], p[2]
                        k_int = rd.liu_length_mm if rd.liu_rule else rd.mm_per_unit
                        k_pt = rd.mm_per_unit
                        inc = modal.incremental
                        if xs is not None:
                            v = float(xs) * (k_pt if "." in xs else k_int)
                            x = x + v if inc else v
                        if ys is not None:
                            v = float(ys) * (k_pt if "." in ys else k_int)
                            y = y + v if inc else v
                        if zs is not None:
                            v = float(zs) * (k_pt if "." in zs else k_int)
                            z = z + v if inc else v
                        new = (x, y, z, p[3], p[4], p[5])
                        frame = it.frame
                        if fs is not None:
                            f = float(fs)
                            it.modal = modal = modal.with_(feed=f)
                            yield FeedRate(new_span(sid, m.start(7) - 1, m.end(7)), frame, f * k_pt, False)
                        if motion == "rapid":
                            yield new_rapid(new_span(sid, pos, end), frame, p, new, modal.path)
                        elif arc:
                            ci = x0 = p[0]
                            cj = y0 = p[1]
                            if is_ is not None:
                                ci = x0 + float(is_) * (k_pt if "." in is_ else k_int)
                            if js is not None:
                                cj = y0 + float(js) * (k_pt if "." in js else k_int)
                            yield Arc(new_span(sid, pos, end), frame, p, new, (ci, cj, p[2], p[3], p[4], p[5]),
                                      -1 if motion == "arc_cw" else 1, Plane.XY, modal.feed * k_pt,  # type: ignore[operator]
                                      modal.path)
                        else:
                            yield new_linear(new_span(sid, pos, end), frame, p, new, modal.feed * k_pt,  # type: ignore[operator]
                                             modal.path)
                        it.pos = new
                        pos = end + 1
                        continue
        if end > pos:
            for block in parser.blocks_of_line(src, pos, end, line_no):
                yield from it.execute(block)
        pos = end + 1
