"""The fast path, a chunk of lines at a time: runs of plain blocks become :class:`MoveBatch` es.

:func:`lower_batched` lowers a straight-line program (:func:`fastpath.is_straight_line`)
to the same commands as :func:`fastpath.lower_straight`, except that runs of plain blocks
come out as :class:`~cncc.ir.batch.MoveBatch` items that stand for exactly the commands
the per-line fast path makes (``tests/frontend/test_fastbatch.py`` compares both).

It alternates two modes.  The per-line loop (:func:`fastpath.lower_lines`) runs until
``STREAK`` plain lines in a row took its fast path; then a chunk of whole lines is matched
with one ``findall`` of :data:`CHUNK_LINE` (the pattern of :data:`fastpath.CAM_LINE` with
the places of the F word's ends captured).  If every line of the chunk matched, the words
are converted column by column and the conditions of the per-line fast path are checked
with array operations; the lines before the first line that fails one go out as one batch,
and the per-line loop takes over at that line.  A chunk in which some line does not match
is halved until one matches (or goes to the per-line loop).

Only absolute distances (G90), no held axes and the modes the per-line fast path accepts
are lowered by chunks; everything else stays with the per-line loop, which is the
definition.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import Any

import numpy as np

from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend.fastpath import _NUM, Resume, _write_back, lower_lines
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.parser import MAX_LINE_CHARS, ParseOptions, Parser
from cncc.ir import Plane
from cncc.ir.batch import Item, MoveBatch
from cncc.source import SourceFile

_HEAD = r"^(?:N\d+ *)?(?:G0*([0-3]) *)?"
_XYZ = rf"(?:X{_NUM} *)?(?:Y{_NUM} *)?(?:Z{_NUM} *)?"
_IJ = rf"(?:I{_NUM} *)?(?:J{_NUM} *)?"
_FEED = r"(?:F([\d.]{1,12}+))?"
CHUNK_LINE = re.compile(_HEAD + _XYZ + _IJ + _FEED + r"( *;? *\r?)$", re.MULTILINE)
""":data:`fastpath.CAM_LINE` (the same lines) with the text after the F number as one group,
so the F word's span follows from the line's end."""
_VARIANTS = {  # (I or J in the chunk, F in the chunk) -> the same pattern without the absent words' groups
    (True, True): CHUNK_LINE,
    (True, False): re.compile(_HEAD + _XYZ + _IJ + r" *;? *\r?$", re.MULTILINE),
    (False, True): re.compile(_HEAD + _XYZ + _FEED + r"( *;? *\r?)$", re.MULTILINE),
    (False, False): re.compile(_HEAD + _XYZ + r" *;? *\r?$", re.MULTILINE),
}
"""A chunk without the letters I, J or F matches these exactly where it matches :data:`CHUNK_LINE`;
fewer groups make ``findall`` cheaper.  Missing columns are filled in as empty."""

_POW10 = np.array([10.0 ** k for k in range(16)])  # exact doubles
STREAK = 32  # plain lines in a row before the per-line loop hands over to chunks
MIN_CHUNK, MAX_CHUNK = 1 << 11, 1 << 16  # characters per chunk
_MOTION_CODE = {"": -1, "0": 0, "1": 1, "2": 2, "3": 3}
_CODE_MOTION = ("rapid", "linear", "arc_cw", "arc_ccw")
_MOTION_NUMBER = {"rapid": 0, "linear": 1, "arc_cw": 2, "arc_ccw": 3}
_KIND_OF_CODE = np.array([0, 1, 2, 2], dtype=np.int8)  # G0 rapid, G1 linear, G2/G3 arc
_TURNS_OF_CODE = np.array([0, 0, -1, 1], dtype=np.int8)


def lower_batched(src: SourceFile, dialect: Dialect, sink: DiagnosticSink,
                  opts: InterpOptions) -> Iterator[Item]:
    """Lower a straight-line program; runs of plain blocks come out as batches."""
    parser = Parser(dialect, sink, ParseOptions(strict=opts.strict))
    it = Interpreter(dialect, sink, src.source_id, opts)
    text = src.text
    n = len(text)
    last_line_end = n - 1 if text.endswith("\n") else n
    semicolon_ok = dialect.block_end == ";"
    pos, line_no = 0, 0
    size = MIN_CHUNK
    while pos < n:
        resume = Resume(streak=STREAK)
        yield from lower_lines(parser, it, src, pos, line_no, None, resume)
        if not resume.stopped:
            return
        pos, line_no = resume.pos, resume.line_no
        while pos <= last_line_end:  # chunks while they lower whole
            stop = text.find("\n", pos + size, last_line_end) if pos + size < last_line_end else -1
            stop = last_line_end if stop < 0 else stop
            lines = text.count("\n", pos, stop) + 1
            has_ij = text.find("I", pos, stop) >= 0 or text.find("J", pos, stop) >= 0
            has_f = text.find("F", pos, stop) >= 0 or (not semicolon_ok and text.find(";", pos, stop) >= 0)
            rows = _VARIANTS[has_ij, has_f].findall(text, pos, stop)
            if len(rows) != lines:  # some line is no plain block
                if size > MIN_CHUNK:
                    size //= 2
                    continue
                break
            got = _chunk(it, src, pos, stop, _columns(rows, has_ij, has_f), semicolon_ok)
            if got is None:
                break
            batch, done = got
            if batch is not None:
                yield batch
            line_no += done
            pos = stop + 1 if done == lines else _line_start(text, pos, done)
            if done < lines:
                break
            size = min(size * 2, MAX_CHUNK)


def _columns(rows: list[tuple[str, ...]], has_ij: bool, has_f: bool) -> list[tuple[str, ...]]:
    """The 8 columns of :data:`CHUNK_LINE` (g x y z i j f tail) from the rows of a variant."""
    cols = list(zip(*rows, strict=True))
    empty = ("",) * len(rows)
    ij = cols[4:6] if has_ij else [empty, empty]
    rest = cols[6 if has_ij else 4:]
    f_tail = rest if has_f else [empty, empty]
    return cols[:4] + ij + f_tail


def _line_start(text: str, pos: int, k: int) -> int:
    """The offset of the line ``k`` lines after the one starting at ``pos``."""
    for _ in range(k):
        pos = text.index("\n", pos) + 1
    return pos


def _numbers(u: np.ndarray[Any, Any]) -> tuple[np.ndarray[Any, Any], np.ndarray[Any, Any], int]:
    """(values, has a point, index of the first bad one or ``len(u)``) of the words of the string
    array ``u`` (``''``: no word, value 0).

    The regular expression lets through ``[-+]?[\\d.]{1,12}``; ``float()`` refuses those without a
    digit or with two points.  The others are read as an integer of at most 12 digits divided by
    a power of ten: both are exact doubles, so the quotient is the correctly rounded value
    ``float()`` gives."""
    n = len(u)
    width = u.dtype.itemsize // 4
    c = u.view(np.uint32).reshape(n, width) if n else np.zeros((0, width), dtype=np.uint32)
    digit = (c >= 48) & (c <= 57)
    dot = c == 46
    ndots = dot.sum(axis=1)
    ndigits = digit.sum(axis=1)
    present = c[:, 0] != 0
    bad = present & ((ndots > 1) | (ndigits == 0))
    value = np.zeros(n, dtype=np.int64)
    after = np.zeros(n, dtype=np.int64)  # digits after the point
    seen_dot = np.zeros(n, dtype=bool)
    for col in range(width):
        d = digit[:, col]
        value = np.where(d, value * 10 + (c[:, col].astype(np.int64) - 48), value)
        after += d & seen_dot
        seen_dot |= dot[:, col]
    out = value / _POW10[after]
    out = np.where(c[:, 0] == 45, -out, out)
    first_bad = np.flatnonzero(bad)
    return out, ndots > 0, int(first_bad[0]) if len(first_bad) else n


def _ffill(values: np.ndarray[Any, Any], present: np.ndarray[Any, Any], first: float) -> np.ndarray[Any, Any]:
    """Each row's value, or the last present one before it, or ``first``."""
    idx = np.where(present, np.arange(len(values)), -1)
    np.maximum.accumulate(idx, out=idx)
    return np.where(idx >= 0, values[np.maximum(idx, 0)], first)


def _chunk(it: Interpreter, src: SourceFile, pos: int, stop: int, cols: list[tuple[str, ...]],
           semicolon_ok: bool) -> tuple[MoveBatch | None, int] | None:
    """Lower the leading lines of a chunk whose lines all match :data:`CHUNK_LINE`: (the batch
    or None, how many lines it covers); None when the state does not allow chunks at all."""
    modal = it.modal
    frame = it.frame
    if (it.ended or modal.cycle or modal.per_rev or frame.polar is not None or modal.incremental
            or True in frame.held_axes[:3] or modal.motion not in _MOTION_NUMBER):
        return None
    rd = it.reader
    k_pt = rd.mm_per_unit
    k_int = rd.liu_length_mm if rd.liu_rule else k_pt
    feed0 = -1.0 if modal.feed is None else modal.feed * k_pt
    p = it.pos
    g, xs, ys, zs, is_, js, fs, tail = cols
    m = len(g)
    # line ends: the newlines of the chunk (all its characters are ASCII: every line matched)
    raw = np.frombuffer(src.text[pos:stop].encode("ascii"), dtype=np.uint8)
    ends = np.empty(m, dtype=np.int64)
    ends[:-1] = np.flatnonzero(raw == 10) + pos
    ends[-1] = stop
    starts = np.empty(m, dtype=np.int64)
    starts[0] = pos
    starts[1:] = ends[:-1] + 1
    ok = ends - starts <= MAX_LINE_CHARS
    words: dict[str, tuple[Any, Any, Any]] = {}
    limit = m
    for name, col in (("x", xs), ("y", ys), ("z", zs), ("i", is_), ("j", js), ("f", fs)):
        if not any(col):
            none = np.zeros(m, dtype=bool)
            words[name] = (none, np.zeros(m), none)
            continue
        u = np.array(col)
        vals, dot, bad = _numbers(u)
        limit = min(limit, bad)
        words[name] = (u != "", vals, dot)
    code = np.array([_MOTION_CODE[c] for c in g], dtype=np.int8)
    code = _ffill(code, code >= 0, _MOTION_NUMBER[modal.motion]).astype(np.int8)
    fp, fv, _ = words["f"]
    f_mm = fv * k_pt
    feed_before = np.empty(m)
    feed_before[0] = feed0
    feed_before[1:] = _ffill(f_mm, fp, feed0)[:-1]
    feed = np.where(fp, f_mm, feed_before)
    rapid = code == 0
    ok &= words["x"][0] | words["y"][0] | words["z"][0]
    if not semicolon_ok:
        ok &= np.array([";" not in t for t in tail])
    ok &= fp | (feed_before > 0.0) | rapid
    ok &= ~(fp & (fv == 0.0) & ~rapid)
    has_ij = words["i"][0] | words["j"][0]
    arc = code >= 2
    ok &= np.where(has_ij, arc & ~words["z"][0] & (frame.plane is Plane.XY), ~arc)
    pos_mm: dict[str, Any] = {}
    for name, k0 in (("x", 0), ("y", 1), ("z", 2)):
        present, vals, dot = words[name]
        v = vals * np.where(dot, k_pt, k_int)
        pos_mm[name] = _ffill(v, present, p[k0])
    sx = np.empty(m)
    sy = np.empty(m)
    sz = np.empty(m)
    sx[0], sy[0], sz[0] = p[0], p[1], p[2]
    sx[1:], sy[1:], sz[1:] = pos_mm["x"][:-1], pos_mm["y"][:-1], pos_mm["z"][:-1]
    ip, iv, idot = words["i"]
    jp, jv, jdot = words["j"]
    ci = np.where(ip, sx + iv * np.where(idot, k_pt, k_int), sx)
    cj = np.where(jp, sy + jv * np.where(jdot, k_pt, k_int), sy)
    ok &= ~(has_ij & (ci == sx) & (cj == sy))
    ok[limit:] = False
    fails = np.flatnonzero(~ok)
    k = int(fails[0]) if len(fails) else m
    if k == 0:
        return None, 0
    end = np.empty((k, 6))
    end[:, 0], end[:, 1], end[:, 2] = pos_mm["x"][:k], pos_mm["y"][:k], pos_mm["z"][:k]
    end[:, 3:] = p[3:]
    center = np.empty((k, 6))
    center[:, 0], center[:, 1], center[:, 2] = ci[:k], cj[:k], sz[:k]
    center[:, 3:] = p[3:]
    ck = code[:k]
    fpk = fp[:k]
    # the F word: from its letter to the end of its number, before the spaces, ';' and the tail
    f_end = np.full(k, -1, dtype=np.int64)
    f_start = np.full(k, -1, dtype=np.int64)
    with_f = np.flatnonzero(fpk)
    if len(with_f):
        rows_f = with_f.tolist()
        f_end[with_f] = ends[with_f] - np.array([len(tail[i]) for i in rows_f], dtype=np.int64)
        f_start[with_f] = f_end[with_f] - np.array([len(fs[i]) for i in rows_f], dtype=np.int64) - 1
    batch = MoveBatch(src.source_id, frame, modal.path, Plane.XY, p, _KIND_OF_CODE[ck], end, center,
                      _TURNS_OF_CODE[ck], feed[:k].copy(), starts[:k].copy(), ends[:k].copy(), f_start, f_end)
    motion = _CODE_MOTION[int(ck[-1])]
    it.pos = batch.last_end
    if motion != modal.motion or fpk.any():
        last_f = np.flatnonzero(fpk)
        feed_prog = float(fv[int(last_f[-1])]) if len(last_f) else modal.feed
        _write_back(it, motion, feed_prog)
    return batch, k
