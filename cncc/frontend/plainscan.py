"""A vectorised scanner for plain CAM blocks: which lines of a byte buffer are plain, and their words.

The fast path (:mod:`cncc.frontend.fastpath`) reads a plain motion block with the regular
expression ``CAM_LINE``: ``N? G0-3? X? Y? Z? I? J? F?`` in that order, each letter directly
followed by its number (``[-+]?[\\d.]{1,12}`` for the axes and centres, ``[\\d.]{1,12}`` for F,
``\\d+`` for N, ``0*[0-3]`` for G), spaces between words, an optional ``;`` and ``\\r`` at the
end.  :func:`scan_chunk` decides the same thing for every line of a chunk of bytes at once,
with numpy over the buffer instead of a regex match per line, and also refuses the numbers
``float()`` refuses (no digit, two points), which the fast path sends to the general path.
A line it calls *plain* (:data:`PLAIN`) matches ``CAM_LINE`` with numbers ``float()`` reads;
every other non-empty line is :data:`GENERAL`.  It is stricter than the regex in one place
only: a ``;`` must end the line (``X1 ; `` is general), which costs speed, never a result.

For a plain line the chunk holds the index of each of its words (``tok[rank, line]``, -1 when
absent) and, per word, the facts the front end's checks need without the number's value: a
sign, a decimal point, whether every digit is zero (``F0``), the G number.  Values are read
on demand by :func:`values` for the words that need them (arc geometry, incremental moves),
exactly as ``float()`` reads them: the digits as an integer (at most 12, so exact) divided by
a power of ten (exact up to 10**22), one correctly rounded division.

Only numpy; no knowledge of modal state (that is :mod:`cncc.frontend.syntax_fast`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

EMPTY, PLAIN, GENERAL = 0, 1, 2  # line kinds

RANKS = "NGXYZIJF"  # the word order of CAM_LINE
N, G, X, Y, Z, I, J, F = range(8)  # noqa: E741 - the address letters
MAX_NUMBER_CHARS = 12  # [\d.]{1,12}: a longer number takes the general path

_DIG, _DOT, _SIGN, _SPACE, _SEMI, _CR, _LETTER, _BAD = 1, 2, 4, 8, 16, 32, 64, 128
_NUM = _DIG | _DOT | _SIGN

_FLAGS = np.full(256, _BAD, np.uint8)
for _c in b"0123456789":
    _FLAGS[_c] = _DIG
_FLAGS[ord(".")] = _DOT
_FLAGS[ord("+")] = _FLAGS[ord("-")] = _SIGN
_FLAGS[ord(" ")] = _SPACE
_FLAGS[ord(";")] = _SEMI
_FLAGS[ord("\r")] = _CR
_FLAGS[ord("\n")] = 0
for _c in RANKS.encode():
    _FLAGS[_c] = _LETTER

_RANK = np.zeros(256, np.int8)
for _i, _c in enumerate(RANKS.encode()):
    _RANK[_c] = _i
_AXIS = np.zeros(256, np.bool_)  # letters whose number may be signed
for _c in b"XYZIJ":
    _AXIS[_c] = True

# one cumulative sum counts three things: number characters (bits 0-20), digits (21-41) and
# letters (42-62); a chunk is at most 2**21 - 1 bytes
_FIELD = 21
_MASK = (1 << _FIELD) - 1
MAX_CHUNK = (1 << _FIELD) - 64
_COUNT = np.zeros(256, np.uint64)
for _c in b"0123456789":
    _COUNT[_c] = 1 | (1 << _FIELD)
_COUNT[ord(".")] = _COUNT[ord("+")] = _COUNT[ord("-")] = 1
for _c in RANKS.encode():
    _COUNT[_c] = 1 << (2 * _FIELD)
_IS_LETTER = (_FLAGS & _LETTER) != 0


def _bad_pairs() -> npt.NDArray[np.bool_]:
    """Whether two consecutive bytes ``x y`` (index ``x * 256 + y``) make the line of ``x`` not plain:
    ``x`` is another character; a '\r' not before the line end; a ';' not before '\r' or the line end;
    a letter not followed by its number; a number after a space; a sign after anything but X Y Z I J
    (a sign that starts a line is refused because a plain line starts with its first word)."""
    x = np.repeat(np.arange(256), 256)
    y = np.tile(np.arange(256), 256)
    fx, fy = _FLAGS[x], _FLAGS[y]
    bad = (fx & _BAD) != 0
    bad |= ((fx & _CR) != 0) & (y != 10)
    bad |= ((fx & _SEMI) != 0) & ((fy & _CR) == 0) & (y != 10)
    bad |= ((fx & _LETTER) != 0) & ((fy & _NUM) == 0)
    bad |= ((fx & _SPACE) != 0) & ((fy & _NUM) != 0)
    bad |= ((fy & _SIGN) != 0) & ~_AXIS[x]
    bad &= x != 10
    out: npt.NDArray[np.bool_] = bad
    return out


_BAD_PAIR = _bad_pairs()

_POW10 = np.array([10.0 ** k for k in range(23)])  # exact: 10**k is a double for k <= 22

IntArray = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]


@dataclass(slots=True)
class Chunk:
    """The lines of ``buf[:n]`` (byte offsets within the chunk) and the words of its plain lines."""

    buf: npt.NDArray[np.uint8]  # the chunk's bytes, then a '\n' and zero padding
    starts: IntArray  # line starts
    ends: IntArray  # line ends: the '\n' (or the chunk's end); a '\r' before it is in the line
    kind: npt.NDArray[np.int8]  # EMPTY, PLAIN or GENERAL per line
    tok: npt.NDArray[np.int32]  # (8, lines): word index of each letter in RANKS order, -1 absent
    letter: IntArray  # per word: position of its letter
    nchars: IntArray  # per word: characters of its number (sign included)
    signed: BoolArray  # per word: the number starts with + or -
    point: BoolArray  # per word: it has a decimal point
    zero: BoolArray  # per word: every digit is 0
    g_number: npt.NDArray[np.int8]  # per word: the last digit (the G number of a G word)
    semi: BoolArray  # per line: ends with ';'


def scan_chunk(data: bytes | memoryview, start: int, stop: int) -> Chunk:
    """Scan ``data[start:stop]`` (whole lines: ``stop`` is just after a '\\n' or the end)."""
    n = stop - start
    buf = np.zeros(n + 32, np.uint8)
    buf[:n] = np.frombuffer(data, np.uint8, n, start)
    buf[n] = 10  # a line end after the last line
    b = buf[:n]
    nl = np.flatnonzero(b == 10)
    ends = nl if n == 0 or b[n - 1] == 10 else np.append(nl, n)
    starts = np.empty_like(ends)
    if len(ends):
        starts[0] = 0
        starts[1:] = ends[:-1] + 1
    nlines = len(ends)
    # the byte-pair rules (_bad_pairs) on the pairs at even and at odd offsets: two lookups of n/2
    half = (n + 2) // 2
    even = _BAD_PAIR[buf[: 2 * half].view(">u2")]
    odd = _BAD_PAIR[buf[1 : 2 * half + 1].view(">u2")]
    pos_bad = np.concatenate((np.flatnonzero(even) * 2, np.flatnonzero(odd) * 2 + 1))
    line_bad = np.zeros(nlines, np.bool_)
    if len(pos_bad):
        line_bad[np.searchsorted(starts, pos_bad[pos_bad < n], "right") - 1] = True
    empty = starts == ends
    line_bad |= ~empty & ~_IS_LETTER[buf[starts]]  # a plain line starts with its first word
    # words: letter, rank, line; ranks strictly increase along a line
    counts = np.cumsum(_COUNT[b])  # inclusive: counts[k] covers b[: k + 1]
    letter = np.flatnonzero(_IS_LETTER[b])
    rank = _RANK[b[letter]]
    per_line = np.zeros(nlines, np.int64)
    if nlines and n:
        c_end = counts[ends - 1] >> np.uint64(2 * _FIELD)
        c_start = np.where(starts > 0, counts[np.maximum(starts - 1, 0)] >> np.uint64(2 * _FIELD), 0)
        per_line = np.where(empty, 0, c_end - c_start).astype(np.int64)
    line = np.repeat(np.arange(nlines), per_line)
    same = line[1:] == line[:-1]
    line_bad[line[1:][same & (rank[1:] <= rank[:-1])]] = True
    bound = np.empty_like(letter)  # the word's characters end at the next letter or the line end
    if len(letter):
        bound[:-1] = np.where(same, letter[1:], ends[line[:-1]])
        bound[-1] = ends[line[-1]]
    c = (counts[bound - 1] - counts[letter]).astype(np.int64)  # over [letter + 1, bound)
    nchars = c & _MASK
    ndigits = (c >> _FIELD) & _MASK
    signed = buf[letter + 1] == 45
    signed |= buf[letter + 1] == 43
    body = nchars - signed  # characters after the sign
    npoints = body - ndigits
    last = buf[letter + nchars]  # the number's last character
    ok = (ndigits >= 1) & (npoints <= 1) & (body <= MAX_NUMBER_CHARS)  # [\d.]{1,12} that float() reads
    is_n = rank == N
    ok[is_n] = npoints[is_n] == 0  # N\d+: any length
    zero = np.zeros(len(letter), np.bool_)
    f_words = np.flatnonzero(rank == F)
    zero[f_words] = _all_zero(buf, letter[f_words] + 1, nchars[f_words])  # F0
    g_words = np.flatnonzero(rank == G)
    g_len = nchars[g_words]
    lead = np.ones(len(g_words), np.bool_)  # the G number is 0*[0-3]: zeros, then its last digit
    two = g_len == 2
    lead[two] = buf[letter[g_words[two]] + 1] == 48
    more = np.flatnonzero(g_len > 2)
    lead[more] = _all_zero(buf, letter[g_words[more]] + 1, g_len[more] - 1)
    ok[g_words] = (npoints[g_words] == 0) & lead & (last[g_words] <= 51)
    zero[g_words] = last[g_words] == 48
    line_bad[line[~ok]] = True
    kind = np.where(empty, EMPTY, np.where(line_bad, GENERAL, PLAIN)).astype(np.int8)
    tok = np.full((8, nlines), -1, np.int32)
    tok[rank, line] = np.arange(len(letter), dtype=np.int32)
    tail = np.maximum(ends - 1, 0)
    semi = (buf[tail] == 59) | ((buf[tail] == 13) & (buf[np.maximum(ends - 2, 0)] == 59) & (ends - starts >= 2))
    return Chunk(buf, starts, ends, kind, tok, letter, nchars, signed, npoints > 0, zero,
                 (last.astype(np.int16) - 48).astype(np.int8), semi & ~empty)


def _all_zero(buf: npt.NDArray[np.uint8], first: IntArray, length: IntArray) -> BoolArray:
    """Whether the ``length`` characters from ``first`` hold no digit 1-9 (a longer number than
    MAX_NUMBER_CHARS + 1 is refused anyway: it counts as not zero)."""
    width = MAX_NUMBER_CHARS + 1
    cells = buf[first[:, None] + np.arange(width)]
    inside = np.arange(width) < length[:, None]
    nonzero = inside & (cells >= 49) & (cells <= 57)
    out: BoolArray = ~nonzero.any(axis=1) & (length <= width)
    return out


class LineTooLong(ValueError):
    """A line longer than a scan chunk (MAX_CHUNK bytes): no plain block, and not for this scanner."""


def chunks(data: bytes, size: int = 1 << 20) -> list[tuple[int, int]]:
    """``(start, stop)`` of chunks of about ``size`` bytes that end at line ends (raises
    :class:`LineTooLong` for a line longer than MAX_CHUNK)."""
    size = min(size, MAX_CHUNK)
    out: list[tuple[int, int]] = []
    pos, n = 0, len(data)
    while pos < n:
        stop = n if n - pos <= size else data.rfind(b"\n", pos, pos + size) + 1
        if stop <= pos:  # a line longer than a chunk: up to its end
            nl = data.find(b"\n", pos + size)
            stop = n if nl < 0 else nl + 1
            if stop - pos > MAX_CHUNK:
                raise LineTooLong(f"a line of more than {MAX_CHUNK} bytes at byte {pos}")
        out.append((pos, stop))
        pos = stop
    return out


def values(ch: Chunk, words: IntArray) -> npt.NDArray[np.float64]:
    """The numbers of ``words`` (indices of words of plain lines), as ``float()`` reads them: Horner's
    rule over the digits (integers below 10**15 are exact doubles), then one correctly rounded
    division by a power of ten (exact up to 10**22)."""
    if len(words) == 0:
        return np.zeros(0)
    first = ch.letter[words] + 1
    signed = ch.signed[words]
    body = ch.nchars[words] - signed
    start = first + signed
    mantissa = np.zeros(len(words))
    frac = np.zeros(len(words), np.int64)
    seen_point = np.zeros(len(words), np.bool_)
    for j in range(int(body.max())):  # the padding keeps start + j in the buffer
        c = ch.buf[start + j]
        inside = j < body
        digit = inside & (c != 46)
        mantissa = np.where(digit, mantissa * 10.0 + (c - 48.0), mantissa)
        frac += digit & seen_point
        seen_point |= inside & (c == 46)
    v = mantissa / _POW10[frac]
    negative = signed & (ch.buf[first] == 45)
    out: npt.NDArray[np.float64] = np.where(negative, -v, v)
    return out
