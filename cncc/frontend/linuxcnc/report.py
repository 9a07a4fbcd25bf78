"""What LinuxCNC's interpreter reports around a block that the shared interpreter does not.

The shared :class:`~cncc.frontend.interp.Interpreter` emits a mode change only when
the mode changes.  LinuxCNC's interpreter calls the canonical functions for every
such code it reads, and adds calls of its own.  :func:`after_block` edits the IR of
one executed block (``out[at:]``) so that the canon trace reads as ``rs274 -g``'s:

- ``COMMENT("interpreter: ...")`` lines (the dialect's ``[canon.comments]``, recorded as
  ``InterpreterReport(key)`` and written by the canon backend only): feed
  mode, cutter compensation, G80, G98/G99 every time; distance modes on a change;
  a work-system code that does not change the system;
- ``SELECT_PLANE``/``USE_LENGTH_UNITS`` for G17-G19/G20-G21 even when unchanged;
- G93/G94/G95 every time, G94/G95 also setting the feed rate to 0 (F must follow);
- ``SET_XY_ROTATION`` after a work-system change;
- canned cycles: ``CANON_EXACT_PATH`` for the cycle and the path mode restored after
  it; a start below R first rises to R, which becomes the cycle's initial level;
- M2/M30: the resets (G54, XY plane, units-per-minute feed 0, spindle stop, coolant
  off) before ``PROGRAM_END``, as ordinary commands (a translation writes those that change
  the target's state before its M02: what the controller does at M2 anyway).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, cast

from cncc import diagnostics as dg
from cncc.frontend.linuxcnc import comp_rules
from cncc.frontend.linuxcnc.placement import Placement
from cncc.frontend.linuxcnc.rotation import reexpress, rotate_frames, rotation_in_use
from cncc.frontend.syntax import Word
from cncc.ir import (
    MODE_TYPES,
    Command,
    Comment,
    CompSide,
    Coolant,
    CoolantState,
    Cycle,
    Dwell,
    FeedMode,
    FeedRate,
    Frame,
    InterpreterReport,
    Origin,
    OriginKind,
    PathMode,
    Plane,
    Rapid,
    SelectTool,
    SetCutterComp,
    SetFeedMode,
    SetG92Offset,
    SetLocalOffset,
    SetPathMode,
    SetPlane,
    SetSpindleMode,
    SetToolLength,
    SetUnits,
    SetWorkSystem,
    SetXyRotation,
    Spindle,
    SpindleSpeed,
    SpindleState,
    Stop,
    StopKind,
    ToolChange,
    Vec6,
    WriteToolTable,
)
from cncc.source import Span

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter

# The trace-only IR records (written by the canon backend, ignored by the others).

# op -> [canon.comments] key, reported every time the code is read
_ALWAYS = {"comp_off": "comp_off", "comp_left": "comp_left", "comp_right": "comp_right",
           "comp_left_dynamic": "comp_left", "comp_right_dynamic": "comp_right",
           "inverse_time": "inverse_time", "feed_per_min_rs274": "per_min", "feed_per_rev_rs274": "per_rev",
           "motion_off": "motion_none", "return_initial": "retract_old_z", "return_r": "retract_r_plane"}
_FEED_MODES = {"inverse_time": FeedMode.INVERSE_TIME, "feed_per_min_rs274": FeedMode.PER_MIN,
               "feed_per_rev_rs274": FeedMode.PER_REV}


# The codes that read a P word in LinuxCNC 2.9 (x10: G5.2 is 52) and rs274's message otherwise.
_P_MOTIONS = frozenset({20, 30, 50, 52, 740, 760, 820, 840, 860, 880, 890})  # G74/G84 read P too (dwell)
_P_G_CODES = _P_MOTIONS | {40, 100, 640}
_P_NEEDED = frozenset({820, 860, 880, 890})  # cycles whose block must have its dwell P
_P_M_CODES = frozenset({500, 510, 520, 530, 620, 630, 640, 650, 660, 980})
_P_CYCLES = frozenset({"drill_dwell", "tap_rs274", "tap_left_rs274", "bore_dwell_stop_rs274", "bore_manual_rs274",
                       "bore_dwell_feed_out_rs274"})
_P_MODAL_OPS = frozenset({"arc_cw", "arc_ccw", "cubic_spline", "nurbs_begin"})
_Q_G_CODES = frozenset({50, 100, 640, 730, 760, 830})
_Q_M_CODES = frozenset({190, 610, 660, 670, 680})  # M61 Q: the tool number
_Q_CYCLES = frozenset({"peck", "peck_high_speed"})
_Q_WITHOUT_USER = "Q word with no G5, G10, G64, G73, G76, G83, M19, M66, M67, M68 or user M code that uses it"
_P_WITHOUT_USER = ("P word with no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 or M50 M51 M52 M53 M62 M63 M64 M65 "
                   "M66 M98 or user M code to use it")


@dataclass(frozen=True, slots=True)
class Before:
    """The interpreter's modes before a block."""

    incremental: bool
    arc_absolute: bool
    work_index: int
    tool_length_mm: float
    frame: Frame
    theta_deg: float  # the XY rotation of the active work system
    pos: Vec6

    @staticmethod
    def of(it: Interpreter) -> Before:
        from cncc.frontend.rs274 import state

        st = state(it)
        theta = st.rotation_deg.get(it.frame.work_index, 0.0) if st.rotation_deg else 0.0
        return Before(it.modal.incremental, st.arc_absolute, it.frame.work_index, it.frame.tool_length_mm,
                      it.frame, theta, it.pos)


@dataclass(slots=True)
class Reporter:
    """Per-program state of the reports (coolant in force) and the block editor."""

    it: Interpreter
    comments: dict[str, str]
    flood: bool = False
    mist: bool = False
    raised_cycle: str = ""  # the cycle code whose initial level was below R (each block rises to R again)

    def allowed(self, span: Span, words: tuple[Word, ...]) -> bool:
        """LinuxCNC's checks of a block against the state before it (an error: not run)."""
        it = self.it
        planes = {"plane_xy": Plane.XY, "plane_zx": Plane.ZX, "plane_yz": Plane.YZ}
        for w in words:
            c = it.dialect.code("G", round(w.value * 10)) if w.letter == "G" else None
            if c is not None and c.op in planes and it.frame.comp_side is not CompSide.OFF \
                    and planes[c.op] is not it.frame.plane:
                it.emit_error(dg.COMP_PLANE_CHANGE, span, f"{c.name}: the plane cannot change while cutter "
                                                          "compensation is on")
                return False
        moves = any(w.letter in "XYZABCUVW" for w in words)
        refused = comp_rules.refused(it, words, self._in_cycle(words) and (moves or self._cycle_code(words)))
        if refused is not None:
            it.emit_error(dg.COMP_REFUSES, span, refused)
            return False
        rotary = next((w.letter for w in words if w.letter in "ABC"), None)
        if rotary is not None and self._in_cycle(words):
            it.emit_error(dg.CONTROLLER_REJECTS, span, f"Cannot put a{'n' if rotary == 'A' else ''} "
                                                       f"{rotary.lower()} in canned cycle")
            return False
        needs_p = next((round(w.value) for w in words if w.letter == "G" and round(w.value * 10) in _P_NEEDED), None)
        if needs_p is not None and not any(w.letter == "P" for w in words) and it.dialect.option("p_word_check", False):
            it.emit_error(dg.CONTROLLER_REJECTS, span, f"Dwell time p word missing with g{needs_p}")
            return False
        if any(w.letter == "P" for w in words) and it.dialect.option("p_word_check", False) and \
                not self._uses_p(words):
            it.emit_error(dg.CONTROLLER_REJECTS, span, _P_WITHOUT_USER)
            return False
        if any(w.letter == "Q" for w in words) and it.dialect.option("p_word_check", False) and \
                not self._uses_q(words):
            it.emit_error(dg.CONTROLLER_REJECTS, span, _Q_WITHOUT_USER)
            return False
        missing = self._absolute_centre_missing(words)
        if missing:
            it.emit_error(dg.CONTROLLER_REJECTS, span, f"{missing} word missing in absolute center arc")
            return False
        if self._feeds_per_rev_without_speed(words):
            it.emit_error(dg.ZERO_FEED, span, "Cannot feed with zero spindle speed in feed per rev mode")
            return False
        return True

    def _absolute_centre_missing(self, words: tuple[Word, ...]) -> str:
        """G90.1: a centre-format arc needs both centre words of its plane (rs274: "J word missing in
        absolute center arc"; in G91.1 a missing one is 0).  The missing letter, or ""."""
        from cncc.frontend.rs274 import state

        it = self.it
        arc_absolute, plane, motion = state(it).arc_absolute, it.frame.plane, it.modal.motion
        for w in words:
            c = it.dialect.code("G", round(w.value * 10)) if w.letter == "G" else None
            if c is None:
                continue
            if c.op in ("arc_absolute", "arc_incremental"):
                arc_absolute = c.op == "arc_absolute"
            elif c.op in ("plane_xy", "plane_zx", "plane_yz"):
                plane = {"plane_xy": Plane.XY, "plane_zx": Plane.ZX, "plane_yz": Plane.YZ}[c.op]
            elif c.group == "motion":
                motion = c.op
        letters = {w.letter for w in words}
        if not arc_absolute or motion not in ("arc_cw", "arc_ccw") or "R" in letters:
            return ""
        pair = {Plane.XY: "IJ", Plane.ZX: "IK", Plane.YZ: "JK"}[plane]
        given = [ch for ch in pair if ch in letters]
        return next(ch for ch in pair if ch not in letters) if len(given) == 1 else ""

    def _feeds_per_rev_without_speed(self, words: tuple[Word, ...]) -> bool:
        """A feed move in G95 (the block's or the mode in force) with a feed rate but no spindle speed (S0 or
        never set); without a feed rate rs274 reports that first."""
        it = self.it
        tenths = {round(w.value * 10) for w in words if w.letter == "G"}
        per_rev = 950 in tenths or (it.modal.per_rev and not tenths & {930, 940})
        rpm = next((w.value for w in words if w.letter == "S"), it.modal.spindle_rpm)
        feed = next((w.value for w in words if w.letter == "F"), None if tenths & {940, 950} else it.modal.feed)
        if not per_rev or rpm != 0 or not feed or not any(w.letter in "XYZABC" for w in words):
            return False
        motions = [t for t in tenths if t in (0, 10, 20, 30)]
        return (motions[0] != 0) if motions else (it.modal.motion in ("linear", "arc_cw", "arc_ccw")
                                                   and not it.modal.cycle and not tenths & {800})

    def _uses_q(self, words: tuple[Word, ...]) -> bool:
        """rs274's check_other_codes for Q: a code that reads it in the block, or G73/G83 in force."""
        for w in words:
            v = round(w.value * 10)
            if (w.letter == "G" and v in _Q_G_CODES) or (w.letter == "M" and (v in _Q_M_CODES or 1000 <= v < 2000)):
                return True
        motion = any(w.letter == "G" and (c := self.it.dialect.code("G", round(w.value * 10))) is not None
                     and c.group in ("motion", "cycle") for w in words)
        return not motion and self.it.modal.cycle in _Q_CYCLES

    def _cycle_code(self, words: tuple[Word, ...]) -> bool:
        return any(w.letter == "G" and (c := self.it.dialect.code("G", round(w.value * 10))) is not None
                   and c.group == "cycle" for w in words)

    def _in_cycle(self, words: tuple[Word, ...]) -> bool:
        """The block runs a canned cycle: a cycle code in it, or the cycle in force and no other motion code."""
        it = self.it
        for w in words:
            c = it.dialect.code("G", round(w.value * 10)) if w.letter == "G" else None
            if c is not None and c.group in ("cycle", "motion"):
                return c.group == "cycle" or c.op == "cycle"
        return bool(it.modal.cycle)

    def _uses_p(self, words: tuple[Word, ...]) -> bool:
        """rs274's check_other_codes: a P word needs one of the codes that read it (the motion in force
        counts for G2/G3/G5/G82/G86/G88/G89)."""
        it = self.it
        motion = None
        for w in words:
            v = round(w.value * 10)
            if w.letter == "G":
                if v in _P_G_CODES:
                    return True
                c = it.dialect.code("G", v)
                if c is not None and c.group == "motion":
                    motion = v
            elif w.letter == "M" and (v in _P_M_CODES or 1000 <= v < 2000):
                return True
        if motion is None:
            return it.modal.cycle in _P_CYCLES or it.modal.motion in _P_MODAL_OPS
        return motion in _P_MOTIONS

    def after_block(self, span: Span, words: tuple[Word, ...], out: list[Command], at: int, before: Before) -> None:
        it = self.it
        ops = [c.op for c in (it.dialect.code("G", round(w.value * 10)) for w in words if w.letter == "G") if c]
        added: list[tuple[int, Command]] = [(_COMMENT_STAGE[k], InterpreterReport(span, it.frame, k))
                                            for k in self._comment_keys(ops, before) if k in self.comments]
        added += self._repeated_modes(span, ops, out[at:])
        stages = {id(cmd): stage for stage, cmd in added}
        end = next((i for i in range(at, len(out)) if _stage(out[i]) >= 20), len(out))
        block = sorted(out[at:end], key=lambda c: _stage(c, stages))  # stable: LinuxCNC's order of execution
        for stage, cmd in sorted(added, key=lambda sc: sc[0]):
            _place(block, 0, stage, cmd, stages)
        out[at:end] = _comments_in_place(block, before.frame)
        self._feed_modes(span, ops, out, at, words)
        self._tool_length(span, ops, out, at, words, before)
        self._retain_g43(span, out, at)
        if "work" in ops:
            self._after_work_select(out, at)
        self._cycles(out, at)
        if before.theta_deg or rotation_in_use(it):
            reexpress(it, Placement.of_frame(before.frame, before.theta_deg), before.pos, words, out, at,
                      select="work" in ops)
            rotate_frames(it, out, at)
        self._program_end(out, at)
        self._track_coolant(out[at:])

    def _comment_keys(self, ops: list[str], before: Before) -> list[str]:
        from cncc.frontend.rs274 import state

        it = self.it
        keys = [_ALWAYS[op] for op in ops if op in _ALWAYS]
        if it.modal.incremental != before.incremental:
            keys.append("distance_incremental" if it.modal.incremental else "distance_absolute")
        if state(it).arc_absolute != before.arc_absolute:
            keys.append("ijk_absolute" if state(it).arc_absolute else "ijk_incremental")
        if "work" in ops and it.frame.work_index == before.work_index:
            keys.append("same_system")
        return keys

    def _repeated_modes(self, span: Span, ops: list[str], out: list[Command]) -> list[tuple[int, Command]]:
        """SELECT_PLANE / USE_LENGTH_UNITS for a plane or units code that changed nothing."""
        it = self.it
        kinds = {type(c) for c in out}
        extra: list[tuple[int, Command]] = []
        if any(op in ("plane_xy", "plane_zx", "plane_yz") for op in ops) and SetPlane not in kinds:
            extra.append((11, SetPlane(span, it.frame, it.frame.plane)))
        if any(op in ("inch", "metric") for op in ops) and SetUnits not in kinds:
            extra.append((12, SetUnits(span, it.frame, it.frame.units)))
        return extra

    def _feed_modes(self, span: Span, ops: list[str], out: list[Command], at: int, words: tuple[Word, ...]) -> None:
        """G93/G94/G95: SET_FEED_MODE every time; G94/G95 reset the feed rate to 0 (F follows)."""
        op = next((o for o in ops if o in _FEED_MODES), None)
        if op is None:
            return
        it = self.it
        i = next((k for k in range(at, len(out)) if isinstance(out[k], SetFeedMode)), None)
        if i is None:
            i = _place(out, at, 2, SetFeedMode(span, it.frame, _FEED_MODES[op]), {})
        if op != "inverse_time":
            out.insert(i + 1, FeedRate(span, it.frame, 0.0, op == "feed_per_rev_rs274"))
            if not any(w.letter == "F" for w in words):
                it.modal = it.modal.with_(feed=None)

    def _tool_length(self, span: Span, ops: list[str], out: list[Command], at: int, words: tuple[Word, ...],
                     before: Before) -> None:
        """G43/G49 report the offset every time; without a Z word the program Z follows the offset
        (LinuxCNC does not move the tool).  A move in the same block is made before that shift."""
        from cncc.frontend.rs274 import shift_z

        if not any(op in ("length_plus", "length_off") for op in ops):
            return
        if not any(isinstance(c, SetToolLength) for c in out[at:]):
            _place(out, at, 14, SetToolLength(span, self.it.frame, self.it.frame.tool_length_mm), {})
        if not any(w.letter == "Z" for w in words):
            shift_z(self.it, before.tool_length_mm)

    def _retain_g43(self, span: Span, out: list[Command], at: int) -> None:
        """INI RETAIN_G43: an M6 while G43 is in force applies the new tool's length (LinuxCNC's doc: "turn on
        G43 after loading the first tool, and then not worry about it"); unloading (T0 M6) ends G43.  The program
        Z stays (rs274 2.9: the tool change is a move of its own)."""
        it = self.it
        if not it.dialect.option("retain_g43", False) or it.group_codes.get("length_comp", "G49") == "G49":
            return
        k = next((i for i in range(len(out) - 1, at - 1, -1) if isinstance(out[i], ToolChange)), None)
        if k is None:
            return
        tool = cast(ToolChange, out[k]).tool
        value = it.options.tool_lengths_mm.get(tool, 0.0) if tool else 0.0
        it.set_frame(replace(it.frame, tool_length_mm=value, tool_length_index=tool))
        out.insert(k + 1, SetToolLength(span, it.frame, value))
        if not tool:
            it.group_codes["length_comp"] = "G49"

    def _after_work_select(self, out: list[Command], at: int) -> None:
        """A work-system change reports the G92 offset and the XY rotation after the G5x offset."""
        from cncc.frontend.rs274_g10 import rotation_deg

        for k in range(len(out) - 1, at - 1, -1):
            c = out[k]
            nxt = out[k + 1] if k + 1 < len(out) else None
            if isinstance(c, SetWorkSystem) and not isinstance(nxt, SetXyRotation):
                out[k + 1:k + 1] = [SetG92Offset(c.span, c.frame, c.frame.g92_offset_mm),
                                    SetXyRotation(c.span, c.frame, rotation_deg(self.it, c.frame.work_index))]

    # ---- canned cycles
    def _cycles(self, out: list[Command], at: int) -> None:
        from cncc.frontend.rs274 import state

        if not self.it.modal.cycle:
            self.raised_cycle = ""

        k = at
        while k < len(out):
            c = out[k]
            if not isinstance(c, Cycle):
                k += 1
                continue
            pre: list[Command] = []
            c, rise = self._rise_to_r(replace(c, zero_moves=True))
            if rise is not None:
                pre.append(rise)
            path = self.it.modal.path
            post: list[Command] = []
            if path.mode is not PathMode.EXACT_PATH:
                pre.append(SetPathMode(c.span, c.frame, PathMode.EXACT_PATH, for_cycle=True))
                naive_mm = state(self.it).naive_mm if path.mode is PathMode.CONTINUOUS else None
                post.append(SetPathMode(c.span, c.frame, path.mode, path.blend_tolerance_mm or 0.0, naive_mm,
                                        for_cycle=True))
            out[k:k + 1] = [*pre, c, *post]
            k += len(pre) + 1 + len(post)

    def _rise_to_r(self, c: Cycle) -> tuple[Cycle, Rapid | None]:
        """A cycle started below R rises to R first; R is then its initial (G98) level."""
        from cncc.frontend import cycles

        n = c.axis
        if self.raised_cycle and self.raised_cycle != c.code:
            self.raised_cycle = ""
        if c.kind.value == "back_bore" or c.start[n] > c.r_mm or (c.start[n] == c.r_mm and not self.raised_cycle):
            return c, None
        self.raised_cycle = c.code  # rs274 compares its remembered initial level with R in every block
        up = _with(c.start, n, c.r_mm)
        data = cycles.cycle_data(self.it)
        if data is not None:  # later blocks of this cycle keep R as their initial level
            self.it.cycle = replace(self.it.cycle, data=replace(data, initial_mm=c.r_mm))
        rise = Rapid(c.span, c.frame, c.start, up, c.motion, Origin(OriginKind.CYCLE, c.code))
        return replace(c, start=up, initial_mm=c.r_mm), rise  # the holes end at R (G99) or max(start, R) = R

    # ---- M2 / M30
    def _program_end(self, out: list[Command], at: int) -> None:
        k = next((i for i in range(at, len(out)) if _is_end(out[i])), None)
        if k is None:
            return
        it, span = self.it, out[k].span
        resets: list[Command] = []
        g54 = it.options.work_offsets_mm.get(1, (0.0,) * 6)
        it.set_frame(replace(it.frame, work_index=1, work_offset_mm=g54))
        from cncc.frontend.rs274_g10 import rotation_deg

        resets += [SetWorkSystem(span, it.frame, 1),
                   SetXyRotation(span, it.frame, rotation_deg(it, 1))]
        if it.frame.plane is not Plane.XY:
            it.set_frame(replace(it.frame, plane=Plane.XY))
            resets.append(SetPlane(span, it.frame, Plane.XY))
        resets += [SetFeedMode(span, it.frame, FeedMode.PER_MIN), FeedRate(span, it.frame, 0.0),
                   Spindle(span, it.frame, SpindleState.OFF, 0.0), SetSpindleMode(span, it.frame, 0.0)]
        if self.flood or self.mist:
            resets.append(Coolant(span, it.frame, CoolantState.OFF))
        out[k:k + 1] = [*resets, replace(out[k], frame=it.frame)]

    def _track_coolant(self, out: list[Command]) -> None:
        from cncc.frontend.linuxcnc.params import coolant_after

        for c in out:
            if isinstance(c, Coolant):
                self.flood, self.mist = coolant_after(c.state, self.flood, self.mist)


# The stage of LinuxCNC's order of execution at which each report is made.
_COMMENT_STAGE = {"inverse_time": 2, "per_min": 2, "per_rev": 2, "comp_off": 13, "comp_left": 13, "comp_right": 13,
                  "same_system": 15, "distance_absolute": 17, "distance_incremental": 17, "ijk_absolute": 17,
                  "ijk_incremental": 17, "retract_old_z": 18, "retract_r_plane": 18, "motion_none": 20}
_MODE_STAGE: dict[type[Command], int] = {
    SetFeedMode: 2, SetPlane: 11, SetUnits: 12, SetCutterComp: 13, SetToolLength: 14, SetWorkSystem: 15,
    SetXyRotation: 15, SetG92Offset: 19, SetLocalOffset: 19, WriteToolTable: 19}


def _stage(c: Command, known: dict[int, int] | None = None) -> int:
    """Where ``c`` falls in LinuxCNC's order of execution (1 messages ... 21 stops)."""
    if known and id(c) in known:
        return known[id(c)]
    match c:
        case Comment():
            return 1
        case InterpreterReport():
            return 1
        case FeedRate():
            return 3
        case SpindleSpeed():
            return 4
        case SelectTool():
            return 5
        case ToolChange():
            return 6
        case Spindle():
            return 7
        case Coolant():
            return 8
        case Dwell():
            return 10
        case SetPathMode():
            return 20 if c.for_cycle else 16
        case _ if isinstance(c, MODE_TYPES):
            return _MODE_STAGE.get(type(c), 20)
        case Stop():
            return 21
    return 20


def _place(out: list[Command], at: int, stage: int, cmd: Command, known: dict[int, int]) -> int:
    """Insert ``cmd`` (of ``stage``) into ``out[at:]``, which is sorted by stage: a comment before
    the calls of its stage, anything else after them; its index.  ``cmd`` takes the frame of
    the command before it, so that the canon trace reports no offset change early."""
    comment = isinstance(cmd, Comment | InterpreterReport)
    k = next((i for i in range(at, len(out)) if _stage(out[i], known) > stage
              or (comment and _stage(out[i], known) == stage)), len(out))
    neighbour = out[k - 1] if k > at else (out[k] if k < len(out) else None)
    if neighbour is not None and neighbour.frame is not cmd.frame:
        cmd = replace(cmd, frame=neighbour.frame)
        known[id(cmd)] = stage
    out.insert(k, cmd)
    return k


def _comments_in_place(block: list[Command], frame: Frame) -> list[Command]:
    """A comment takes the frame in force where LinuxCNC makes it (the command before it; ``frame`` before
    the block): a code run before it in cncc (a work system) does not move its offsets ahead of it."""
    out: list[Command] = []
    for c in block:
        if isinstance(c, Comment | InterpreterReport) and c.frame is not frame:
            c = replace(c, frame=frame)
        out.append(c)
        frame = c.frame
    return out


def _is_end(c: Command) -> bool:
    return isinstance(c, Stop) and c.kind in (StopKind.PROGRAM_END, StopKind.END_REWIND)


def _with(p: Vec6, i: int, v: float) -> Vec6:
    q = list(p)
    q[i] = v
    return (q[0], q[1], q[2], q[3], q[4], q[5])
