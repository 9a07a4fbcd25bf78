"""Normalised G-code from IR commands.

One word order (G codes, axes, arc centre, F), explicit modes, coordinates always
with a decimal point (so the least-input-unit rule never changes their meaning),
absolute distances, and the target's comment syntax.  The output re-parses to the
same IR motion (``tests/backends/test_gcode_roundtrip.py``).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass

from cncc.dialects import Dialect
from cncc.ir import (
    Arc,
    Command,
    Comment,
    Coolant,
    CoolantState,
    Dwell,
    FeedRate,
    Frame,
    Linear,
    Message,
    PathMode,
    Plane,
    Rapid,
    SelectTool,
    SetMode,
    Spindle,
    SpindleSpeed,
    SpindleState,
    Stop,
    StopKind,
    ToolChange,
    Units,
    Vec6,
)

AXES = "XYZABC"


@dataclass(frozen=True, slots=True)
class EmitOptions:
    decimals_mm: int = 3
    decimals_inch: int = 4
    line_numbers: bool = False
    line_step: int = 10


class _Codes:
    """Reverse lookup: op -> code name in the target dialect."""

    def __init__(self, dialect: Dialect) -> None:
        self.by_op: dict[str, str] = {}
        self.work: dict[int, str] = {}
        for cdef in sorted(dialect.codes.values(), key=lambda c: (c.letter, c.tenths)):
            if cdef.op == "work":
                self.work.setdefault(cdef.index, cdef.name)
            self.by_op.setdefault(cdef.op, cdef.name)

    def __call__(self, op: str) -> str:
        return self.by_op.get(op, "")


class GcodeEmitter:
    def __init__(self, dialect: Dialect, options: EmitOptions | None = None) -> None:
        self.dialect = dialect
        self.opt = options or EmitOptions()
        self.codes = _Codes(dialect)
        self.n = 0
        self.units = Units.INCH if dialect.default_units == "inch" else Units.MM
        self.plane = Plane.XY
        self.motion = ""
        self.feed: float | None = None
        self.frame: Frame | None = None

    # -- formatting
    def num(self, v_mm: float, axis: int = 0) -> str:
        if axis >= 3:
            return _trim(f"{v_mm:.4f}")
        v = v_mm / self.units.mm_per_unit
        d = self.opt.decimals_inch if self.units is Units.INCH else self.opt.decimals_mm
        return _trim(f"{v:.{d}f}")

    def block(self, words: list[str], comment: str = "") -> str:
        text = " ".join(w for w in words if w)
        if comment:
            text = (text + " " if text else "") + self.comment(comment)
        if self.opt.line_numbers and words:
            self.n += self.opt.line_step
            text = f"N{self.n} " + text
        end = ";" if self.dialect.block_end == ";" and words else ""
        return text + end + "\n"

    def comment(self, text: str) -> str:
        if "paren" in self.dialect.comments:
            return "(" + text.replace("(", "[").replace(")", "]") + ")"
        if "semi" in self.dialect.comments:
            return "; " + text
        return "// " + text

    # -- program
    def preamble(self) -> Iterator[str]:
        c = self.codes
        yield self.block([c("plane_xy"), c("metric" if self.units is Units.MM else "inch"), c("absolute"),
                          c("feed_per_min")])

    def emit(self, cmds: Iterable[Command]) -> Iterator[str]:
        yield from self.preamble()
        for cmd in cmds:
            yield from self._frame_changes(cmd.frame)
            yield from self._command(cmd)

    def _frame_changes(self, frame: Frame) -> Iterator[str]:
        c = self.codes
        if frame.units is not self.units:
            self.units = frame.units
            yield self.block([c("inch" if frame.units is Units.INCH else "metric")])
        if frame.plane is not self.plane:
            self.plane = frame.plane
            yield self.block([c({Plane.XY: "plane_xy", Plane.ZX: "plane_zx", Plane.YZ: "plane_yz"}[frame.plane])])
        prev = self.frame
        self.frame = frame
        if prev is None or prev.work_index != frame.work_index:
            code = c.work.get(frame.work_index, "")
            if code and (prev is not None or frame.work_index != 1):
                yield self.block([code])
        if prev is not None and prev.local_offset_mm != frame.local_offset_mm and c("local_offset"):
            yield self.block([c("local_offset")] + [f"{a}{self.num(v, i)}" for i, (a, v)
                                                     in enumerate(zip(AXES, frame.local_offset_mm, strict=True))
                                                     if i < 3])
        if prev is not None and prev.tool_length_mm != frame.tool_length_mm:
            if frame.tool_length_mm == 0.0:
                yield self.block([c("length_off")])
            else:
                yield self.block([c("length_plus"), f"H{frame.tool_length_index}"])

    def _axes(self, start: Vec6, end: Vec6) -> list[str]:
        """The axes that move (X alone for a move of zero length)."""
        out = [f"{a}{self.num(end[i], i)}" for i, a in enumerate(AXES) if end[i] != start[i]]
        return out or [f"X{self.num(end[0], 0)}"]

    def _command(self, cmd: Command) -> Iterator[str]:
        c = self.codes
        match cmd:
            case Rapid():
                yield self.block([c("rapid"), *self._axes(cmd.start, cmd.end)])
            case Linear():
                yield self.block([c("linear"), *self._axes(cmd.start, cmd.end), self._feed(cmd.feed_mm_min)])
            case Arc():
                yield self.block(self._arc(cmd))
            case Dwell():
                yield self.block([c("dwell"), f"P{round(cmd.seconds * 1000)}" if self._p_ms() else
                                  f"P{_trim(f'{cmd.seconds:.3f}')}"])
            case FeedRate() | SpindleSpeed() | SelectTool():
                if isinstance(cmd, SpindleSpeed):
                    yield self.block([f"S{_trim(f'{cmd.rpm:.3f}')}"])
                elif isinstance(cmd, SelectTool):
                    yield self.block([f"T{cmd.tool}"])
            case Spindle():
                op = {SpindleState.CW: "spindle_cw", SpindleState.CCW: "spindle_ccw", SpindleState.OFF: "spindle_off",
                      SpindleState.ORIENT: "spindle_orient"}[cmd.state]
                yield self.block([c(op)])
            case Coolant():
                op = {CoolantState.FLOOD: "coolant_flood", CoolantState.MIST: "coolant_mist",
                      CoolantState.OFF: "coolant_off"}[cmd.state]
                yield self.block([c(op)])
            case ToolChange():
                yield self.block([c("tool_change")])
            case Stop():
                op = {StopKind.PROGRAM_STOP: "program_stop", StopKind.OPTIONAL_STOP: "optional_stop",
                      StopKind.PROGRAM_END: "program_end", StopKind.END_REWIND: "program_end_rewind"}[cmd.kind]
                yield self.block([c(op)])
            case Comment() | Message():
                yield self.block([], cmd.text)
            case SetMode():
                if cmd.name == "path_mode":
                    yield self.block([c("exact_stop_mode" if cmd.value is PathMode.EXACT_STOP else "continuous_mode")])
                elif cmd.name == "feed_mode":
                    yield self.block([c("feed_per_rev" if cmd.value == "per_rev" else "feed_per_min")])
                    self.feed = None
            case _:
                pass

    def _p_ms(self) -> bool:
        return self.dialect.decimal_rule == "liu"

    def _feed(self, feed_mm_min: float) -> str:
        if self.feed is not None and abs(self.feed - feed_mm_min) < 1e-9:
            return ""
        self.feed = feed_mm_min
        return "F" + _trim(f"{feed_mm_min / self.units.mm_per_unit:.4f}")

    def _arc(self, a: Arc) -> list[str]:
        c = self.codes
        p = a.plane
        letters = {Plane.XY: ("I", "J"), Plane.ZX: ("K", "I"), Plane.YZ: ("J", "K")}[p]
        words = [c("arc_ccw" if a.turns > 0 else "arc_cw")]
        full = a.start == a.end
        words += self._axes(a.start, a.end) if not full else []
        words.append(f"{letters[0]}{self.num(a.center[p.first] - a.start[p.first])}")
        words.append(f"{letters[1]}{self.num(a.center[p.second] - a.start[p.second])}")
        if abs(a.turns) > 1:
            words.append(f"L{abs(a.turns)}")
        words.append(self._feed(a.feed_mm_min))
        return words


def _trim(s: str) -> str:
    if "." in s:
        s = s.rstrip("0")
    if s in ("-0.", "-0"):
        s = "0."
    return s if "." in s else s + "."


def emit_gcode(cmds: Iterable[Command], dialect: Dialect, options: EmitOptions | None = None) -> Iterator[str]:
    """Yield program lines (with newlines) for ``cmds`` in ``dialect``."""
    return GcodeEmitter(dialect, options).emit(cmds)
