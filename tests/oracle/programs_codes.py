"""Generated LinuxCNC programs for issue 24's missing codes: G38.x probing, @/^ polar words, the
$ spindle word, M61, M70-M73, (abort,...) and what an INI file sets (tests/oracle/programs.py
registers them in FEATURES).  Each has a share of the errors rs274 gives; the verdict comes
from rs274."""

from __future__ import annotations

import random

from tests.oracle.programs import TOOLS, Program, _end, _units, num


def _xyz(rng: random.Random, k: float, axes: str = "XYZ", span: float = 30.0) -> str:
    return " ".join(f"{a}{num(rng.uniform(-span, span) * k)}" for a in rng.sample(axes, rng.randint(1, len(axes))))


# ---- G38.2 - G38.5 ------------------------------------------------------------------------------
def probe(rng: random.Random) -> Program:
    u, k = _units(rng)
    out = [f"{u} G90 G17"]
    r = rng.random()
    if r < 0.08:
        pass  # no feed rate: "Cannot probe with zero feed rate"
    elif r < 0.13:
        out.append(f"F{num(100 * k)} G41.1 D{num(2 * k)}")  # comp on
    elif r < 0.18:
        out.append(f"F{num(100 * k)} S500 M3\nG95 F{num(0.1 * k)}")  # feed per rev
    elif r < 0.25:
        out.append(f"F{num(200 * k)}\nG93")  # inverse time: the last F of G94 is the probe feed
    else:
        out.append(f"F{num(rng.uniform(20, 500) * k)}")
    if rng.random() < 0.3:
        out.append(f"G10 L2 P1 {_xyz(rng, k)}")
    if rng.random() < 0.2:
        out.append(f"G92 {_xyz(rng, k)}")
    if rng.random() < 0.07:
        out.append("G38.2 X0 Y0 Z0")  # at the start (0, 0, 0 in G54 before offsets change it): too close
    for _ in range(rng.randint(1, 4)):
        code = rng.choice(["G38.2", "G38.3", "G38.4", "G38.5"])
        dist = rng.choice(["", "", "G91 ", "G90 "])
        axes = _xyz(rng, k, "XYZ" if rng.random() < 0.9 else "XYZA", 20.0)
        out.append(f"{dist}{code} {axes}")
        if rng.random() < 0.3:  # the same mode again, axis words only
            out.append(_xyz(rng, k, "XYZ", 5.0))
        out.append("G90 G94" if "G93" in out[1] else "G90")
        out.append(rng.choice([f"G1 X#5061 Y#5062 Z#5063 F{num(300 * k)}",
                               f"G0 X[#5061 + {num(rng.uniform(-5, 5) * k)}]",
                               f"G0 Z[#5063 + #5070 + {num(2 * k)}]", f"G1 Y{num(rng.uniform(-9, 9) * k)} F100"]))
    return Program(_end(out, rng))


# ---- @ and ^ ----------------------------------------------------------------------------------
def polar(rng: random.Random) -> Program:
    u, k = _units(rng)
    out = [f"{u} G90 G17 F{num(400 * k)}"]
    if rng.random() < 0.8:  # away from the origin (there, @ alone and G91 are errors)
        out.append(f"G0 X{num(rng.uniform(-20, 20) * k)} Y{num(rng.uniform(-20, 20) * k)}")
    for _ in range(rng.randint(1, 5)):
        words = [rng.choice(["G0", "G1", "", "G91 G1", "G90 G0"])]
        r = rng.random()
        if r < 0.4:
            words += [f"@{num(rng.uniform(0, 30) * k)}", f"^{num(rng.uniform(-360, 360))}"]
        elif r < 0.6:
            words.append(f"@{num(rng.uniform(-5, 30) * k)}")
        elif r < 0.8:
            words.append(f"^{num(rng.uniform(-180, 180))}")
        elif r < 0.87:
            words += [f"X{num(rng.uniform(-9, 9) * k)}", f"@{num(5 * k)}"]  # both: an error
        elif r < 0.92:
            out.append("G90")  # (G53 in G91 is an error of its own)
            words = ["G53 G0", f"@{num(5 * k)}", "^45"]  # G53: an error
        else:
            words += [f"^{num(rng.uniform(-90, 90))}", f"Z{num(rng.uniform(-5, 5) * k)}"]
        out.append(" ".join(w for w in words if w))
        if rng.random() < 0.3:
            out.append("G90")
    return Program(_end(out, rng))


# ---- $ ----------------------------------------------------------------------------------------
def spindle_word(rng: random.Random) -> Program:
    out = ["G21 G90 F300"]
    for _ in range(rng.randint(1, 4)):
        d = rng.choice(["$0", "$0", "$-1", "$0.5", "$-0.7"] if rng.random() < 0.88 else ["$1", "$-2", "$2"])
        users = [f"S{rng.randint(100, 3000)} {d} M3", f"M4 {d} S{rng.randint(100, 900)}", f"M5 {d}",
                 f"S{rng.randint(100, 900)} {d}", f"G0 X{rng.randint(-9, 9)}", f"G1 X{rng.randint(-9, 9)}"]
        unused = [f"{d}", f"G0 X{rng.randint(-9, 9)} {d}"]  # nothing in the block uses the $: an error
        out.append(rng.choice(users if rng.random() < 0.95 else unused))
    return Program(_end(out, rng))


# ---- M61 ----------------------------------------------------------------------------------------
def m61(rng: random.Random) -> Program:
    u, k = _units(rng)
    out = [f"{u} G90"]
    for _ in range(rng.randint(1, 4)):
        r = rng.random()
        if r < 0.55:
            out.append(f"M61 Q{rng.choice(['0', '1', '2', '3', '4', '1.4', '2.6'])}")
        elif r < 0.65:
            out.append(rng.choice(["M61", "M61 Q-1", "M61 Q7"]))  # errors
        elif r < 0.8:
            t = rng.randint(1, 4)
            out.append(f"T{t} M6")
        else:
            out.append(f"G43 H{rng.randint(1, 4)}")
        if rng.random() < 0.15:
            out.append("G43")  # without H: the tool M61 set (a deliberate difference, tests/oracle/allow.toml)
        out.append(f"G0 X{num(rng.uniform(-20, 20) * k)} Z{num(rng.uniform(-5, 5) * k)}")
    return Program(_end(out, rng), TOOLS)


# ---- M70 - M73 ----------------------------------------------------------------------------------
def _modal_change(rng: random.Random, k: float) -> str:
    return rng.choice([
        rng.choice(["G20", "G21"]), f"F{num(rng.uniform(10, 900) * k)}", f"S{rng.randint(100, 3000)} M3",
        rng.choice(["M4", "M5"]), rng.choice(["G17", "G18", "G19"]), rng.choice(["G54", "G55", "G56", "G59.1"]),
        rng.choice(["G61", "G61.1", "G64", f"G64 P{num(rng.uniform(0, 0.5) * k)}",
                    f"G64 P{num(rng.uniform(0, 0.5) * k)} Q{num(rng.uniform(0, 0.5) * k)}"]),
        rng.choice(["G90", "G91"]), rng.choice(["G90.1", "G91.1"]), rng.choice(["G98", "G99"]),
        rng.choice(["M7", "M8", "M9"]), rng.choice(["G7", "G8"]),  # coolant and G7/G8 are restored too
    ])


def _moves(rng: random.Random, k: float) -> list[str]:
    return [f"G1 X{num(rng.uniform(-9, 9) * k)} Y{num(rng.uniform(-9, 9) * k)} F{num(300 * k)}"
            for _ in range(rng.randint(0, 2))]


def modal_state(rng: random.Random) -> Program:
    u, k = _units(rng)
    out = [f"{u} G90 G17 F{num(300 * k)}", "G10 L2 P2 X1 Y2", "G10 L2 P3 Z-1", "G10 L2 P7 X-3"]
    if rng.random() < 0.4:  # M73 in a subroutine: restored at the return
        out += ["o100 sub", rng.choice(["M73", "M73", "M70"]),
                *[_modal_change(rng, k) for _ in range(rng.randint(1, 4))], *_moves(rng, k), "o100 endsub"]
        for _ in range(rng.randint(1, 2)):
            out += [*[_modal_change(rng, k) for _ in range(rng.randint(0, 2))], "o100 call", *_moves(rng, k)]
        if rng.random() < 0.2:
            out.append("M72")  # nothing saved at this level
    else:
        if rng.random() < 0.9:
            out.append(rng.choice(["M70", "M70", "M73"]))
        for _ in range(rng.randint(1, 5)):
            out.append(_modal_change(rng, k))
            out += _moves(rng, k)
        if rng.random() < 0.15:
            out.append("M71")  # then M72 is an error
        out.append("M72")
        out += _moves(rng, k)
        if rng.random() < 0.3:
            out += [_modal_change(rng, k), "M72"]
    out.append("G90")
    out += [f"G1 X{num(rng.uniform(-9, 9) * k)} Z{num(rng.uniform(-9, 9) * k)}"]
    return Program(_end(out, rng))


# ---- (abort, ...) -------------------------------------------------------------------------------
def abort(rng: random.Random) -> Program:
    out = ["G21 G90 F300", f"#1 = {num(rng.uniform(-9, 9))}", f"#<depth> = {num(rng.uniform(0, 9))}"]
    text = rng.choice(["stop here", "depth #1 too big", "#<depth> is the depth", "done"])
    where = rng.random()
    out.append(f"G1 X{num(rng.uniform(-9, 9))}")
    if where < 0.4:
        out.append(f"(abort, {text})")
    elif where < 0.7:
        out += [f"o100 if [#1 GT {num(rng.uniform(-9, 9))}]", f"(ABORT,{text})", "o100 endif"]
    else:
        out = [*out[:1], "o200 sub", "G1 Y#1", f"(abort, {text})", "o200 endsub", *out[1:], "o200 call [2]"]
    out.append(f"G1 Y{num(rng.uniform(-9, 9))}")
    return Program(_end(out, rng))


# ---- an INI file --------------------------------------------------------------------------------
def ini(rng: random.Random) -> Program:
    sections = {"MY": {"DEPTH": num(rng.uniform(-9, 9)), "COUNT": str(rng.randint(1, 4)), "NAME": "probe"},
                "AXIS_X": {"MAX_LIMIT": num(rng.uniform(10, 500))}}
    no_fanuc = rng.random() < 0.3
    text = ["[RS274NGC]", "SUBROUTINE_PATH = subs"] + (["DISABLE_FANUC_STYLE_SUB = 1"] if no_fanuc else [])
    for sec, entries in sections.items():
        text += [f"[{sec}]", *(f"{n} = {v}" for n, v in entries.items())]
    files = (("side.ngc", "o<side> sub\nG1 X[#1 * 2] Y#2 F300\no<side> endsub\nM2\n"),
             ("up.ngc", "o<up> sub\nG0 Z#<_ini[my]depth>\no<up> endsub\nM2\n"))
    out = ["G21 G90"]
    for i in range(rng.randint(1, 4)):
        valid = [f"o<side> call [{num(rng.uniform(-9, 9))}] [{num(rng.uniform(-9, 9))}]", "o<up> call",
                 f"G0 X#<_ini[MY]DEPTH> Y#<_ini[{rng.choice(['my', 'My', 'MY'])}]count>",
                 "G0 X[#<_ini[axis_x]max_limit> / 10]",
                 f"o{101 + i} repeat [#<_ini[my]count>]\nG91 G0 X1\nG90\no{101 + i} endrepeat"]
        wrong = ["G0 Y#<_ini[my]name>", "G0 Y#<_ini[my]missing>", f"#<_ini[my]depth> = {rng.randint(1, 5)}",
                 "o<missing> call"]  # not a number, not in the file, read-only, no such file
        out.append(rng.choice(valid if rng.random() < 0.88 else wrong))
    if no_fanuc and rng.random() < 0.5:
        out.append("M98 P100")
    return Program(_end(out, rng), ini="\n".join(text) + "\n", files=files)


FEATURES = {"probe": probe, "polar": polar, "spindle_word": spindle_word, "m61": m61, "modal_state": modal_state,
            "abort": abort, "ini": ini}
