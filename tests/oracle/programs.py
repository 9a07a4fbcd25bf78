"""Generated LinuxCNC programs, one generator per feature of the oracle suite.

Each generator takes a seeded :class:`random.Random` and returns a :class:`Program`: the text
and the tool table both interpreters read.  Programs are mostly valid (the geometry is built
so that arcs close and compensated contours have room), with a share of deliberate errors
where the feature has them; the verdict always comes from rs274, never from this file.
"""

from __future__ import annotations

import math
import random
import re
from collections.abc import Callable
from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class Program:
    text: str
    tool_table: str = ""
    ini: str = ""  # a LinuxCNC INI file both interpreters read (rs274 -i, cncc --ini)
    files: tuple[tuple[str, str], ...] = ()  # subroutine files in the folder "subs" beside the INI
    local_files: tuple[tuple[str, str], ...] = ()  # subroutine files beside the program: (name.ngc, text)


# In machine units, which are inches for the stand-alone rs274 (the harness scales them for cncc).
TOOLS = "T1 P1 Z0.5 D0.25 ;\nT2 P2 Z-0.125 D0.375 ;\nT3 P3 Z1 D0.125 ;\nT4 P4 Z0 D0 ;\n"


def num(x: float) -> str:
    """A G-code number with at most four decimals and no exponent."""
    s = f"{round(x, 4):.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _xy(rng: random.Random, span: float = 50.0) -> tuple[float, float]:
    return round(rng.uniform(-span, span), 3), round(rng.uniform(-span, span), 3)


def _units(rng: random.Random) -> tuple[str, float]:
    return ("G20", 0.04) if rng.random() < 0.3 else ("G21", 1.0)


def _end(lines: list[str], rng: random.Random) -> str:
    lines.append(rng.choice(["M2", "M30"]))
    return "\n".join(lines) + "\n"


# ---- straight moves ---------------------------------------------------------------------------
def lines(rng: random.Random) -> Program:
    u, k = _units(rng)
    out = [f"{u} G90 G17", f"F{num(rng.uniform(50, 2000) * k)}"]
    for i in range(rng.randint(3, 10)):
        words = [rng.choice(["G0", "G1"] if i == 0 else ["G0", "G1", "", ""])]
        if rng.random() < 0.2:
            words.append(rng.choice(["G90", "G91"]))
        for ax in rng.sample("XYZABC", rng.randint(1, 3)):
            words.append(f"{ax}{num(rng.uniform(-100, 100) * (k if ax in 'XYZ' else 1))}")
        out.append(" ".join(w for w in words if w))
    return Program(_end(out, rng))


# ---- arcs -------------------------------------------------------------------------------------
_PLANES = {"G17": ("X", "Y", "Z", "I", "J"), "G18": ("Z", "X", "Y", "K", "I"), "G19": ("Y", "Z", "X", "J", "K")}


def _arc_block(rng: random.Random, plane: str, pos: dict[str, float], k: float, *, turns: bool,
               absolute_centre: bool, incremental: bool) -> str:
    a, b, n, ca, cb = _PLANES[plane]
    r = rng.uniform(1, 30) * k
    ang0 = rng.uniform(0, 2 * math.pi)
    centre = (pos[a] - r * math.cos(ang0), pos[b] - r * math.sin(ang0))
    ang1 = ang0 + rng.uniform(-2 * math.pi, 2 * math.pi)
    ea, eb = round(centre[0] + r * math.cos(ang1), 4), round(centre[1] + r * math.sin(ang1), 4)
    words = [rng.choice(["G2", "G3"])]
    if incremental:
        words += [f"{a}{num(ea - pos[a])}", f"{b}{num(eb - pos[b])}"]
    else:
        words += [f"{a}{num(ea)}", f"{b}{num(eb)}"]
    if absolute_centre:
        words += [f"{ca}{num(centre[0])}", f"{cb}{num(centre[1])}"]
    else:
        words += [f"{ca}{num(centre[0] - pos[a])}", f"{cb}{num(centre[1] - pos[b])}"]
    if rng.random() < 0.3:
        dz = round(rng.uniform(-5, 5) * k, 3)
        words.append(f"{n}{num(dz if incremental else pos[n] + dz)}")
        pos[n] += dz
    if turns:
        words.append(f"P{rng.randint(1, 4)}")
    pos[a], pos[b] = ea, eb
    return " ".join(words)


def _arcs(rng: random.Random, *, turns: bool) -> Program:
    u, k = _units(rng)
    absolute_centre = rng.random() < 0.3
    out = [f"{u} G90 {'G90.1' if absolute_centre else 'G91.1'}", f"F{num(500 * k)}"]
    pos = {"X": 0.0, "Y": 0.0, "Z": 0.0}
    for _ in range(rng.randint(2, 6)):
        plane = rng.choice(list(_PLANES))
        incremental = rng.random() < 0.3
        out.append(f"{plane} {'G91' if incremental else 'G90'}")
        out.append(_arc_block(rng, plane, pos, k, turns=turns and rng.random() < 0.7,
                              absolute_centre=absolute_centre, incremental=incremental))
    out.append("G90")
    return Program(_end(out, rng))


def arcs_ijk(rng: random.Random) -> Program:
    return _arcs(rng, turns=False)


def helix_turns(rng: random.Random) -> Program:
    return _arcs(rng, turns=True)


def arcs_r(rng: random.Random) -> Program:
    u, k = _units(rng)
    out = [f"{u} G90 G17", f"F{num(300 * k)}"]
    x, y = 0.0, 0.0
    for _ in range(rng.randint(2, 6)):
        ex, ey = _xy(rng, 40 * k)
        chord = math.hypot(ex - x, ey - y)
        if chord < 1e-3:
            continue
        r = chord / 2 * rng.choice([1.0, 1.0001, rng.uniform(1.0, 3.0), rng.uniform(1.0, 3.0)])
        if rng.random() < 0.15:  # just short of half the chord: inside or outside the tolerance
            r = chord / 2 - rng.choice([0.0005, 0.001, 0.002, 0.00004, 0.00006])
        if rng.random() < 0.5:
            r = -r
        out.append(f"{rng.choice(['G2', 'G3'])} X{num(ex)} Y{num(ey)} R{num(r)}")
        x, y = ex, ey
    return Program(_end(out, rng))


def arc_tolerance(rng: random.Random) -> Program:
    from tests.oracle.gen_arc_tolerance import arc_tolerance as generated

    return generated(rng)


# ---- offsets ----------------------------------------------------------------------------------
_SYSTEMS = ["G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"]


def _moves(rng: random.Random, k: float, n: int) -> list[str]:
    return [f"{rng.choice(['G0', 'G1 F300'])} X{num(rng.uniform(-50, 50) * k)} Y{num(rng.uniform(-50, 50) * k)}"
            f" Z{num(rng.uniform(-10, 10) * k)}" for _ in range(n)]


def work_offsets(rng: random.Random) -> Program:
    u, k = _units(rng)
    out = [f"{u} G90"]
    for _ in range(rng.randint(2, 5)):
        p = rng.randint(0, 9)
        lw = rng.choice(["L2", "L20"])
        axes = " ".join(f"{ax}{num(rng.uniform(-80, 80) * k)}" for ax in rng.sample("XYZA", rng.randint(1, 3)))
        out.append(f"G10 {lw} P{p} {axes}")
        out.append(rng.choice(_SYSTEMS))
        out += _moves(rng, k, rng.randint(1, 2))
    return Program(_end(out, rng))


def rotation(rng: random.Random) -> Program:
    from tests.oracle.gen_rotation import rotation as generated

    return generated(rng)


def g92_offsets(rng: random.Random) -> Program:
    u, k = _units(rng)
    out = [f"{u} G90", *_moves(rng, k, 1)]
    for _ in range(rng.randint(2, 6)):
        c = rng.choice(["G92", "G92", "G52", "G92.1", "G92.2", "G92.3"])
        if c in ("G92", "G52"):
            axes = " ".join(f"{ax}{num(rng.uniform(-40, 40) * k)}" for ax in rng.sample("XYZ", rng.randint(1, 3)))
            out.append(f"{c} {axes}")
        else:
            out.append(c)
        out += _moves(rng, k, rng.randint(0, 2))
    return Program(_end(out, rng))


def tool_length(rng: random.Random) -> Program:
    u, k = _units(rng)
    out = [f"{u} G90"]
    for _ in range(rng.randint(2, 5)):
        t = rng.randint(1, 4)
        choice = rng.random()
        if choice < 0.4:
            out.append(f"T{t} M6")
            out.append(rng.choice([f"G43 H{t}", "G43", f"G43 H{rng.randint(1, 4)}"]))
        elif choice < 0.6:
            out.append(f"G43.1 Z{num(rng.uniform(-20, 20) * k)}")
        elif choice < 0.8:
            out.append("G49")
        else:
            out.append(f"G43 H{t}")
        out += _moves(rng, k, rng.randint(1, 2))
    return Program(_end(out, rng), TOOLS)


# ---- canned cycles ----------------------------------------------------------------------------
def cycles(rng: random.Random) -> Program:
    u, k = _units(rng)
    plane = rng.choice(["G17", "G17", "G18", "G19"])
    out = [f"{u} G90 {plane}", f"F{num(200 * k)} S1000 M3", f"G0 X0 Y0 Z{num(20 * k)}"]
    a, b, n = {"G17": "XYZ", "G18": "ZXY", "G19": "YZX"}[plane]
    g = rng.choice(["G81", "G82", "G83", "G73", "G84", "G85", "G86", "G88", "G89"])
    incremental = rng.random() < 0.25
    words = [rng.choice(["G98", "G99"]), "G91" if incremental else "G90", g]
    if incremental:
        words += [f"{a}{num(rng.uniform(-10, 10) * k)}", f"{b}{num(rng.uniform(-10, 10) * k)}",
                  f"{n}{num(-rng.uniform(2, 10) * k)}", f"R{num(-rng.uniform(0, 5) * k)}"]
    else:
        words += [f"{a}{num(rng.uniform(-30, 30) * k)}", f"{b}{num(rng.uniform(-30, 30) * k)}",
                  f"{n}{num(-rng.uniform(1, 10) * k)}", f"R{num(rng.uniform(1, 5) * k)}"]
    if g in ("G82", "G86", "G88", "G89") or rng.random() < 0.2:
        words.append(f"P{num(rng.choice([0, 0.5, 1]))}")
    if g in ("G83", "G73"):
        words.append(f"Q{num(rng.uniform(0.5, 3) * k)}")
    if rng.random() < 0.3:
        words.append(f"L{rng.randint(1, 3)}")
    out.append(" ".join(words))
    for _ in range(rng.randint(0, 3)):
        out.append(f"{a}{num(rng.uniform(-30, 30) * k)} {b}{num(rng.uniform(-30, 30) * k)}")
    out.append(rng.choice(["G80", "G0 G90 Z20", "G80 G90"]))
    return Program(_end(out, rng), TOOLS)


# ---- cutter compensation ----------------------------------------------------------------------
def cutter_comp(rng: random.Random) -> Program:
    from tests.oracle.gen_comp import cutter_comp as generated

    return generated(rng)


# ---- O-words and expressions ------------------------------------------------------------------
def _expr(rng: random.Random, depth: int = 0) -> str:
    if depth > 2 or rng.random() < 0.4:
        return rng.choice([num(rng.uniform(-10, 10)), "#1", "#<v>", "#<_g>", str(rng.randint(1, 9))])
    op = rng.choice(["+", "-", "*", "/", "MOD", "**", "EQ", "LT", "GT", "AND", "OR"])
    if rng.random() < 0.2:
        f = rng.choice(["ABS", "SIN", "COS", "SQRT", "ROUND", "FIX", "FUP", "EXP", "ATAN"])
        if f == "ATAN":
            return f"ATAN[{_expr(rng, depth + 1)}]/[{_expr(rng, depth + 1)}]"
        if f == "SQRT":
            return f"SQRT[ABS[{_expr(rng, depth + 1)}]]"
        if f == "EXP":
            return f"EXP[[{_expr(rng, depth + 1)}] MOD 3]"
        return f"{f}[{_expr(rng, depth + 1)}]"
    rhs = _expr(rng, depth + 1)
    if op in ("/", "MOD"):
        rhs = f"[ABS[{rhs}] + 1]"
    if op == "**":
        return f"[ABS[{_expr(rng, depth + 1)}] ** {rng.randint(0, 3)}]"
    return f"[{_expr(rng, depth + 1)} {op} {rhs}]"


def owords(rng: random.Random) -> Program:
    out = ["G21 G90 F500", f"#1 = {num(rng.uniform(-5, 5))}", f"#<_g> = {num(rng.uniform(-5, 5))}",
           f"#<v> = {num(rng.uniform(-5, 5))}"]
    body: list[str] = []
    kind = rng.choice(["if", "while", "repeat", "call", "do", "expr"])
    if kind == "if":
        body += [f"o100 if [{_expr(rng)} GT {_expr(rng)}]", f"G1 X[{_expr(rng)}]"]
        if rng.random() < 0.5:
            body += [f"o100 elseif [{_expr(rng)} LT 0]", f"G1 Y[{_expr(rng)}]"]
        if rng.random() < 0.5:
            body += ["o100 else", f"G1 Z[{_expr(rng)}]"]
        body.append("o100 endif")
    elif kind == "while":
        n = rng.randint(0, 5)
        body += ["#<i> = 0", f"o101 while [#<i> LT {n}]", f"G1 X[#<i> * {_expr(rng)}]"]
        if rng.random() < 0.3:
            body += [f"o102 if [#<i> EQ {rng.randint(0, 4)}]", "o101 break", "o102 endif"]
        body += ["#<i> = [#<i> + 1]", "o101 endwhile"]
    elif kind == "do":
        body += ["#<i> = 0", "o103 do", f"G1 Y[#<i> + {_expr(rng)}]", "#<i> = [#<i> + 1]",
                 f"o103 while [#<i> LT {rng.randint(0, 4)}]"]
    elif kind == "repeat":
        body += [f"o104 repeat [{rng.randint(0, 4)}]", f"G91 G1 X{num(rng.uniform(-5, 5))}", "G90", "o104 endrepeat"]
    elif kind == "call":
        out[1:1] = ["o200 sub", "#<a> = [#1 * 2]", f"G1 X[#<a>] Y[#2 + {_expr(rng)}]", "o200 endsub"]
        body += [f"o200 call [{_expr(rng)}] [{_expr(rng)}]"]
        if rng.random() < 0.5:
            out[1:1] = ["o201 sub", "o201 return [#1 + 1]", "o201 endsub"]
            body += [f"o201 call [{_expr(rng)}]", "G1 Z[#<_value>]"]
    else:
        body += [f"G1 X[{_expr(rng)}] Y[{_expr(rng)}]", f"#2 = {_expr(rng)}", "G1 Z#2"]
    out += body
    return Program(_end(out, rng))


# ---- path modes and feeds ---------------------------------------------------------------------
def path_feed(rng: random.Random) -> Program:
    u, k = _units(rng)
    out = [f"{u} G90 G17"]
    for _ in range(rng.randint(2, 6)):
        c = rng.random()
        if c < 0.25:
            out.append(rng.choice(["G61", "G61.1", "G64", f"G64 P{num(rng.uniform(0, 1) * k)}",
                                   f"G64 P{num(rng.uniform(0, 1) * k)} Q{num(rng.uniform(0, 1) * k)}"]))
        elif c < 0.5:
            out.append(f"G93 G1 X{num(rng.uniform(-50, 50) * k)} Y{num(rng.uniform(-50, 50) * k)} "
                       f"F{num(rng.uniform(0.5, 20))}")
            out.append("G94 F" + num(rng.uniform(100, 900) * k))
        else:
            out.append(f"G1 X{num(rng.uniform(-50, 50) * k)} F{num(rng.uniform(10, 900) * k)}")
    return Program(_end(out, rng))


# ---- rs274ngc syntax (issue 24's syntax items) ---------------------------------------------------
def syntax(rng: random.Random) -> Program:
    a, b = rng.randint(-9, 9) or 1, rng.randint(-9, 9) or 2
    x = num(rng.uniform(-20, 20))
    pieces = [
        f"#1 = [{a} MOD {b}]\nG1 X#1",
        f"G1 X {rng.choice(['SQRT', 'ABS', 'ROUND', 'FIX'])}[{abs(a) * abs(b)}]",
        f"#<p> = {x}\nG1 Y EXISTS[#<p>] Z EXISTS[#<q>]",
        f"#<k> = {rng.randint(5, 30)}\n#{rng.randint(5, 30)} = {x}\nG1 X##<k>",
        f"#<s> = {a}\no110 if [#<s> GT 0]\nG1 X1\no110 else if [#<s> LT -3]\nG1 X2\no110 else\nG1 X3\no110 end if",
        f"o120 sub\nG1 X#1 Y#2\no120 end sub\no120 call [{a}] (between) [{b}]",
        f"{rng.choice(['G0 G80', 'G80 G0', 'G1 G80'])} X{x}",
        f"#2 = {a} {rng.choice(['*', '+', '/'])} {b}",
        "o130 sub\no131 sub\no131 endsub\no130 endsub",
        f"#3 = {rng.choice(['-', ''])}[{a} ** 2]\nG1 Z#3",
    ]
    out = ["G21 G90 F500"]
    out += rng.sample(pieces, rng.randint(1, 3))
    return Program(_end(out, rng))


# ---- parameters read back (issue 24: #5211, #5221, #54xx, #<_line> ...) ----------------------------
_OFFSET_PARAMS = [5210, 5211, 5212, 5213, 5214, 5220, *range(5221, 5231), 5241, 5242, 5243, 5250, 5261, 5262,
                  5281, 5301, 5321, 5341, 5361, 5381, 5390, 5161, 5162, 5163, 5181, 5182, 5183]
_POSITION_PARAMS = [*range(5420, 5429), 5400, 5403, 5410]
# (#<_abs_z> left out: after G43 and a G20/G21 change rs274 2.9 adds the tool length in the old units)
_NAMED_PARAMS = ["_line", "_motion_mode", "_plane", "_ccomp", "_metric", "_imperial", "_absolute", "_incremental",
                 "_inverse_time", "_units_per_minute", "_units_per_rev", "_coord_system", "_tool_offset",
                 "_retract_r_plane", "_retract_old_z", "_spindle_rpm_mode", "_spindle_css_mode",
                 "_ijk_absolute_mode", "_spindle_on", "_spindle_cw", "_mist", "_flood", "_feed", "_rpm", "_x", "_y",
                 "_z", "_a", "_b", "_c", "_u", "_abs_x", "_abs_y", "_abs_a", "_value",
                 "_value_returned", "_call_level", "_vmajor", "_vminor", "_task"]


def _debug_params(rng: random.Random, tool_loaded: bool) -> str:
    """A DEBUG line printing a few parameters.  The tool parameters only once a tool is loaded:
    before the first M6 the stand-alone rs274 2.9 reports whatever tool another rs274 process running at
    the same time has (its tool data is shared between processes)."""
    position = _POSITION_PARAMS if tool_loaded else _POSITION_PARAMS[:9]
    picks = [f"#{n}" for n in rng.sample(_OFFSET_PARAMS, 3)] + [f"#{n}" for n in rng.sample(position, 2)]
    picks += [f"#<{n}>" for n in rng.sample(_NAMED_PARAMS + (["_current_tool", "_selected_tool"] if tool_loaded
                                                             else []), 3)]
    rng.shuffle(picks)
    return "(DEBUG," + " ".join(f"{p[1:]}={p}" for p in picks) + ")"


def _parameter_step(rng: random.Random, k: float) -> list[str]:
    c = rng.random()
    if c < 0.2:
        axes = " ".join(f"{ax}{num(rng.uniform(-40, 40) * k)}" for ax in rng.sample("XYZA", rng.randint(1, 3)))
        lw = rng.choice(["L2", "L2", "L20"])
        rot = f" R{num(rng.uniform(-90, 90))}" if lw == "L2" and rng.random() < 0.2 else ""
        return [f"G10 {lw} P{rng.randint(0, 9)} {axes}{rot}"]
    if c < 0.4:
        g = rng.choice(["G92", "G92", "G52", "G92.1", "G92.2", "G92.3"])
        if g in ("G92", "G52"):
            g += " " + " ".join(f"{ax}{num(rng.uniform(-30, 30) * k)}" for ax in rng.sample("XYZ", rng.randint(1, 3)))
        return [g]
    if c < 0.5:
        return [rng.choice(["G28.1", "G30.1", *_SYSTEMS])]
    if c < 0.55:
        t = rng.randint(1, 4)
        return [f"T{t} M6", rng.choice(["G43", "G49"])]  # (G43.1 and M6: the tool_length feature)
    if c < 0.7:
        return [rng.choice(["G20", "G21", "G90", "G91", "G17", "G18", "G19", "G90.1", "G91.1", "G93 G1 X1 F2", "G94",
                            "G95", "M3 S200", "M4 S300", "M5", "M7", "M8", "M9", "G98", "G99", "G96 S100 D200",
                            "G97", "G80"])]
    if c < 0.75:
        n = rng.choice(_OFFSET_PARAMS)
        return [f"#{n} = {num(rng.uniform(-5, 5))}", f"(DEBUG,w{n}=#{n})"]
    return _moves(rng, k, 1)


def parameters(rng: random.Random) -> Program:
    u, k = _units(rng)
    out = [f"{u} G90 G17 F{num(300 * k)}"]
    for _ in range(rng.randint(2, 6)):
        out += _parameter_step(rng, k)
        if rng.random() < 0.7:
            out.append(_debug_params(rng, any(" M6" in ln for ln in out)))
    out.append("G90 G94 G17 F100")
    if rng.random() < 0.06:  # writing a read-only parameter is an error
        out.append(rng.choice(["#5420 = 1", "#5400 = 2", "#<_x> = 1", "#<_line> = 3", "#5602 = 1"]))
    out.append(_debug_params(rng, any(" M6" in ln for ln in out)))
    if any(ln.startswith(("G92 ", "G52 ")) for ln in out):  # G92 under an XY rotation: the rotation feature's
        out = [re.sub(r" R-?[\d.]+$", "", ln) if ln.startswith("G10 ") else ln for ln in out]
    return Program(_end(out, rng), TOOLS)


# ---- (DEBUG,...) / (MSG,...) text ---------------------------------------------------------------
_FORMAT_WORDS = ["%d", "%f", "%lf", "%.0f", "%.1f", "%.3f", "%.9f", "%.12f", "%.f", "%%", "%x", "%", "%.3d", "%s",
                 "%5.1f"]
_VALUES = [2.5, -2.5, 0.5, -0.4, 1.0e-7, 123456.789, 7, -3.25, 0.125, 1.0 / 3]


def messages(rng: random.Random) -> Program:
    out = ["G21"]
    for i in range(1, 4):
        out.append(f"#{i} = {num(rng.choice(_VALUES)) if rng.random() < 0.7 else num(rng.uniform(-99, 99))}")
    out.append(f"#<v> = {num(rng.choice(_VALUES))}")
    for _ in range(rng.randint(1, 4)):  # a "#" at the end of the text reads past it in rs274 2.9: not tested
        pieces = []
        for _ in range(rng.randint(1, 6)):
            pieces.append(rng.choice([*_FORMAT_WORDS, "#1", "#2", "#3", "#<v>", "#<nope>", "##1", "# x", "x=#1", "ab",
                                      "#<_line>", "#1#2", "%d#1"]))
        sep = rng.choice([" ", "  ", ""])
        lead = rng.choice(["", " ", "   "])
        tail = rng.choice(["", " ", "  "])
        kind = rng.choice(["DEBUG", "DEBUG", "debug", "MSG"])
        out.append(f"({kind},{lead}{sep.join(pieces)}{tail})")
        if rng.random() < 0.3:
            out.append(f"G0 X{num(rng.uniform(-9, 9))}")
    return Program(_end(out, rng))


# ---- Fanuc-style M98/M99 programs ------------------------------------------------------------------
def _m98_call(rng: random.Random, labels: list[int]) -> str:
    call = f"M98 P{rng.choice(labels)}"
    if rng.random() < 0.6:
        call += f" L{rng.choice(['1', '2', '3', '[#1]', '[#9 + 1]'])}"  # (L0: rs274 2.9 counts a call level)
    if rng.random() < 0.04:  # errors: M98 not first, a fraction, a stray Q
        call = rng.choice([f"G0 X1 {call}", call + ".5", call + " Q1"])
    return call


def m98_subs(rng: random.Random) -> Program:
    labels = rng.sample([100, 200, 300, 1234], rng.randint(1, 3))
    out = ["G21 G90 F500", f"#1 = {rng.randint(1, 3)}", "#9 = 1"]
    for _ in range(rng.randint(1, 4)):
        out.append(_m98_call(rng, labels))
        if rng.random() < 0.6:
            out.append("(DEBUG,main #1 #2 #3 #9 #<_call_level>)")
        if rng.random() < 0.3:
            out.append(f"G0 X{num(rng.uniform(-9, 9))}")
    out.append(rng.choice(["M30", "M2", "M99"]))
    for i, label in enumerate(labels):
        out.append(f"O{label}")
        out += [f"#2 = [#2 + {rng.randint(1, 3)}]", f"G91 G1 X{num(rng.uniform(-5, 5))} Y#1", "G90"]
        if rng.random() < 0.4:
            out.append(f"(DEBUG,in{label} #1 #2 #<_call_level>)")
        if i + 1 < len(labels) and rng.random() < 0.4:
            out.append(f"M98 P{labels[i + 1]}")  # nested, only downwards: no endless recursion
        if rng.random() < 0.3:
            out += [f"o{label + 1} if [#2 GT 4]", "M99", f"o{label + 1} endif"]
        out.append("#3 = [#3 + 1]")
        out.append("M99")
    return Program("\n".join(out) + "\n")


# ---- named subroutines in files (o<name> call finds name.ngc) ----------------------------------------
def file_subs(rng: random.Random) -> Program:
    names = rng.sample(["edge", "Hole", "pocket", "sq"], rng.randint(1, 3))
    files = []
    for name in names:
        body = [f"O<{name}> sub", "#<_count> = [#<_count> + 1]", f"G91 G1 X[#1 * {rng.randint(1, 3)}] Y#2 F100",
                "G90", f"(DEBUG,{name.lower()} #1 #2 #<_count> #<_call_level>)"]
        if rng.random() < 0.4:
            body.append(f"O<{name}> return [#1 + #2]")
        body.append(f"O<{name}> endsub")
        if rng.random() < 0.3:
            body = ["%", *body, "%"]
        elif rng.random() < 0.3:
            body.append("M2")
        files.append((f"{name.lower()}.ngc", "\n".join(body) + "\n"))
    out = ["G21 G90", "#<_count> = 0"]
    if rng.random() < 0.3:
        out.insert(0, rng.choice(["O<Main>", "O<main program>", "O100"]))
    for _ in range(rng.randint(1, 4)):
        name = rng.choice(names)
        out.append(f"o<{rng.choice([name, name.upper(), name.lower()])}> call [{rng.randint(-3, 3)}] "
                   f"[{num(rng.uniform(-2, 2))}]")
        if rng.random() < 0.5:
            out.append("(DEBUG,main #<_value> #<_value_returned> #<_count>)")
    if rng.random() < 0.05:
        out.append("o<missing> call")
    return Program(_end(out, rng), "", local_files=tuple(files))


# ---- lathe codes (G7/G8, G70-G72, G76) ----------------------------------------------------------
def lathe_modes(rng: random.Random) -> Program:
    """G7/G8 with X words in moves, arcs (I/K stay radii), G91, G92/G10 and read-back of #<_x>."""
    u, k = _units(rng)
    out = [f"{u} G18 G90 F{num(200 * k)}", f"G0 X{num(rng.uniform(0, 20) * k)} Z{num(rng.uniform(0, 5) * k)}"]
    diameter = False
    for _ in range(rng.randint(3, 8)):
        c = rng.random()
        mode = rng.choice(["G7 ", "G8 ", "", "", ""])
        if mode:
            diameter = mode == "G7 "
        scale = 2 if diameter else 1
        if c < 0.4:
            g = rng.choice(["G0", "G1"])
            out.append(f"{mode}{g} X{num(rng.uniform(-30, 30) * k)} Z{num(rng.uniform(-20, 5) * k)}")
        elif c < 0.55:
            out.append(f"{mode}G91 G1 X{num(rng.uniform(-5, 5) * k)}")
            out.append("G90")
        elif c < 0.7:  # a half circle in XZ: I/K are radii in both modes (now and then X is not doubled)
            r, xr, zr = rng.uniform(1, 5) * k, rng.uniform(2, 10) * k, rng.uniform(-5, 5) * k
            xw = xr * (scale if rng.random() < 0.9 else 1)
            out.append(f"{mode}G1 X{num(xw)} Z{num(zr)}")
            out.append(f"{rng.choice(['G2', 'G3'])} X{num(xw)} Z{num(zr - 2 * r)} I0 K{num(-r)}")
        elif c < 0.8:
            out.append(f"{mode}{rng.choice(['G92', 'G10 L2 P1', 'G10 L20 P1'])} X{num(rng.uniform(-10, 10) * k)}")
            if rng.random() < 0.5:
                out.append(rng.choice(["G92.1", "G10 L2 P1 X0 Z0"]))
        elif c < 0.9:
            out.append(f"{mode}G0 Z[#<_x>]")
        else:
            out.append(mode.strip() or "G7")
            diameter = diameter or not mode
    return Program(_end(out, rng))


def _profile(rng: random.Random, k: float, along_z: bool) -> tuple[list[str], tuple[float, float]]:
    """Profile moves for a G7x subroutine, monotonic along Z (G71) or X (G72) as a rule, and the start
    point outside it.  Now and then a move turns back (a 'Not monotonic' profile both must refuse)."""
    n = rng.randint(3, 6)  # two moves at least: one-move profiles are an open class (docs/dialects-notes.md)
    lead, side = 0.0, rng.uniform(2, 6)
    pts = []
    for _ in range(n):
        lead -= rng.uniform(1, 6)
        if rng.random() < 0.04:
            lead += rng.uniform(2, 8)  # turns back
        side = max(0.5, side + rng.uniform(-2, 4))
        pts.append((lead, side))
    lines = []
    g = ""
    for i, (a, b) in enumerate(pts):
        z, x = (a, b) if along_z else (b, a)
        arc_before = g in ("G2", "G3")
        g = rng.choice(["G1", "G1", "G1", "", "G2", "G3"]) if i else rng.choice(["G1", "G0"])
        if g == "" and arc_before:
            g = "G1"  # an arc without R would be an error: the modal arc needs its centre again
        words = [g] if g else []
        words += [f"X{num(x * k)}", f"Z{num(z * k)}"]
        if g in ("G2", "G3"):
            pz, px = (pts[i - 1] if along_z else pts[i - 1][::-1])
            chord = math.hypot(z - pz, x - px)
            words.append(f"R{num(chord / 2 * rng.uniform(1.2, 4) * k)}")
        if i and rng.random() < 0.15:
            words.append(f"{rng.choice('AC')}{num(rng.uniform(0.1, 0.6) * k)}")
        lines.append(" ".join(words))
    first_z, first_x = (pts[0] if along_z else pts[0][::-1])
    # the start point on the stock's side: past the highest point of the profile (it climbs as it goes)
    if along_z:
        start = (max(p[1] for p in pts) + rng.uniform(1, 4), first_z + rng.uniform(1, 3))
    else:
        start = (first_x + rng.uniform(1, 3), max(p[1] for p in pts) + rng.uniform(1, 4))
    return lines, start


def lathe_roughing(rng: random.Random) -> Program:
    """G70, G71/G71.1/G71.2, G72/G72.1/G72.2 on generated profiles (D, I, R, P, E, X/Z start words)."""
    u, k = _units(rng)
    cycle = rng.choice(["G71", "G71", "G71.1", "G71.2", "G72", "G72.1", "G72.2", "G70"])
    along_z = cycle.startswith("G71") or (cycle == "G70" and rng.random() < 0.6)
    lines, (sx, sz) = _profile(rng, k, along_z)
    if rng.random() < 0.3:  # mirrored: an inside profile, or one that runs towards +Z
        flip = rng.choice(["X", "Z"])
        lines = [" ".join(w if not w.startswith(flip) else flip + num(-float(w[1:])) for w in ln.split())
                 for ln in lines]
        sx, sz = (-sx, sz) if flip == "X" else (sx, -sz)
    out = [f"{u} G18 G90 F{num(150 * k)}", "o100 sub", *lines, "o100 endsub"]
    if rng.random() < 0.15:
        out.append("G7")
        out[2:2 + len(lines)] = [" ".join(w if not w.startswith("X") else "X" + num(float(w[1:]) * 2)
                                          for w in ln.split()) for ln in lines]
        sx *= 2
    out.append(f"G0 X{num(sx * k)} Z{num(sz * k)}")
    words = [cycle, "Q100"]
    if cycle == "G70":
        if rng.random() < 0.5:
            words += [f"D{num(rng.uniform(0, 1) * k)}", f"E{num(rng.uniform(0, 0.3) * k)}", f"P{rng.randint(1, 3)}"]
    else:
        words += [f"D{num(rng.uniform(0, 0.8) * k)}", f"I{num(rng.uniform(0.3, 2) * k)}"]
        if rng.random() < 0.4:
            words.append(f"R{num(rng.uniform(0.1, 1) * k)}")
        if rng.random() < 0.05:
            words[-1] = rng.choice(["I0", "I-1"])
    if rng.random() < 0.2:
        words.append(f"X{num((sx + 1) * k)}")
    out.append(" ".join(words))
    out.append(f"G0 X{num((abs(sx) + 5) * k)}")
    return Program(_end(out, rng))


def threading(rng: random.Random) -> Program:
    """G76 with pitch, depths, degression, compound angle, spring passes and tapers (and its errors)."""
    u, k = _units(rng)
    out = [f"{u} G18 G90", rng.choice(["S300 M3", "S300 M3", "S300 M4", "S300 M3", ""])]
    if rng.random() < 0.2:
        out.append("G7")
    x0, z0 = rng.uniform(2, 20) * k, rng.uniform(-2, 2) * k
    out.append(f"G0 X{num(x0)} Z{num(z0)}")
    j = rng.uniform(0.02, 0.3) * k
    kk = j * rng.uniform(1.5, 12)
    z1 = z0 + rng.choice([-1, -1, -1, 1]) * rng.uniform(5, 30) * k
    words = ["G76", f"P{num(rng.uniform(0.5, 3) * k)}", f"Z{num(z1)}",
             f"I{num(rng.choice([-1, -1, 1]) * rng.uniform(0.1, 2) * k)}", f"J{num(j)}", f"K{num(kk)}"]
    optional = (("R", num(rng.uniform(0.8, 2.5))), ("Q", num(rng.choice([0, 29, 29.5, 30, 45]))),
                ("H", str(rng.randint(0, 3))), ("E", num(rng.uniform(0, 2) * k)), ("L", str(rng.randint(0, 3))))
    for letter, value in optional:
        if rng.random() < 0.5:
            words.append(letter + value)
    if rng.random() < 0.08:  # a deliberate error: K not above J, J not positive, I zero, no P
        bad = rng.choice(["K", "J", "I", "P"])
        words = [w for w in words if not w.startswith(bad)]
        words.append({"K": f"K{num(j / 2)}", "J": "J0", "I": "I0", "P": ""}[bad])
    if rng.random() < 0.1:
        words.insert(0, "G7")
    out.append(" ".join(w for w in words if w))
    out.append(f"G0 X{num(x0 + 5 * k)}")
    return Program(_end(out, rng))


FEATURES: dict[str, Callable[[random.Random], Program]] = {
    "lines": lines, "arcs_ijk": arcs_ijk, "arcs_r": arcs_r, "helix_turns": helix_turns,
    "work_offsets": work_offsets, "rotation": rotation, "g92_g52": g92_offsets, "tool_length": tool_length,
    "cycles": cycles, "cutter_comp": cutter_comp, "owords": owords, "path_feed": path_feed, "syntax": syntax,
    "parameters": parameters, "messages": messages, "m98_subs": m98_subs,
    "file_subs": file_subs,
    "lathe_modes": lathe_modes, "threading": threading, "lathe_roughing": lathe_roughing,
}
FEATURES["arc_tolerance"] = arc_tolerance


def semantics(rng: random.Random) -> Program:
    from tests.oracle.gen_semantics import semantics as generated

    return generated(rng)


FEATURES["semantics"] = semantics


def comp_rules(rng: random.Random) -> Program:
    from tests.oracle.gen_comp_rules import comp_rules as generated

    return generated(rng)


FEATURES["comp_rules"] = comp_rules


def ini_keys(rng: random.Random) -> Program:
    from tests.oracle.gen_ini_keys import ini_keys as generated

    return generated(rng)


FEATURES["ini_keys"] = ini_keys


def generate(feature: str, count: int, seed: int = 0) -> list[Program]:
    """``count`` programs of ``feature``, the same ones for the same seed."""
    gen = FEATURES[feature]
    return [gen(random.Random(f"{feature}:{seed}:{i}")) for i in range(count)]


def _register_codes() -> None:
    from tests.oracle.programs_codes import FEATURES as CODES  # issue 24's missing codes

    FEATURES.update(CODES)


_register_codes()
