"""``-fsyntax-only`` on a straight-line program: the fast path's checks as array operations.

``cncc -fsyntax-only big.nc`` must report what the whole front end and the path passes report,
nothing more or less.  On a straight-line program (:func:`cncc.frontend.fastpath.is_straight_line`)
the front end is :func:`cncc.frontend.fastpath.lower_straight`: a plain block
(``fastpath.CAM_LINE``) under plain modes is lowered without diagnostics, every other line
goes through the grammar and the interpreter.  :func:`lower_for_check` walks the same program,
and instead of a command per plain block it decides with numpy, for a whole run of plain lines
at once (:mod:`cncc.frontend.plainscan`), the fast path's conditions -- motion mode in force
(the last G0-G3), a feed programmed (the last F before, not F0), no I/J on G0/G1, I/J and no Z
on G2/G3 in the XY plane, no zero-radius arc -- and the end points the arcs need.  The first
line of a run that fails goes through the grammar and the interpreter with the modal state
written back, as the fast path does it, and the run goes on after it.

What it yields is a *sparse* command stream for the path passes, equivalent for them to the
front end's whole stream: frames that transform nothing, have no offset and no pending
transform cancel (:func:`_plain_frame`) make the frame passes relinking pass-throughs and leave
``arc-check`` as the only pass that looks at a move.  So of a run of plain moves it yields the
first and last moves, and every arc whose radii do not agree clearly within the arc check's
tolerances (:class:`ArcLimits`: a margin above the rounding of ``np.hypot``), each after a
stand-in move that ends where the move before it ended, so the passes see the same starts and
the real ``arc-check`` reports it.  Other arcs are checked here and dropped.  Everything that
is not plain -- a frame that transforms, offsets or holds axes, a machine mode the fast path
refuses -- is the real thing: general lines through the interpreter, and from the first
non-plain frame on the rest of the file through :func:`lower_straight` itself.

It is only for ``-fsyntax-only`` with the default passes (the driver decides,
``driver.fast_syntax_only``): the commands are incomplete by design.  A program that turns out
not to be straight-line raises :class:`NotStraight` before any line of that chunk ran; the
driver then forgets the diagnostics and runs the front end (``tests/frontend/test_syntax_fast.py``
holds both paths to identical diagnostics).
"""

from __future__ import annotations

import re
from collections.abc import Generator, Iterator
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend import plainscan as ps
from cncc.frontend.fastpath import CAM_LINES, Checkpoints, _write_back, is_straight_line, lower_straight
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.parser import MAX_LINE_CHARS, ParseOptions, Parser
from cncc.ir import PROGRAMMED, Arc, Command, FeedRate, Frame, Linear, Plane
from cncc.ir.fastnew import new_rapid, new_span
from cncc.ir.frame import ZERO6, CompSide, Vec6
from cncc.source import SourceFile

_MOTIONS = ("rapid", "linear", "arc_cw", "arc_ccw")
_CODE = {m: k for k, m in enumerate(_MOTIONS)}
_OTHER = 9  # a motion mode the fast path does not lower (a line without G under it is general)
_MIN_RUN = 4  # shorter runs between general lines: line by line through the grammar
_SLOW_SHARE = 64  # hand the rest to lower_straight once more than 1/64 of the lines went slow
CHUNK_BYTES = 1 << 20  # scanned at once (tests make it small to cross chunk boundaries often)


class NotStraight(Exception):
    """The program is not for this checker after all: it has macro syntax, calls or jumps (found
    before that chunk ran), or a line longer than a scan chunk (found before anything ran)."""


@dataclass(frozen=True, slots=True)
class ArcLimits:
    """The tolerances of the ``arc-check`` pass that runs after the front end (its options)."""

    abs_tol_mm: float
    rel_tol: float
    abs_tol_inch_mm: float = 0.0
    max_abs_factor: float = 0.0


def applies(dialect: Dialect) -> bool:
    """Whether the dialect runs straight-line programs on the fast path, with no code or keyword
    a plain block could spell (then a plain line never decides :func:`is_straight_line`)."""
    from cncc.frontend.macro.executor import EXEC_OPS
    from cncc.frontend.macro.remap import remaps_cycles
    from cncc.frontend.plugins import front_end

    if not front_end(dialect).fast_path or not dialect.raw.get("fast_path", True) or remaps_cycles(dialect):
        return False
    if any(not (len(kw) >= 2 and kw.isalpha()) for kw in dialect.lexicon.executor_marks):
        return False  # a plain line has no two letters in a row: only such marks are out of its reach
    for c in dialect.codes.values():
        if c.op in EXEC_OPS and (c.letter in "NXYZIJF" or (c.letter == "G" and c.tenths <= 30)):
            return False
    return True


def lower_for_check(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, opts: InterpOptions,
                    arcs: ArcLimits, walks: list[object] | None = None) -> Iterator[Command]:
    """The sparse command stream of ``src`` for the path passes of ``-fsyntax-only`` (module doc).
    The caller checked :func:`applies`; the tape end (``before_tape_end``) is the caller's too.
    ``walks`` receives the walk (its ``vectorised`` and ``slow`` line counts, for tests)."""
    walk = _Walk(src, dialect, sink, opts, arcs)
    if walks is not None:
        walks.append(walk)
    return walk.run(CHUNK_BYTES)


def _plain_frame(f: Frame) -> bool:
    """Frames whose moves the frame passes pass through (relinked) and never report on."""
    return (f.polar is None and f.scaling is None and f.mirror is None and f.rotation is None
            and f.comp_side is CompSide.OFF and f.comp_radius_mm == 0.0 and not f.after_cancel
            and not f.machine_coords and f.total_offset_mm == ZERO6)


def _noop(line: int, offset: int, it: Interpreter) -> None:
    return None


class _Walk:
    """One walk over a program; the fast path's cached state lives in the attributes."""

    def __init__(self, src: SourceFile, dialect: Dialect, sink: DiagnosticSink, opts: InterpOptions,
                 arcs: ArcLimits) -> None:
        self.src, self.dialect, self.sink, self.opts, self.arcs = src, dialect, sink, opts, arcs
        self.parser = Parser(dialect, sink, ParseOptions(strict=opts.strict))
        self.it = Interpreter(dialect, sink, src.source_id, opts)
        self.semicolon_ok = dialect.block_end == ";"
        self.stale = True
        self.dirty = False
        self.slow = 0  # plain lines that went through the grammar for a state reason
        self.vectorised = 0  # plain lines decided by arrays (tests check the walk really is vectorised)
        self.window = 4096  # lines decided at once (shrinks after a failing line, grows back)

    # ---- state (the fast path's locals) ---------------------------------------------------
    def _load(self) -> None:
        it = self.it
        modal = it.modal
        self.ok = not (it.ended or modal.cycle or modal.per_rev or it.frame.polar is not None)
        self.cur = modal.motion
        self.inc = modal.incremental
        self.frame = it.frame
        rd = it.reader
        self.k_pt = rd.mm_per_unit
        self.k_int = rd.liu_length_mm if rd.liu_rule else self.k_pt
        self.feed_prog = modal.feed
        self.path = modal.path
        self.p = it.pos
        self.holding = not self.inc and True in self.frame.held_axes[:3]
        self.plain = _plain_frame(self.frame)
        self.stale = False

    def _store(self) -> None:
        if not self.stale:
            self.it.pos = self.p
        if self.dirty:
            _write_back(self.it, self.cur, self.feed_prog)
            self.dirty = False

    # ---- the walk -------------------------------------------------------------------------
    def run(self, chunk_bytes: int) -> Iterator[Command]:
        text = self.src.text
        ascii_only = text.isascii()
        data = text.encode("ascii") if ascii_only else text.encode("utf-8", "surrogatepass")
        try:
            bounds = ps.chunks(data, chunk_bytes)
        except ps.LineTooLong:
            raise NotStraight from None
        total_lines = data.count(b"\n") + 1
        char_base = 0  # character offset of the chunk's first byte
        line_base = 0  # 0-based line number of the chunk's first line
        for cs, ce in bounds:
            ch = ps.scan_chunk(data, cs, ce)
            if ascii_only:
                chars = np.arange(0)  # unused: characters are bytes
            else:
                cont = np.zeros(ce - cs + 1, np.int64)
                np.cumsum((ch.buf[: ce - cs] & 0xC0) == 0x80, out=cont[1:])
                chars = np.arange(ce - cs + 1) - cont + char_base
            starts = ch.starts + char_base if ascii_only else chars[ch.starts]
            ends = ch.ends + char_base if ascii_only else chars[ch.ends]
            general = np.flatnonzero(ch.kind == ps.GENERAL)
            if len(general):
                joined = "\n".join(text[starts[k]:ends[k]] for k in general.tolist())
                if not is_straight_line(joined, self.dialect):
                    raise NotStraight
            view = _ChunkView(ch, starts, ends)
            handed = yield from self._chunk(view, line_base, total_lines)
            if handed:
                return
            char_base = int(chars[ce - cs]) if not ascii_only else ce
            line_base += len(ch.starts)
        self._store()

    def _chunk(self, v: _ChunkView, line_base: int, total_lines: int) -> Generator[Command, None, bool]:
        """Walk one chunk's lines; True when the rest of the file went to lower_straight."""
        kind = v.ch.kind
        nlines = len(kind)
        breaks = [*np.flatnonzero(kind == ps.GENERAL).tolist(), nlines]
        i, b = 0, 0
        while i < nlines:
            while breaks[b] < i:
                b += 1
            j = min(breaks[b], i + self.window)  # lines [i, j) are plain or empty
            if j == i:
                yield from self._general(v, i, line_base)
                i += 1
                continue
            if self.stale:
                self._load()
            if self.slow > max(256, total_lines // _SLOW_SHARE) or (self.ok and not self.holding and not self.plain):
                yield from self._hand_over(v, i, line_base)
                return True
            if not self.ok:  # the fast path's modes are not in force: every line is general
                yield from self._general(v, i, line_base)
                i += 1
                continue
            if self.holding or j - i < _MIN_RUN:
                if kind[i] == ps.PLAIN:
                    self.slow += 1
                    yield from self._scalar(v, i, line_base)
                i += 1
                continue
            i = yield from self._run(v, i, j, line_base)
        return False

    def _general(self, v: _ChunkView, k: int, line_base: int) -> Iterator[Command]:
        """Line ``k`` through the grammar and the interpreter (nothing for an empty line)."""
        pos, end = int(v.starts[k]), int(v.ends[k])
        if end <= pos:
            return
        self._store()
        it = self.it
        for block in self.parser.blocks_of_line(self.src, pos, end, line_base + k + 1):
            yield from it.execute(block)
        self.stale = True

    def _scalar(self, v: _ChunkView, k: int, line_base: int) -> Iterator[Command]:
        """Plain line ``k`` as lower_straight's loop lowers it, one line (state loaded, ``ok``)."""
        text = self.src.text
        pos, end = int(v.starts[k]), int(v.ends[k])
        m = CAM_LINES.match(text, pos)
        if m is None or m.end() != end:  # pragma: no cover - the scanner and CAM_LINE disagree
            raise AssertionError(f"line {line_base + k + 1}: not a plain block after all")
        if end - pos <= MAX_LINE_CHARS:
            g, xs, ys, zs, is_, js, fs, semi = m.groups()
            p, cur, inc, k_pt, k_int = self.p, self.cur, self.inc, self.k_pt, self.k_int
            feed_mm_min = -1.0 if self.feed_prog is None else self.feed_prog * k_pt
            motion = cur if g is None else _MOTIONS[int(g)]
            if ((xs is not None or ys is not None or zs is not None) and (self.semicolon_ok or not semi)
                    and (fs is not None or feed_mm_min > 0.0 or motion == "rapid")
                    and (motion == "linear" or motion == "rapid" if is_ is None and js is None
                         else (motion == "arc_cw" or motion == "arc_ccw") and zs is None
                         and self.frame.plane is Plane.XY)):
                try:  # every number first: one that float() rejects sends the line to the general path
                    f_new = float(fs) if fs is not None else -1.0
                    if f_new == 0.0 and motion != "rapid":
                        raise ValueError("F0 on a feed move: the general path reports it")
                    x, y, z, ci, cj = _words(p, xs, ys, zs, is_, js, k_pt, k_int, inc)
                    if (is_ is not None or js is not None) and ci == p[0] and cj == p[1]:
                        raise ValueError("zero-radius arc: the general path reports it")
                except ValueError:
                    pass
                else:
                    yield from self._lowered(m, pos, end, motion, p, (x, y, z, p[3], p[4], p[5]), ci, cj,
                                             f_new if fs is not None else None, feed_mm_min)
                    return
        yield from self._general(v, k, line_base)

    def _lowered(self, m: re.Match[str], pos: int, end: int, motion: str, p: Vec6, q: Vec6, ci: float, cj: float,
                 f_new: float | None, feed_mm_min: float) -> Iterator[Command]:
        """The commands of a line the scalar walk lowers, and the state after it."""
        sid = self.src.source_id
        _g, xs, ys, zs = m.group(1, 2, 3, 4)
        if motion != self.cur:
            self.cur = motion
            self.dirty = True
        frame = self.frame
        if f_new is not None:
            self.feed_prog = f_new
            feed_mm_min = f_new * self.k_pt
            self.dirty = True
            yield FeedRate(new_span(sid, m.start(7) - 1, m.end(7)), frame, feed_mm_min, False)
        if self.holding:
            held = frame.held_axes
            named = [k for k, t in ((0, xs), (1, ys), (2, zs)) if t is not None and held[k]]
            if named:
                self.it.release_axes(named)
                frame = self.frame = self.it.frame
                self.holding = True in frame.held_axes[:3]
                self.plain = _plain_frame(frame)
        span = new_span(sid, pos, end)
        if motion == "linear":
            yield Linear(span, frame, p, q, feed_mm_min, self.path, PROGRAMMED)
        elif motion == "rapid":
            yield new_rapid(span, frame, p, q, self.path)
        else:
            yield Arc(span, frame, p, q, (ci, cj, p[2], p[3], p[4], p[5]), -1 if motion == "arc_cw" else 1,
                      Plane.XY, feed_mm_min, self.path)
        self.p = q

    def _hand_over(self, v: _ChunkView, k: int, line_base: int) -> Iterator[Command]:
        """The rest of the file, from line ``k`` of this chunk, through lower_straight itself
        (once the rest, whose later chunks were not scanned, is seen to be straight-line too)."""
        start = int(v.starts[k])
        if not is_straight_line(self.src.text[start:], self.dialect):
            raise NotStraight
        self._store()
        cp = Checkpoints(on_line=_noop, every=1 << 62, interp=self.it, start=start, line=line_base + k)
        yield from lower_straight(self.src, self.dialect, self.sink, self.opts, cp)

    # ---- a run of plain lines --------------------------------------------------------------
    def _run(self, v: _ChunkView, i: int, j: int, line_base: int) -> Generator[Command, None, int]:
        """Decide lines [i, j) (plain or empty) with arrays; yield what the passes must see;
        return the next line to walk."""
        ch = v.ch
        window = j - i
        tk = ch.tok[:, i:j]
        has = tk >= 0
        nonempty = ch.kind[i:j] == ps.PLAIN
        ar = np.arange(window)
        gw = tk[ps.G]
        g = np.where(gw >= 0, ch.g_number[np.maximum(gw, 0)], -1)
        last_g = np.maximum.accumulate(np.where(gw >= 0, ar, -1))
        motion = np.where(last_g >= 0, g[np.maximum(last_g, 0)], _CODE.get(self.cur, _OTHER))
        fw = tk[ps.F]
        has_f = fw >= 0
        f_zero = has_f & ch.zero[np.maximum(fw, 0)]
        last_f = np.maximum.accumulate(np.where(has_f, ar, -1))
        before_f = np.empty_like(last_f)
        before_f[0] = -1
        before_f[1:] = last_f[:-1]
        seed_pos = self.feed_prog is not None and self.feed_prog * self.k_pt > 0.0
        feed_pos = np.where(before_f >= 0, ~ch.zero[fw[np.maximum(before_f, 0)]], seed_pos)
        has_xyz = has[ps.X] | has[ps.Y] | has[ps.Z]
        arc = has[ps.I] | has[ps.J]
        cond = has_xyz & (has_f | feed_pos | (motion == 0))
        if not self.semicolon_ok:
            cond &= ~ch.semi[i:j]
        plane_xy = self.frame.plane is Plane.XY
        cond &= np.where(arc, (motion >= 2) & (motion <= 3) & ~has[ps.Z] & plane_xy, motion <= 1)
        cond &= ~(f_zero & (motion != 0))
        cond &= (v.ends[i:j] - v.starts[i:j]) <= MAX_LINE_CHARS
        fail = np.flatnonzero(nonempty & ~cond)
        stop = int(fail[0]) if len(fail) else window  # lines [0, stop) of the window are fast
        ends = _Ends(self, ch, tk, has, stop)
        arcs = np.flatnonzero(arc[:stop] & nonempty[:stop])
        suspects: list[int] = []
        if len(arcs):
            sx, sy = ends.at(ps.X, arcs - 1), ends.at(ps.Y, arcs - 1)
            ex, ey = ends.at(ps.X, arcs), ends.at(ps.Y, arcs)
            ci = np.where(has[ps.I, arcs], sx + ends.word_values(tk[ps.I, arcs], has[ps.I, arcs]), sx)
            cj = np.where(has[ps.J, arcs], sy + ends.word_values(tk[ps.J, arcs], has[ps.J, arcs]), sy)
            flat = np.flatnonzero((ci == sx) & (cj == sy))  # a zero-radius arc: the general path reports it
            if len(flat):
                stop = int(arcs[flat[0]])
                keep = arcs < stop
                arcs = arcs[keep]
                sx, sy, ex, ey, ci, cj = (a[keep] for a in (sx, sy, ex, ey, ci, cj))
            suspects = arcs[~self._arcs_clear(sx, sy, ex, ey, ci, cj)].tolist()
        fast = np.flatnonzero(nonempty[:stop])
        if len(fast):
            first, last = int(fast[0]), int(fast[-1])
            shown = sorted({first, *suspects, last})
            rank = np.searchsorted(fast, shown).tolist()  # place among the fast lines
            for n, k in enumerate(shown):
                prev = shown[n - 1] if n and rank[n] - rank[n - 1] > 1 else None  # fast lines skipped between
                yield from self._materialise(v, ends, i, k, prev, line_base)
            self.vectorised += len(fast)
            self.p = ends.position(last)
            if bool(has_f[:stop].any()):
                w = int(fw[int(last_f[stop - 1])])
                self.feed_prog = float(ps.values(ch, np.array([w]))[0])
                self.dirty = True
            new_cur = _MOTIONS[int(motion[last])]
            if new_cur != self.cur:
                self.cur = new_cur
                self.dirty = True
        if stop < window:
            self.slow += 1
            self.window = max(64, 2 * stop)
            yield from self._general(v, i + stop, line_base)
            return i + stop + 1
        self.window = min(2 * self.window, 1 << 17)
        return j

    def _arcs_clear(self, sx: npt.NDArray[np.float64], sy: npt.NDArray[np.float64], ex: npt.NDArray[np.float64],
                    ey: npt.NDArray[np.float64], ci: npt.NDArray[np.float64],
                    cj: npt.NDArray[np.float64]) -> npt.NDArray[np.bool_]:
        """Arcs whose radii agree within the arc check's tolerance by more than any rounding."""
        a = self.arcs
        r0 = np.hypot(sx - ci, sy - cj)
        r1 = np.hypot(ex - ci, ey - cj)
        diff = np.abs(r1 - r0)
        tol = a.abs_tol_inch_mm if a.abs_tol_inch_mm > 0 and self.frame.units.value == "inch" else a.abs_tol_mm
        margin = 1e-9 + 1e-12 * (r0 + r1)
        clear = diff <= np.maximum(tol, a.rel_tol * r0) + 1e-9 - margin
        if a.max_abs_factor > 0:
            clear &= diff <= a.max_abs_factor * tol - margin
        out: npt.NDArray[np.bool_] = clear & np.isfinite(diff)
        return out

    def _materialise(self, v: _ChunkView, ends: _Ends, i: int, k: int, prev: int | None,
                     line_base: int) -> Iterator[Command]:
        """The fast path's commands of line ``i + k``, built as lower_straight builds them; when
        fast lines after line ``i + prev`` (the last one yielded) were skipped, first a stand-in
        move from its end to where line ``i + k`` starts, so the passes relink as they would."""
        start = ends.position(k - 1)
        frame = self.frame
        sid = self.src.source_id
        if prev is not None:
            yield Linear(new_span(sid, int(v.starts[i + k - 1]), int(v.ends[i + k - 1])), frame,
                         ends.position(prev), start, 1.0, self.path, PROGRAMMED)
        pos, end = int(v.starts[i + k]), int(v.ends[i + k])
        m = CAM_LINES.match(self.src.text, pos)
        if m is None or m.end() != end:  # pragma: no cover - the scanner and CAM_LINE disagree
            raise AssertionError(f"line {line_base + i + k + 1}: not a plain block after all")
        gs, xs, ys, zs, is_, js, fs, _semi = m.groups()
        motion = ends.motion_before(k) if gs is None else _MOTIONS[int(gs)]
        p = start
        k_pt, k_int, inc = self.k_pt, self.k_int, self.inc
        x, y, z, ci, cj = _words(p, xs, ys, zs, is_, js, k_pt, k_int, inc)
        q = (x, y, z, p[3], p[4], p[5])
        feed_mm_min = ends.feed_before(k)
        if fs is not None:
            feed_mm_min = float(fs) * k_pt
            yield FeedRate(new_span(sid, m.start(7) - 1, m.end(7)), frame, feed_mm_min, False)
        span = new_span(sid, pos, end)
        if motion == "linear":
            yield Linear(span, frame, p, q, feed_mm_min, self.path, PROGRAMMED)
        elif motion == "rapid":
            yield new_rapid(span, frame, p, q, self.path)
        else:
            yield Arc(span, frame, p, q, (ci, cj, p[2], p[3], p[4], p[5]), -1 if motion == "arc_cw" else 1,
                      Plane.XY, feed_mm_min, self.path)


def _words(p: Vec6, xs: str | None, ys: str | None, zs: str | None, is_: str | None, js: str | None,
           k_pt: float, k_int: float, inc: bool) -> tuple[float, float, float, float, float]:
    """X, Y, Z and the arc centre of a plain block's words from ``p``, as the fast path's loop reads
    them (:func:`cncc.frontend.fastpath.lower_straight`, inlined there for speed); ValueError for a
    number that float() rejects."""
    x, y, z = p[0], p[1], p[2]
    if xs is not None:
        d = float(xs) * (k_pt if "." in xs else k_int)
        x = x + d if inc else d
    if ys is not None:
        d = float(ys) * (k_pt if "." in ys else k_int)
        y = y + d if inc else d
    if zs is not None:
        d = float(zs) * (k_pt if "." in zs else k_int)
        z = z + d if inc else d
    ci, cj = p[0], p[1]
    if is_ is not None:
        ci += float(is_) * (k_pt if "." in is_ else k_int)
    if js is not None:
        cj += float(js) * (k_pt if "." in js else k_int)
    return x, y, z, ci, cj


@dataclass(slots=True)
class _ChunkView:
    ch: ps.Chunk
    starts: npt.NDArray[np.int64]  # line starts, characters in the source
    ends: npt.NDArray[np.int64]


class _Ends:
    """End points, motion and feed along a window of plain lines (lines before ``stop`` are fast)."""

    def __init__(self, w: _Walk, ch: ps.Chunk, tk: npt.NDArray[np.int32], has: npt.NDArray[np.bool_],
                 stop: int) -> None:
        self.w, self.ch, self.tk, self.has, self.stop = w, ch, tk, has, stop
        ar = np.arange(tk.shape[1])
        self.last = {a: np.maximum.accumulate(np.where(has[a], ar, -1)) for a in (ps.X, ps.Y, ps.Z)}
        self.table: dict[int, npt.NDArray[np.float64]] = {}  # incremental: end after each word

    def word_values(self, words: npt.NDArray[np.int32], present: npt.NDArray[np.bool_]) -> npt.NDArray[np.float64]:
        """The programmed lengths of ``words`` (0 where not ``present``), in mm, as the fast path reads them."""
        out = np.zeros(len(words))
        sel = words[present].astype(np.int64)
        w = self.w
        out[present] = ps.values(self.ch, sel) * np.where(self.ch.point[sel], w.k_pt, w.k_int)
        return out

    def at(self, axis: int, ks: npt.NDArray[np.int64]) -> npt.NDArray[np.float64]:
        """The axis position after lines ``ks`` of the window (-1: before the window)."""
        seed = self.w.p[axis - ps.X]
        li = np.where(ks >= 0, self.last[axis][np.maximum(ks, 0)], -1)
        if self.w.inc:
            table = self.table.get(axis)
            if table is None:
                words = self.tk[axis][self.has[axis]]
                steps = self.word_values(words, np.ones(len(words), np.bool_))
                table = np.cumsum(np.concatenate(([seed], steps)))
                self.table[axis] = table
            count = np.cumsum(self.has[axis])  # words up to and including each line
            return np.where(li >= 0, table[count[np.maximum(li, 0)]], seed)
        out = np.full(len(ks), seed)
        m = li >= 0
        if m.any():
            out[m] = self.word_values(self.tk[axis, li[m]], np.ones(int(m.sum()), np.bool_))
        return out

    def position(self, k: int) -> tuple[float, float, float, float, float, float]:
        """The position after line ``k`` of the window (-1: the position before it)."""
        p = self.w.p
        if k < 0:
            return p
        ks = np.array([k])
        return (float(self.at(ps.X, ks)[0]), float(self.at(ps.Y, ks)[0]), float(self.at(ps.Z, ks)[0]), p[3], p[4], p[5])

    def motion_before(self, k: int) -> str:
        gw = self.tk[ps.G, :k]
        present = np.flatnonzero(gw >= 0)
        if len(present) == 0:
            return self.w.cur
        return _MOTIONS[int(self.ch.g_number[gw[present[-1]]])]

    def feed_before(self, k: int) -> float:
        fw = self.tk[ps.F, :k]
        present = np.flatnonzero(fw >= 0)
        if len(present) == 0:
            fp = self.w.feed_prog
            return -1.0 if fp is None else fp * self.w.k_pt
        return float(ps.values(self.ch, np.array([int(fw[present[-1]])]))[0]) * self.w.k_pt

