"""Property tests of canned-cycle expansion, through the front end and the pass.

For any hole list, levels, cycle and G98/G99: each hole is reached at the level the
previous one returned to (the initial level first) and ends at the level the mode
requires; no feed goes past the bottom or above R; no rapid on the way down goes
deeper than R or than material already cut (G83's re-entry stays d above the last
peck).  The expected levels are computed here from the mode, not taken from the code.
"""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cncc.ir import Cycle, Linear, Rapid
from cncc.passes.expand_cycles import expand

EPS = 1e-6
CODES = ["G73", "G74", "G76", "G81", "G82", "G83", "G84", "G85", "G86", "G87", "G88", "G89"]

coord = st.integers(-200_000, 200_000).map(lambda v: v / 1000)
level = st.integers(-50_000, 50_000).map(lambda v: v / 1000)
depth = st.integers(500, 40_000).map(lambda v: v / 1000)


@st.composite
def cycle_programs(draw: st.DrawFn) -> tuple[str, dict[str, object], dict[str, object]]:
    code = draw(st.sampled_from(CODES))
    g98 = draw(st.booleans())
    z0 = draw(level)
    r = draw(level)
    d = draw(depth)
    bottom = round(r + d if code == "G87" else r - d, 3)
    if code == "G87" or (g98 and z0 <= bottom):  # else E0419: the return level would be inside the hole
        z0 = round(bottom + draw(st.integers(1, 20_000)) / 1000, 3)
    holes = draw(st.lists(st.tuples(coord, coord), min_size=1, max_size=5))
    q = draw(st.integers(100, 15_000)) / 1000
    higher = draw(st.booleans())
    spindle = "M04" if code == "G74" else "M03"
    x, y = holes[0]
    lines = [f"S500 {spindle};", f"G00 X0. Y0. Z{z0:.3f};",
             f"G{98 if g98 else 99} {code} X{x:.3f} Y{y:.3f} Z{bottom:.3f} R{r:.3f} Q{q:.3f} P0.5 F300.;"]
    lines += [f"X{hx:.3f} Y{hy:.3f};" for hx, hy in holes[1:]]
    lines.append("G80;")
    options = {"cycle_return_higher": higher, "cycle_g73_retract_mm": draw(st.sampled_from([0.0, 0.5, 2.0])),
               "cycle_g83_clearance_mm": draw(st.sampled_from([0.0, 0.5, 2.0]))}
    facts = {"code": code, "g98": g98, "z0": z0, "r": r, "bottom": bottom, "holes": holes, "higher": higher}
    return "\n".join(lines) + "\n", options, facts


def expected_return(f: dict[str, object]) -> float:
    z0, r = float(f["z0"]), float(f["r"])  # type: ignore[arg-type]
    if f["code"] == "G87":
        return z0
    if not f["g98"]:
        return r
    return r if f["higher"] and r > z0 else z0


def front_end_cycles(text: str, options: dict[str, object]) -> list[Cycle]:
    """The Cycle commands of ``text`` before the pass (one per drilling block here)."""
    from cncc.diagnostics import DiagnosticSink
    from cncc.driver import Options, front_end, resolve_dialect, resolve_machine
    from cncc.source import SourceMap

    opts = Options(dialect="syntec", dialect_options=options)
    sink = DiagnosticSink()
    dialect, machine = resolve_dialect(opts, sink), resolve_machine(opts.machine, sink)
    assert dialect is not None and machine is not None
    src = SourceMap().add("<t>", text)
    cmds = list(front_end(src, dialect, machine, opts, sink))
    assert not sink.has_errors, [d.message for d in sink]
    return [c for c in cmds if isinstance(c, Cycle)]


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(cycle_programs())
def test_levels_and_no_unsafe_moves(case: tuple[str, dict[str, object], dict[str, object]]) -> None:
    text, options, f = case
    cycles = front_end_cycles(text, options)
    holes = f["holes"]
    assert len(cycles) == len(holes)  # type: ignore[arg-type]
    z0, r, bottom = float(f["z0"]), float(f["r"]), float(f["bottom"])  # type: ignore[arg-type]
    ret = expected_return(f)
    back = f["code"] == "G87"
    low, high = (r, bottom) if back else (bottom, r)
    height = z0
    for c, (hx, hy) in zip(cycles, holes, strict=True):  # type: ignore[call-overload]
        assert abs(c.retract_mm - ret) < EPS
        moves = [m for m in expand(c) if isinstance(m, Rapid | Linear)]
        assert abs(c.start[2] - height) < EPS  # the hole starts at the level the last one returned to
        if moves:
            assert abs(moves[0].start[2] - height) < EPS
            end = moves[-1].end
            assert abs(end[2] - ret) < EPS and abs(end[0] - hx) < EPS and abs(end[1] - hy) < EPS
        deepest = r
        for m in moves:
            if isinstance(m, Linear):
                assert low - EPS <= m.end[2] <= high + EPS  # never feeds past the bottom or above R
                deepest = min(deepest, m.end[2])
            elif back:
                assert m.end[2] >= r - EPS  # a back bore never goes below R
            elif m.end[2] < m.start[2]:
                assert m.end[2] >= min(r, deepest) - EPS  # no rapid into uncut material
        height = ret


def test_return_level_inside_the_hole_is_an_error() -> None:
    from cncc.api import compile_text

    r = compile_text("G00 X0 Y0 Z-12.;\nG98 G81 X5. Z-10. R2. F100.;\nG80;\n",
                     dialect_options={"cycle_return_higher": False})
    assert "E0419" in [d.code for d in r.sink]
    assert "STRAIGHT_FEED" not in r.output
