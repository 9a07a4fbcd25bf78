"""The commands that are not moves: modes, tool and spindle codes, stops, M codes and probing.

:class:`ModeWriter` writes the mode commands a translation acts on (call boundaries, G92 presets, G10
work tables, G61/G64, M61), tool selection and change, stops, auxiliary M codes, dwells, and the
moves after a G38.x probe marker (the target's probe code, or refused with E0883; the stand-alone
interpreter's back-off is not written).
"""

from __future__ import annotations

from collections.abc import Iterator

from cncc import diagnostics as dg
from cncc.backends.gcode.frame_sync import FrameSync
from cncc.backends.gcode.numbers import fixed
from cncc.ir import (
    Aux,
    CallBoundary,
    Linear,
    ModeCommand,
    OriginKind,
    PathMode,
    PresetG92,
    Probe,
    SelectTool,
    SetPathMode,
    SetToolNumber,
    Stop,
    StopKind,
    ToolChange,
    WriteWorkTable,
)

_STOP_OPS = {StopKind.PROGRAM_STOP: "program_stop", StopKind.OPTIONAL_STOP: "optional_stop",
             StopKind.PROGRAM_END: "program_end", StopKind.END_REWIND: "program_end_rewind"}


class ModeWriter(FrameSync):
    """Mode, tool, spindle, stop, M-code and probe commands."""

    def _mode(self, cmd: ModeCommand) -> Iterator[str]:
        """The mode commands a translation acts on: call boundaries, G92 presets, G10 work offsets, G61/G64."""
        match cmd:
            case Probe():
                self.probe = (self.t.code(cmd.op), cmd.folded)
            case SetToolNumber():  # M61 Q
                yield self.op_block("set_tool_number", "setting the tool number without a change", [f"Q{cmd.tool}"])
            case CallBoundary() if self.opt.keep_subprograms:
                self.spindle_stopped = False  # a kept body's blocks may not depend on where it is called
                from cncc.backends.gcode.subprograms import call_marker

                yield call_marker(self, cmd)
            case PresetG92():
                self.g92_force |= set(cmd.axes)
            case WriteWorkTable():
                yield from self._work_table(cmd.index, cmd.old_mm, cmd.new_mm)
            case SetPathMode() if not cmd.for_cycle:
                op = "exact_stop_mode" if cmd.mode is PathMode.EXACT_STOP else "continuous_mode"
                if self.t.has(op):
                    yield self.block([self.t.code(op)])

    def _select_tool(self, cmd: SelectTool) -> str:
        limit = self.t.word_max.get("T")
        if limit is not None and cmd.tool > limit:
            self.warn(dg.XL_WORD_RANGE, f"T{cmd.tool}: {self.t.name} takes tool numbers up to {limit:g}")
        return self.block([f"T{cmd.tool}"])

    def _stop(self, cmd: Stop) -> Iterator[str]:
        if self.cycle_initial is not None and cmd.kind in (StopKind.PROGRAM_END, StopKind.END_REWIND):
            yield self.block([self.t.code("cycle_off")])
            self.cycle_initial = None
        yield self.op_block(_STOP_OPS[cmd.kind], cmd.kind.name.lower().replace("_", " "))

    def _tool_change(self, cmd: ToolChange) -> Iterator[str]:
        code = self.t.code("tool_change")
        if code:
            yield self.block([code])
            return
        self.warn(dg.XL_NO_CODE, f"{self.t.name} has no tool change; a program stop asks the operator")
        yield self.block([self.t.code("program_stop")], f"change to tool T{cmd.tool}")

    def _aux(self, cmd: Aux) -> Iterator[str]:
        whole, frac = divmod(cmd.code, 10)
        name = f"M{whole:02d}" + (f".{frac}" if frac else "")
        if self.opt.same_dialect:
            yield self.block([name, *(f"{k}{v:g}" for k, v in cmd.args)])
        else:
            self.warn(dg.XL_NO_CODE, f"{name} has no known meaning to carry over to {self.t.name}")
            yield self.block([], f"{name} not translated")

    def _probe_move(self, cmd: Linear) -> Iterator[str]:
        """The moves after a probe marker: the probe move in the target's probe code (or refused), then
        the stand-alone interpreter's back-off, which a machine does not make (the position is unknown)."""
        assert self.probe is not None
        self._note_frame(cmd)
        code, left = self.probe
        self.probe = (code, left - 1) if left > 1 else None
        if cmd.origin.kind is OriginKind.PROBE_BACKOFF:
            pass
        elif code:
            self._check_increment(cmd)
            yield from self._sync(cmd.frame, cmd.start, cancel_cycle=True)
            words = [code, *self._axes(cmd.start, cmd.end, self._released(cmd.frame)), self._feed_word(cmd.feed_mm_min)]
            yield from self._g91(words)
        else:
            self.warn(dg.XL_NO_PROBE, f"{self.t.name} has no probing: the {cmd.origin.code} probe move is not written",
                      once=False)
            yield self.block([], f"{cmd.origin.code} probe: no {self.t.name} code")
        if self.probe is None:  # where a probe stops is not known: the next move writes every axis
            self.unknown |= {0, 1, 2}
            self.qpos = None

    def _dwell_word(self, seconds: float) -> str:
        """The dwell word in the target: a word of kind ``time`` in seconds, else ``time_ms``."""
        cdef = self.t.by_op.get("dwell")
        kinds = cdef.words if cdef is not None else {}
        for letter in ("P", "X", "U"):
            if kinds.get(letter) == "time":
                return f"{letter}{fixed(seconds, 3)}"
        for letter, kind in kinds.items():
            if kind == "time_ms":
                return f"{letter}{round(seconds * 1000)}"
        return f"P{fixed(seconds, 3)}"
