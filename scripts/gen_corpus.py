"""Generate the CAM-style programs of tests/corpus/ (thousands of lines each).

Each program is a roughing/finishing job of the kind CAM posts write: a header naming
the CAM system and the post, a tool block, a spiral pocket (many short line segments
at a fixed depth per pass), a finishing contour with arcs, a drilling cycle where the
dialect has one, and the end.  The geometry comes from :func:`pocket_points` and
:func:`contour`, which the corpus test uses as the independent expectation of the
motion (the program's end points, rounded to the digits written).

    python scripts/gen_corpus.py          # rewrite the generated files
    python scripts/gen_corpus.py --check  # exit 1 if a file is stale
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CORPUS = ROOT / "tests" / "corpus"
DIGITS = 3


def pocket_points(cx: float, cy: float, r_max: float, step: float, seg_deg: float) -> list[tuple[float, float]]:
    """An Archimedean spiral from the centre out to ``r_max``: ``step`` per turn, a point
    every ``seg_deg`` degrees (CAM posts write such spirals as short lines)."""
    out = []
    turns = r_max / step
    n = int(turns * 360 / seg_deg)
    for k in range(n + 1):
        a = math.radians(k * seg_deg)
        r = step * a / (2 * math.pi)
        out.append((round(cx + r * math.cos(a), DIGITS), round(cy + r * math.sin(a), DIGITS)))
    return out


def contour(w: float, h: float, r: float) -> list[tuple[str, float, float, float, float]]:
    """A w x h rounded rectangle from (r, 0) counter-clockwise: (kind, x, y, i, j) with I/J
    the arc centre from the start (kind "L" line, "A" counter-clockwise arc)."""
    return [
        ("L", w - r, 0.0, 0.0, 0.0), ("A", w, r, 0.0, r),
        ("L", w, h - r, 0.0, 0.0), ("A", w - r, h, -r, 0.0),
        ("L", r, h, 0.0, 0.0), ("A", 0.0, h - r, 0.0, -r),
        ("L", 0.0, r, 0.0, 0.0), ("A", r, 0.0, r, 0.0),
    ]


@dataclass(frozen=True)
class Job:
    path: str  # under tests/corpus
    dialect: str
    header: list[str]
    start: list[str]
    end: list[str]
    comment: Callable[[str], str]
    units: str = "mm"  # "mm" or "inch"
    eob: str = ""  # block end written after every block (";" for SYNTEC/SZGH styles)
    numbered: bool = False
    drill: bool = True
    passes: int = 6
    unsigned_centre: bool = False  # SERIES 8: I/J are unsigned distances (single-quadrant arcs)

    @property
    def scale(self) -> float:
        return 1.0 / 25.4 if self.units == "inch" else 1.0


def _fmt(v: float) -> str:
    text = f"{v:.{DIGITS}f}".rstrip("0")
    return text + "0" if text.endswith(".") else text


def program(job: Job) -> str:
    s = job.scale
    lines: list[str] = list(job.header) + list(job.start)
    depth_step = 0.5 * s
    pts = pocket_points(0.0, 0.0, 18.0 * s, 1.5 * s, 4.0)
    for p in range(1, job.passes + 1):
        z = -depth_step * p
        lines.append(job.comment(f"pocket pass {p}"))
        lines.append(f"G00 X{_fmt(pts[0][0])} Y{_fmt(pts[0][1])}")
        lines.append(f"G01 Z{_fmt(z)} F{_fmt(300 * s)}")
        lines.append(f"F{_fmt(1200 * s)}")
        lines += [f"X{_fmt(x)} Y{_fmt(y)}" for x, y in pts[1:]]
        lines.append(f"G00 Z{_fmt(5 * s)}")
    lines.append(job.comment("finish contour"))
    w, h, r = 60.0 * s, 40.0 * s, 5.0 * s
    lines.append(f"G00 X{_fmt(r - 20 * s)} Y{_fmt(-10 * s)}")
    lines.append(f"G01 Z{_fmt(-3 * s)} F{_fmt(300 * s)}")
    lines.append(f"G01 X{_fmt(r)} Y0. F{_fmt(800 * s)}")
    for kind, x, y, i, j in contour(w, h, r):
        if kind == "L":
            lines.append(f"G01 X{_fmt(x)} Y{_fmt(y)}")
        else:
            if job.unsigned_centre:
                i, j = abs(i), abs(j)
            lines.append(f"G03 X{_fmt(x)} Y{_fmt(y)} I{_fmt(i)} J{_fmt(j)}")
    lines.append(f"G00 Z{_fmt(5 * s)}")
    if job.drill:
        lines.append(job.comment("drill"))
        lines.append(f"G98 G81 X{_fmt(10 * s)} Y{_fmt(10 * s)} Z{_fmt(-6 * s)} R{_fmt(2 * s)} F{_fmt(150 * s)}")
        for x, y in ((50, 10), (50, 30), (10, 30)):
            lines.append(f"X{_fmt(x * s)} Y{_fmt(y * s)}")
        lines.append("G80")
    lines += job.end
    out = []
    n = 10
    for ln in lines:
        if job.numbered and ln and not ln.startswith(("(", "%", ";", "O", "/")):
            ln = f"N{n} {ln}"
            n += 10
        if job.eob and ln and not ln.startswith(("%", "(", ";", "//")):
            ln += job.eob
        out.append(ln)
    return "\n".join(out) + "\n"


def expected_feeds(job: Job) -> list[tuple[float, float, float]]:
    """The end point of every feed move (lines, arcs, drilling feeds) the program makes, in
    program units and in order: the independent expectation of the corpus test."""
    s = job.scale

    def r3(v: float) -> float:
        return round(v, DIGITS)

    out: list[tuple[float, float, float]] = []
    pts = pocket_points(0.0, 0.0, 18.0 * s, 1.5 * s, 4.0)
    for p in range(1, job.passes + 1):
        z = r3(-0.5 * s * p)
        out += [(x, y, z) for x, y in pts]
    w, h, r = 60.0 * s, 40.0 * s, 5.0 * s
    z = r3(-3 * s)
    out.append((r3(r - 20 * s), r3(-10 * s), z))
    out.append((r3(r), 0.0, z))
    out += [(r3(x), r3(y), z) for _, x, y, _, _ in contour(w, h, r)]
    if job.drill:
        out += [(r3(x * s), r3(y * s), r3(-6 * s)) for x, y in ((10, 10), (50, 10), (50, 30), (10, 30))]
    return out


def _paren(text: str) -> str:
    return f"({text.upper()})"


JOBS: tuple[Job, ...] = (
    Job("fanuc/cam_fusion_pocket.nc", "fanuc",
        ["%", "O1001 (POCKET PLATE)", "(T1 D=10. CR=0. - ZMIN=-3. - FLAT END MILL)",
         "(POST: FANUC GENERIC MILL)"],
        ["G90 G94 G17 G49 G40 G80", "G21", "G28 G91 Z0.", "G90", "T1 M06", "S6000 M03", "G54", "G00 X0. Y0.",
         "G43 Z15. H01", "M08", "G00 Z5."],
        ["M09", "G28 G91 Z0.", "G90", "M05", "M30", "%"], _paren, numbered=True),
    Job("haas/cam_fusion_vf2.nc", "haas",
        ["%", "O01002 (BRACKET)", "(MACHINE)", "(  VENDOR HAAS AUTOMATION)", "(  MODEL VF-2)",
         "(T1 D=0.375 CR=0. - ZMIN=-0.118 - FLAT END MILL)"],
        ["G90 G94 G17 G40 G49 G80", "G20", "G28 G91 Z0.", "G90", "T1 M06", "S8000 M03", "G154 P1",
         "G00 X0. Y0.", "G43 Z0.6 H01", "M08", "G187 P2 E0.001", "G00 Z0.2"],
        ["M09", "G187", "G28 G91 Z0.", "G90", "M05", "M30", "%"], _paren, units="inch"),
    Job("syntec/cam_syntec_pocket.nc", "syntec",
        ["%", "O2001", "// CAM output for a SYNTEC 900M (metric)"],
        ["G71 G90 G94 G17 G40 G49 G80", "T1 M06", "S5000 M03", "G54 G00 X0. Y0.", "G43 Z15. H01", "M08",
         "G00 Z5."],
        ["M09", "G91 G28 Z0.", "G90", "M05", "M30", "%"], lambda t: f"// {t}", eob=";"),
    Job("szgh/cam_szgh_pocket.nc", "szgh",
        ["; SZGH-990MDb job from CAM", "WAT+X12 ; wait for the clamp-closed input"],
        ["G90 G94 G17 G40 G49 G80", "G21", "M6 T1", "M3 S4000", "G54 G00 X0. Y0.", "G43 Z15. H1",
         "OUT+Y05 ; air blast on", "G00 Z5."],
        ["OUT-Y05", "G91 G28 Z0.", "G90", "M5", "M30"], lambda t: f"; {t}"),
    Job("series8/cam_s8_pocket.nc", "series8",
        ["; SERIES 8 job from CAM, inch"],
        ["G70", "G90", "G17", "G00XY ; to the part zero", "M03 S3000"],
        ["G00Z0.2 ; clear", "M05", "M30"], lambda t: f"; {t}", units="inch", drill=False,
        unsigned_centre=True),
    Job("linuxcnc/cambam_pocket.nc", "linuxcnc",
        ["( Made using CamBam - http://www.cambam.co.uk )", "( pocket plate 2024-05-11 )",
         "( T1 : 6.0 )"],
        ["G21 G90 G91.1 G64 G40", "G0 Z3.0", "T1 M6", "G17", "M3 S12000"],
        ["G0 Z5.", "M5", "M30"], lambda t: f"( {t} )"),
    Job("linuxcnc/freecad_linuxcnc.ngc", "linuxcnc",
        ["(Exported by FreeCAD)", "(Post Processor: linuxcnc_post)", "(Output Time:2024-03-02 10:11:12)",
         "(begin preamble)"],
        ["G17 G54 G40 G49 G80 G90", "G21", "(begin operation: Pocket)", "M6 T1", "M3 S10000"],
        ["(begin postamble)", "M05", "G17 G54 G90 G80 G40", "M2"], lambda t: f"({t})"),
    Job("grbl/freecad_grbl.nc", "grbl",
        ["(Exported by FreeCAD)", "(Post Processor: grbl_post)", "(Output Time:2024-03-02 10:11:12)",
         "(begin preamble)"],
        ["G17 G90", "G21", "(begin operation: Pocket)", "M3 S10000"],
        ["(begin postamble)", "M5", "G17 G90", "M2"], lambda t: f"({t})", drill=False),
    Job("grbl/carve_job.gcode", "grbl",
        ["; job for a grbl 1.1 router", "; units mm, origin front left"],
        ["G21 G90 G17", "M3 S18000"],
        ["M5", "G0 X0 Y0", "M2"], lambda t: f"; {t}", drill=False, passes=4),
)


def main(argv: list[str]) -> int:
    stale = []
    for job in JOBS:
        path = CORPUS / job.path
        text = program(job)
        if "--check" in argv:
            if not path.exists() or path.read_text(encoding="utf-8") != text:
                stale.append(job.path)
            continue
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    if stale:
        print("stale generated corpus files (run python scripts/gen_corpus.py):", *stale, sep="\n  ")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
