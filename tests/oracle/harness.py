"""Differential harness: one program through LinuxCNC 2.9's ``rs274 -g`` and cncc's canon trace.

:func:`rs274_path` finds the wrapper installed by ``scripts/ensure-rs274.sh`` (or ``$CNCC_RS274``).
:func:`compare` runs both on the same text and reports the first disagreement:

- traces: the calls in :data:`COMPARED` (motion, offsets, rotation, tool, feed, plane, units, spindle sync,
  dwell, coolant, operator messages), in order, numbers equal within :data:`TOLERANCE` (a message's text
  exactly: its numbers are how ``(DEBUG,...)`` prints parameters);
- errors: when rs274 stops with an error, cncc must fail too; when rs274's message is one of
  :data:`MESSAGES`, cncc must report that diagnostic code.  When rs274 stops, only the calls
  before its error are compared (it prints the trace up to the failing block).
"""

from __future__ import annotations

import os
import re
import resource
import shutil
import signal
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

TOLERANCE = 1e-4
CPU_LIMIT_S = 4  # rs274 runs a generated program in well under a CPU second; more is its endless G71 loop
WALL_TIMEOUT_S = 120.0  # and a wall-clock bound for a loaded machine
TIMED_OUT = "rs274 did not finish (timed out)"
WRAPPER_DEFAULT = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "cncc" / "rs274" / "bin" / "rs274"

COMPARED = frozenset({
    "STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED", "STRAIGHT_PROBE", "RIGID_TAP",
    "SET_G5X_OFFSET", "SET_G92_OFFSET", "SET_XY_ROTATION", "USE_TOOL_LENGTH_OFFSET",
    "CHANGE_TOOL", "CHANGE_TOOL_NUMBER", "SELECT_TOOL", "SET_FEED_RATE", "SELECT_PLANE", "USE_LENGTH_UNITS", "DWELL",
    "SET_FEED_MODE", "PROGRAM_END", "MESSAGE",
    "START_SPEED_FEED_SYNC", "STOP_SPEED_FEED_SYNCH", "DISABLE_FEED_OVERRIDE", "ENABLE_FEED_OVERRIDE",  # G33, G76
    "MIST_ON", "MIST_OFF", "FLOOD_ON", "FLOOD_OFF",  # coolant (M7-M9, the M2 resets, M72 restores)
})
TEXT_CALLS = frozenset({"MESSAGE"})  # compared as one string, blanks included

# rs274's error message (first line after "executing") -> the diagnostic code cncc reports.
MESSAGES: dict[str, str] = {
    "Parameter is readonly": "E0303",
    "Cannot assign to read-only parameter": "E0303",
    "Parameter number out of range": "E0302",
    "Found 'm98' code with no P-word": "E0316",
    "Negative l word used": "E0316",
    "Too many subroutine levels": "E0309",
    "Nested subroutine definition": "E0350",
    "Fanuc 'O....' subroutine must be called with 'M98'": "E0386",
    "'O.... sub' subroutine must be called with 'O.... call'": "E0386",
    "Fanuc 'O....' subroutine definition must end with 'M99'": "E0386",
    "'O.... endsub' or 'O.... return' must follow 'O.... sub' subroutine definition": "E0386",
    "Bug:  Reached convert_stop() from M99 as subprogram return": "E0386",
    "Cannot feed with zero spindle speed in feed per rev mode": "E0260",
    "Two m codes used from same modal group": "E0203",
    "Two g codes used from same modal group": "E0203",
    "I word missing in absolute center arc": "E0250",
    "J word missing in absolute center arc": "E0250",
    "K word missing in absolute center arc": "E0250",
    "Cannot use g53 with cutter radius comp": "E0572",
    "Cannot use g28 or g30 with cutter radius comp": "E0572",
    "Cannot change tools with cutter radius compensation on": "E0572",
    "Cannot change coordinate systems with cutter radius compensation on": "E0572",
    "Cannot read current position with cutter radius compensation on": "E0572",
}

_CALL = re.compile(r"^\s*(?:\d+\s+)?N\S*\s+([A-Z_0-9]+)\((.*)\)\s*$")


def _limit_cpu() -> None:
    resource.setrlimit(resource.RLIMIT_CPU, (CPU_LIMIT_S, CPU_LIMIT_S + 1))


def rs274_path() -> Path | None:
    """The rs274 wrapper, or None when the oracle is not installed."""
    env = os.environ.get("CNCC_RS274")
    for cand in ([Path(env)] if env else []) + [WRAPPER_DEFAULT]:
        if cand.is_file() and os.access(cand, os.X_OK):
            return cand
    found = shutil.which("rs274")
    return Path(found) if found else None


Call = tuple[str, tuple[str, ...]]


def parse_trace(text: str) -> list[Call]:
    """The compared calls of a ``-g`` canon trace (rs274's or cncc's)."""
    calls: list[Call] = []
    for line in text.splitlines():
        m = _CALL.match(line)
        if m is None or m.group(1) not in COMPARED:
            continue
        if m.group(1) in TEXT_CALLS:
            calls.append((m.group(1), (m.group(2),)))
            continue
        args = tuple(a.strip() for a in re.split(r"[,\s]+", m.group(2)) if a.strip())
        calls.append((m.group(1), args))
    return calls


@dataclass(slots=True)
class Run:
    ok: bool
    calls: list[Call]
    error: str = ""  # rs274: its message; cncc: the first error's code and message
    codes: tuple[str, ...] = ()


Files = tuple[tuple[str, str], ...]  # (name, text): subroutine files in the folder "subs" beside the INI


def _write_ini(tmp: str, ini: str, files: Files) -> list[str]:
    """The INI file and its subroutine files in ``tmp``; the ``-i`` arguments (none without an INI)."""
    for name, body in files:
        (Path(tmp) / "subs").mkdir(exist_ok=True)
        (Path(tmp) / "subs" / name).write_text(body)
    if not ini:
        return []
    (Path(tmp) / "prog.ini").write_text(ini)
    return ["-i", str(Path(tmp) / "prog.ini")]


def _write_files(folder: str, files: dict[str, str] | None) -> None:
    """Subroutine files beside the program (``name.ngc``), where both interpreters look for them."""
    for name, body in (files or {}).items():
        (Path(folder) / name).write_text(body)


def run_rs274(text: str, tool_table: str = "", *, exe: Path | None = None, ini: str = "", files: Files = (),
              local_files: dict[str, str] | None = None) -> Run:
    """``files``: subroutine files in the INI's ``subs`` folder; ``local_files``: beside the program."""
    exe = exe or rs274_path()
    assert exe is not None, "rs274 is not installed (scripts/ensure-rs274.sh)"
    with tempfile.TemporaryDirectory(prefix="cncc-oracle-") as tmp:
        _write_files(tmp, local_files)
        prog = Path(tmp) / "prog.ngc"
        prog.write_text(text)
        tbl = Path(tmp) / "tool.tbl"
        tbl.write_text(tool_table)
        ini_args = _write_ini(tmp, ini, files)
        # rs274 keeps the tool table in $HOME/.tool.mmap: runs at the same time (other tests, other
        # checkouts) read each other's tables ("Requested tool N not found"), so each run has its own HOME.
        env = {**os.environ, "HOME": tmp}
        for _ in range(8):  # rs274 now and then exits non-zero without a message: run it again
            try:
                p = subprocess.run([str(exe), *ini_args, "-t", str(tbl), "-g", str(prog)], capture_output=True,
                                   text=True, timeout=WALL_TIMEOUT_S, cwd=tmp, preexec_fn=_limit_cpu, env=env)
            except subprocess.TimeoutExpired as exc:  # no verdict from rs274
                out = exc.stdout.decode(errors="replace") if isinstance(exc.stdout, bytes) else (exc.stdout or "")
                return Run(False, parse_trace(out), TIMED_OUT)
            if p.returncode in (-signal.SIGXCPU, -signal.SIGKILL):  # an endless loop of rs274 (its G71 bug)
                return Run(False, parse_trace(p.stdout), TIMED_OUT)
            err_lines = [ln for ln in p.stderr.splitlines() if ln.strip() and ln.strip() != "executing"]
            if p.returncode == 0 or (err_lines and not _table_race(err_lines[0], tool_table)):
                break
    return Run(p.returncode == 0, parse_trace(p.stdout), err_lines[0] if err_lines else "")


def _table_race(error: str, tool_table: str) -> bool:
    """rs274 2.9 now and then reports "Requested tool 1 not found in the tool table" for a tool the
    table has (another rs274 run rewrote the shared $HOME/.tool.mmap; each run now has its own HOME,
    this stays as a safety net); run it again."""
    m = re.match(r"Requested tool (\d+) not found in the tool table", error)
    return m is not None and re.search(rf"^\s*T{m.group(1)}\b", tool_table, re.MULTILINE) is not None


def tool_table_mm(table: str) -> str:
    """A LinuxCNC tool table in inches (the stand-alone rs274's machine units) as millimetres,
    the unit cncc reads ``.tbl`` files in."""
    def scale(m: re.Match[str]) -> str:
        return f"{m.group(1)}{float(m.group(2)) * 25.4:.6f}"

    rows = (re.sub(r"\b([XYZUVWDIJQ])([-+]?[\d.]+)", scale, ln.split(";")[0]) for ln in table.splitlines())
    return "\n".join(rows) + "\n"


def run_cncc(text: str, tool_table: str = "", *, ini: str = "", files: Files = (),
             local_files: dict[str, str] | None = None) -> Run:
    from cncc.api import compile_text
    from cncc.diagnostics import Severity

    with tempfile.TemporaryDirectory(prefix="cncc-oracle-") as tmp:
        opts: dict[str, object] = {}
        if local_files:
            _write_files(tmp, local_files)
            opts["include_dirs"] = [tmp]
        tbl = Path(tmp) / "tool.tbl"  # rs274 always runs with a table (empty when none is given): so does cncc
        tbl.write_text(tool_table_mm(tool_table))
        opts["tools_file"] = str(tbl)
        if _write_ini(tmp, ini, files):  # SUBROUTINE_PATH is relative to the INI's folder for cncc, cwd for rs274
            opts["ini_file"] = str(Path(tmp) / "prog.ini")
        r = compile_text(text, dialect="linuxcnc", emit="canon", **opts)
    errors = [d for d in r.sink if d.severity is Severity.ERROR]
    first = f"{errors[0].code}: {errors[0].message}" if errors else ""
    return Run(r.ok, parse_trace(r.output), first, tuple(d.code for d in errors))


def _same_args(a: tuple[str, ...], b: tuple[str, ...]) -> bool:
    if len(a) != len(b):
        return False
    for x, y in zip(a, b, strict=True):
        if x == y:
            continue
        try:
            if abs(float(x) - float(y)) > TOLERANCE + 1e-9:  # one unit of the 4th decimal: both round
                return False
        except ValueError:
            return False
    return True


@dataclass(slots=True)
class Verdict:
    agree: bool
    reason: str = ""
    oracle: Run | None = None
    cncc: Run | None = None
    extra: dict[str, str] = field(default_factory=dict)


def _fmt(c: Call | None) -> str:
    return "(end)" if c is None else f"{c[0]}({', '.join(c[1])})"


def diff_calls(want: list[Call], got: list[Call], *, prefix: bool = False) -> str:
    """"" when equal (``prefix``: ``want`` may end before ``got``), else the first difference."""
    n = len(want) if prefix else max(len(want), len(got))
    for i in range(n):
        w = want[i] if i < len(want) else None
        g = got[i] if i < len(got) else None
        if w is None or g is None or w[0] != g[0] or not _same_args(w[1], g[1]):
            return f"call {i + 1}: rs274 {_fmt(w)} / cncc {_fmt(g)}"
    return ""


_RETAIN_G43 = re.compile(r"(?im)^\s*RETAIN_G43\s*=\s*0*[1-9]")


def same_offset_once(calls: list[Call]) -> list[Call]:
    """The calls without a USE_TOOL_LENGTH_OFFSET that repeats the offset in force.  With RETAIN_G43 the
    stand-alone rs274 2.9 re-reports the offset two to four times at every block; the offsets in force,
    and when they change, are what the two traces must share."""
    out: list[Call] = []
    last: Call | None = None
    for c in calls:
        if c[0] == "USE_TOOL_LENGTH_OFFSET":
            if last is not None and _same_args(c[1], last[1]):
                continue
            last = c
        out.append(c)
    return out


def compare(text: str, tool_table: str = "", local_files: dict[str, str] | None = None, *, ini: str = "",
            files: Files = ()) -> Verdict:
    want = run_rs274(text, tool_table, ini=ini, files=files, local_files=local_files)
    got = run_cncc(text, tool_table, ini=ini, files=files, local_files=local_files)
    if _RETAIN_G43.search(ini):
        want.calls, got.calls = same_offset_once(want.calls), same_offset_once(got.calls)
    if want.error == TIMED_OUT:  # no verdict from rs274: never an agreement (allow.toml may accept it)
        d = diff_calls(want.calls[:len(got.calls)], got.calls, prefix=True)  # rs274 may repeat moves for ever
        what = "ok" if got.ok else " ".join(got.codes)
        return Verdict(False, f"{TIMED_OUT}; cncc {what}" + (f"; before it {d}" if d else ""), want, got)
    if want.ok != got.ok:
        why = f"rs274 error {want.error!r}" if not want.ok else f"cncc error {got.error!r}"
        return Verdict(False, f"only one fails: {why}", want, got)
    if not want.ok:
        code = next((c for msg, c in MESSAGES.items() if want.error.startswith(msg)), None)
        if code is not None and code not in got.codes:
            return Verdict(False, f"rs274 {want.error!r} is {code}; cncc {got.error!r}", want, got)
        return Verdict(True, "", want, got)
    d = diff_calls(want.calls, got.calls)
    return Verdict(not d, d, want, got)
