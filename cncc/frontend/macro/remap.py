"""SZGH User P500-P504: G74, G81, G82, G83 and G84 run a user cycle program.

The dialect options ``cycle_user_g74`` ... ``cycle_user_g84`` hold the parameter
values: 0 keeps the built-in cycle; 101-170 makes the code call ``ProgramG<n>``
(found like any user G code: the -I folders, then the dialect's cycle library) with
the block's words as G65 arguments.  The controller runs 101-150 once per block;
151-170 it keeps modal, which cncc does not model yet: such a code also calls its
program only from the blocks that name it (a warning says so).
"""

from __future__ import annotations

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import CodeDef, Dialect, code_tenths
from cncc.source import NO_SPAN

REMAP_OPTIONS = {"G74": "cycle_user_g74", "G81": "cycle_user_g81", "G82": "cycle_user_g82",
                 "G83": "cycle_user_g83", "G84": "cycle_user_g84"}
_PARAMETER = {"G74": 500, "G81": 501, "G82": 502, "G83": 503, "G84": 504}


def remaps_cycles(dialect: Dialect) -> bool:
    """Whether any of G74/G81-G84 runs a user program in this dialect."""
    return dialect.macro_flavour == "szgh" and any(dialect.option(k, 0) for k in REMAP_OPTIONS.values())


def remapped_codes(dialect: Dialect, sink: DiagnosticSink) -> dict[tuple[str, int], CodeDef]:
    """Code-table entries that turn the remapped cycle codes into user macro calls."""
    out: dict[tuple[str, int], CodeDef] = {}
    for code, key in REMAP_OPTIONS.items():
        raw = dialect.option(key, 0)
        try:
            n = int(raw or 0)
        except (TypeError, ValueError):
            n = -1
        if n == 0:
            continue
        if not 101 <= n <= 170 or n != raw:
            sink.emit(dg.BAD_OPTION, NO_SPAN, f"{key}={raw}: User P{_PARAMETER[code]} is 0 or a program "
                                              f"number 101 to 170")
            continue
        if n >= 151:
            sink.emit(dg.MACRO_NOT_SUPPORTED, NO_SPAN,
                      f"{key}={n}: ProgramG151-170 are modal on the controller; cncc calls ProgramG{n} only "
                      f"from the blocks that name {code}")
        tenths = code_tenths(code[1:])
        out[("G", tenths)] = CodeDef("G", tenths, code, "user_macro", "non_modal",
                                     f"{code} runs ProgramG{n} (User P{_PARAMETER[code]})", {}, n)
    return out


__all__ = ["REMAP_OPTIONS", "remapped_codes", "remaps_cycles"]
