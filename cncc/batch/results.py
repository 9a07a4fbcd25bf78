"""Results files: rows written as they arrive, read back to resume.

CSV and JSON Lines are appended one whole line per row with a single ``write`` on an
``O_APPEND`` descriptor, so a killed batch leaves only complete rows (a torn last
line, which only a crash of the machine can leave, is cut off on the next run).
Parquet cannot be appended to: its rows go to a JSON Lines journal beside it
(``NAME.parquet.journal.jsonl``) and the Parquet file is rewritten from the
journal when the batch ends (needs ``pyarrow``).
"""

from __future__ import annotations

import csv
import io
import json
import os
from collections.abc import Iterable, Iterator
from typing import Any

from cncc.batch.row import COLUMNS, Row

FORMATS = ("csv", "jsonl", "parquet")
LIST_COLUMNS = ("codes", "tools")
INT_COLUMNS = ("opt_level", "errors", "warnings", "soft_limit_violations")


class ResultsError(Exception):
    """The results file cannot be used (the message says why)."""


def format_of(path: str) -> str:
    ext = os.path.splitext(path)[1].lower().lstrip(".")
    fmt = {"ndjson": "jsonl", "json": "jsonl"}.get(ext, ext)
    if fmt not in FORMATS:
        raise ResultsError(f"-o {path}: the results file must end in .csv, .jsonl or .parquet")
    if fmt == "parquet":
        try:
            import pyarrow  # noqa: F401
        except ImportError:
            raise ResultsError("parquet results need pyarrow (pip install pyarrow); "
                               "or write .csv or .jsonl") from None
    return fmt


# ---- encoding one row ------------------------------------------------------------------------
def csv_line(row: Row) -> str:
    buf = io.StringIO()
    cells = []
    for col in COLUMNS:
        v = row.get(col)
        if col == "codes":
            v = " ".join(f"{k}:{n}" for k, n in (v or {}).items())
        elif col == "tools":
            v = " ".join(str(t) for t in v or [])
        cells.append("" if v is None else v)
    csv.writer(buf, lineterminator="\n").writerow(cells)
    return buf.getvalue()


def csv_row(cells: dict[str, str]) -> Row:
    """A CSV record back to a row (numbers as numbers, codes and tools as a dict and a list)."""
    row: Row = {}
    for col in COLUMNS:
        v = cells.get(col, "")
        if col == "codes":
            row[col] = {k: int(n) for k, n in (item.split(":") for item in v.split())}
        elif col == "tools":
            row[col] = [int(t) for t in v.split()]
        elif v == "":
            row[col] = None if col not in ("reason",) else ""
        elif col in INT_COLUMNS:
            row[col] = int(v)
        elif col.endswith("_s") or col.endswith("_mm"):
            row[col] = float(v)
        else:
            row[col] = v
    return row


def json_line(row: Row) -> str:
    return json.dumps({c: row.get(c) for c in COLUMNS}, separators=(",", ":")) + "\n"


# ---- reading ---------------------------------------------------------------------------------
def _complete_text(path: str, header: str | None = None) -> str:
    """The file's text up to its last newline; a torn last line is cut off the file itself."""
    with open(path, "rb") as fh:
        data = fh.read()
    end = data.rfind(b"\n") + 1
    if end < len(data):
        with open(path, "r+b") as fh:
            fh.truncate(end)
    return data[:end].decode("utf-8")


def read_rows(path: str) -> list[Row]:
    """Every complete row already in ``path`` (none when it does not exist)."""
    fmt = format_of(path)
    if fmt == "parquet":
        rows = _read_parquet(path) if os.path.exists(path) else []
        journal = journal_path(path)
        return rows + (_read_jsonl(journal) if os.path.exists(journal) else [])
    if not os.path.exists(path) or os.path.getsize(path) == 0:
        return []
    return _read_csv(path) if fmt == "csv" else _read_jsonl(path)


def _read_csv(path: str) -> list[Row]:
    text = _complete_text(path)
    records = list(csv.reader(io.StringIO(text)))
    if not records:
        return []
    if tuple(records[0]) != COLUMNS:
        raise ResultsError(f"{path} has other columns than a cncc batch results file (an older cncc?); "
                           "name another file with -o")
    return [csv_row(dict(zip(COLUMNS, r, strict=False))) for r in records[1:] if r]


def _read_jsonl(path: str) -> list[Row]:
    rows = []
    for n, line in enumerate(_complete_text(path).splitlines(), 1):
        if not line.strip():
            continue
        try:
            row = json.loads(line)
        except json.JSONDecodeError:
            raise ResultsError(f"{path}:{n}: not a JSON row; name another file with -o") from None
        if not isinstance(row, dict) or "key" not in row:
            raise ResultsError(f"{path}:{n}: not a cncc batch row; name another file with -o")
        rows.append(row)
    return rows


def _read_parquet(path: str) -> list[Row]:
    import pyarrow.parquet as pq

    try:
        table = pq.read_table(path)
    except Exception as exc:  # pyarrow raises several types for a file that is not Parquet
        raise ResultsError(f"{path}: cannot read it as Parquet ({exc})") from None
    return [_from_parquet(r) for r in table.to_pylist()]


def journal_path(path: str) -> str:
    return path + ".journal.jsonl"


# ---- writing ---------------------------------------------------------------------------------
class ResultsWriter:
    """Append rows to a results file; ``close()`` finishes it (Parquet: rewritten from the journal)."""

    def __init__(self, path: str) -> None:
        self.path, self.fmt = path, format_of(path)
        target = journal_path(path) if self.fmt == "parquet" else path
        new = not os.path.exists(target) or os.path.getsize(target) == 0
        try:
            self.fd = os.open(target, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
        except OSError as exc:
            raise ResultsError(f"cannot write {target}: {exc.strerror or exc}") from None
        if new and self.fmt == "csv":
            self._write(",".join(COLUMNS) + "\n")

    def _write(self, text: str) -> None:
        data = text.encode("utf-8")
        while data:  # one write for a row on a local file; loop for the rare short write
            n = os.write(self.fd, data)
            data = data[n:]

    def write(self, row: Row) -> None:
        self._write(csv_line(row) if self.fmt == "csv" else json_line(row))

    def close(self, finish: bool = True) -> None:
        """Close the file; Parquet, with ``finish``: rewrite it from the journal (else the journal stays)."""
        if self.fd < 0:
            return
        os.close(self.fd)
        self.fd = -1
        if self.fmt == "parquet" and finish:
            write_parquet(self.path, read_rows(self.path))
            os.unlink(journal_path(self.path))


def _to_parquet(row: Row) -> dict[str, Any]:
    out = dict(row)
    out["codes"] = json.dumps(row.get("codes") or {}, sort_keys=True)
    return out


def _from_parquet(rec: dict[str, Any]) -> Row:
    rec = dict(rec)
    rec["codes"] = json.loads(rec.get("codes") or "{}")
    rec["tools"] = list(rec.get("tools") or [])
    return rec


def write_parquet(path: str, rows: Iterable[Row]) -> None:
    """All ``rows`` into ``path`` (atomically: a temporary file, then renamed)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from cncc.backends.timing.events import CATEGORIES

    floats = ["cycle_s", *(f"{c}_s" for c in CATEGORIES), "cpu_s",
              *(c for c in COLUMNS if c.endswith("_mm"))]
    types = {c: pa.float64() for c in floats}
    types.update({c: pa.int64() for c in INT_COLUMNS})
    types["tools"] = pa.list_(pa.int64())
    schema = pa.schema([(c, types.get(c, pa.string())) for c in COLUMNS])
    recs = [_to_parquet(r) for r in rows]
    table = pa.Table.from_pylist(recs, schema=schema)
    tmp = path + ".tmp"
    pq.write_table(table, tmp)
    os.replace(tmp, path)


def dedupe(rows: Iterable[Row]) -> Iterator[Row]:
    """The first row of each (path, key)."""
    seen: set[tuple[str, str]] = set()
    for r in rows:
        k = (r["path"], r["key"])
        if k not in seen:
            seen.add(k)
            yield r
