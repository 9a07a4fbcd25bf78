"""Per-line columns of a timing report made on demand, for reports of a million lines.

:class:`SourceLines` reads a line's text or ``N`` word from the source text when asked
(no list of a million strings); :class:`SparseRows` keeps an ``(L, K)`` table of mostly
zeros as its non-zero entries and gives dense rows for an index or a slice;
:class:`KeyView` is the ``(source id, line)`` of each report line over two arrays.
"""

from __future__ import annotations

import re
from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, Any, overload

from cncc.source import SourceMap

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

    I64 = npt.NDArray[np.int64]
    Ints = npt.NDArray[np.integer[Any]]

N_WORD = re.compile(r"\s*/?\s*([Nn]\s*\d+)")
"""The N word at the start of a block (as the report shows it: no spaces, upper case)."""


_MAY_START_N = tuple(map(ord, "Nn/ \t\v\f\r\x1c\x1d\x1e\x1f\x85\xa0"))
"""Characters a line with an N word can start with (``\\s`` of :data:`N_WORD`, ``/``, ``N``)."""


def n_word(raw: str) -> str:
    m = N_WORD.match(raw)
    return m.group(1).replace(" ", "").upper() if m else ""


class LineStarts:
    """The character offset where each line of each source starts, as int64 arrays (cached);
    the same offsets as :attr:`cncc.source.SourceFile.line_starts`, without a list of ints."""

    def __init__(self, sources: SourceMap) -> None:
        self.sources = sources
        self._starts: dict[int, I64] = {}
        self._first: dict[int, Any] = {}

    def first_chars(self, sid: int) -> Any:
        """The first byte of each line of an ASCII source (a line's newline if it is empty); None
        for other texts."""
        import numpy as np

        if sid not in self._first:
            src, starts = self.sources.get(sid), self.of(sid)
            got = None
            if src is not None and starts is not None and src.text.isascii():
                raw = np.frombuffer((src.text + "\n").encode("ascii"), dtype=np.uint8)
                got = raw[starts]
            self._first[sid] = got
        return self._first[sid]

    def of(self, sid: int) -> I64 | None:
        """The line starts of source ``sid`` (None: no such source)."""
        import numpy as np

        got = self._starts.get(sid)
        if got is None:
            src = self.sources.get(sid)
            if src is None:
                return None
            if src.text.isascii():
                nl = np.flatnonzero(np.frombuffer(src.text.encode("ascii"), dtype=np.uint8) == 10)
                got = np.concatenate((np.zeros(1, dtype=np.int64), nl.astype(np.int64) + 1))
            else:
                got = np.asarray(src.line_starts, dtype=np.int64)
            self._starts[sid] = got
        return got


class SourceLines(Sequence[str]):
    """``what`` ("text": the stripped line, "n": its N word) of lines ``(sid[k], line[k])``.

    The same strings as ``text.split("\\n")[line - 1].rstrip("\\r")`` (``""`` outside the
    text or for an unknown source), made when indexed."""

    def __init__(self, starts: LineStarts, sid: Ints, line: Ints, what: str) -> None:
        self._starts, self._sid, self._line, self._what = starts, sid, line, what

    def __len__(self) -> int:
        return len(self._line)

    def _make(self, lo: int, hi: int) -> list[str]:
        import numpy as np

        sids, lines = self._sid[lo:hi], self._line[lo:hi]
        out = [""] * len(lines)
        for sid in np.unique(sids).tolist():
            starts = self._starts.of(sid)
            src = self._starts.sources.get(sid)
            if starts is None or src is None:
                continue
            mine = np.flatnonzero(sids == sid)
            ln = lines[mine]
            last = len(starts) - 1
            begin = starts[np.clip(ln - 1, 0, last)]
            end = np.where(ln < len(starts), starts[np.clip(ln, 0, last)] - 1, len(src.text))
            ok = (ln >= 1) & (ln <= len(starts))
            if self._what == "n":  # only a line that starts with N, "/" or a blank can have an N word
                first = self._starts.first_chars(sid)
                if first is not None:
                    ok &= np.isin(first[np.clip(ln - 1, 0, last)], _MAY_START_N)
            text = src.text
            if len(ln) and bool(ok.all()) and (len(ln) == 1 or bool((np.diff(ln) == 1).all())):
                region = text[int(begin[0]):int(end[-1])].split("\n")  # consecutive lines: one split
                if self._what == "n":
                    for k in np.flatnonzero(ok).tolist():
                        out[int(mine[k])] = n_word(region[k].rstrip("\r"))
                else:
                    for k, raw in zip(mine.tolist(), region, strict=True):
                        out[k] = raw.strip()
                continue
            for k, b, e in zip(mine[ok].tolist(), begin[ok].tolist(), end[ok].tolist(), strict=True):
                raw = text[b:e]
                out[k] = n_word(raw.rstrip("\r")) if self._what == "n" else raw.strip()
        return out

    @overload
    def __getitem__(self, k: int) -> str: ...

    @overload
    def __getitem__(self, k: slice) -> list[str]: ...

    def __getitem__(self, k: int | slice) -> str | list[str]:
        if isinstance(k, slice):
            lo, hi, step = k.indices(len(self))
            return self._make(lo, hi)[::step] if hi > lo else []
        if k < 0:
            k += len(self)
        if not 0 <= k < len(self):
            raise IndexError(k)
        return self._make(k, k + 1)[0]

    def __iter__(self) -> Iterator[str]:
        chunk = 4096
        for lo in range(0, len(self), chunk):
            yield from self._make(lo, min(lo + chunk, len(self)))


class KeyView(Sequence[tuple[int, int]]):
    """``(source id, line)`` of each report line, over two arrays."""

    def __init__(self, sid: Ints, line: Ints) -> None:
        self._sid, self._line = sid, line

    def __len__(self) -> int:
        return len(self._line)

    @overload
    def __getitem__(self, k: int) -> tuple[int, int]: ...

    @overload
    def __getitem__(self, k: slice) -> list[tuple[int, int]]: ...

    def __getitem__(self, k: int | slice) -> tuple[int, int] | list[tuple[int, int]]:
        if isinstance(k, slice):
            return list(zip(self._sid[k].tolist(), self._line[k].tolist(), strict=True))
        return int(self._sid[k]), int(self._line[k])


class SparseRows:
    """An ``(rows, width)`` int64 table given by its non-zero entries ``(row, col, value)``.

    Indexing with an int gives a dense ``(width,)`` row, with a slice a dense
    ``(n, width)`` block, as a numpy table would."""

    def __init__(self, rows: int, width: int, row: Ints, col: Ints, value: I64, ordered: bool = False) -> None:
        """``ordered``: the entries are already sorted by row, then col."""
        import numpy as np

        self.shape = (rows, width)
        if not ordered:
            order = np.lexsort((col, row))
            row, col, value = row[order], col[order], value[order]
        self._row, self._col, self._value = row, col, value
        self._first = np.searchsorted(self._row, np.arange(rows + 1, dtype=self._row.dtype))

    def __len__(self) -> int:
        return self.shape[0]

    def _block(self, lo: int, hi: int) -> I64:
        import numpy as np

        out = np.zeros((max(hi - lo, 0), self.shape[1]), dtype=np.int64)
        if hi > lo:
            a, b = int(self._first[lo]), int(self._first[hi])
            out[self._row[a:b] - lo, self._col[a:b]] = self._value[a:b]
        return out

    def __getitem__(self, k: int | slice) -> I64:
        if isinstance(k, slice):
            lo, hi, step = k.indices(self.shape[0])
            block: I64 = self._block(lo, hi)[::step]
            return block
        if k < 0:
            k += self.shape[0]
        if not 0 <= k < self.shape[0]:
            raise IndexError(k)
        row: I64 = self._block(k, k + 1)[0]
        return row
