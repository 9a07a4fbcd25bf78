"""Unit tests of the server's pure parts: positions, guard, config, scanner, outline."""

from __future__ import annotations

import time
from pathlib import Path

from cncc.dialects import load_dialect
from cncc.lsp.analysis import Request, analyze, new_analysis
from cncc.lsp.config import Settings, find_config, guess_dialect, read_config
from cncc.lsp.guard import Gate, Job
from cncc.lsp.navigate import outline, program_key
from cncc.lsp.positions import LineIndex
from cncc.lsp.variables import hover_variable

SYNTEC = load_dialect("syntec")


def test_positions_round_trip_in_every_encoding() -> None:
    text = "G1 (é😀) X1\nY2\r\nZ3"
    at = text.index("X1")
    expected = {"utf-16": len("G1 (é".encode("utf-16-le")) // 2 + 4, "utf-32": at, "utf-8": len(
        "G1 (é😀) ".encode())}
    for enc, col in expected.items():
        index = LineIndex(text, enc)
        assert index.position(at) == (0, col)
        assert index.offset(0, col) == at
    index = LineIndex(text)
    assert index.line_text(1) == "Y2"  # the \r is not part of the line
    assert index.position(len(text)) == (2, 2)


def test_guard_stops_a_loop_that_never_checks() -> None:
    def endless(check: object) -> None:
        n = 0
        while True:
            n += 1

    job = Job(endless, 0.05).start()
    assert job.future.result(timeout=10) == "budget"


def test_guard_cancel_and_normal_end() -> None:
    seen: list[int] = []

    def cooperative(check: object) -> None:
        while True:
            seen.append(1)
            check()  # type: ignore[operator]
            time.sleep(0.001)

    job = Job(cooperative, 30.0).start()
    time.sleep(0.02)
    job.cancel()
    assert job.future.result(timeout=10) == "cancelled"
    assert Job(lambda check: None, 1.0).start().future.result(timeout=10) is None


def test_background_job_waits_for_the_foreground() -> None:
    gate = Gate()
    events: list[str] = []

    def foreground(check: object) -> None:
        for _ in range(30):
            events.append("F")
            check()  # type: ignore[operator]
            time.sleep(0.002)

    def background(check: object) -> None:
        for _ in range(5):
            check()  # type: ignore[operator]
            events.append("B")

    fg = Job(foreground, 30.0, gate=gate).start()  # holds the gate from start() on
    bg = Job(background, 30.0, gate=gate, background=True).start()
    assert fg.future.result(timeout=30) is None and bg.future.result(timeout=30) is None
    assert events == ["F"] * 30 + ["B"] * 5
    assert not gate.busy


def test_analysis_keeps_partial_results_when_stopped() -> None:
    """Stopped by the budget: the lines timed so far are kept.  The budget is scaled by what a
    tenth of the program costs on this machine right now (the suite runs under heavy load)."""
    import time

    line = "G91 G01 X1. F6000.\n"
    tenth = new_analysis(Request("file:///w.nc", "/w.nc", 1, line * 20_000, "syntec", Settings()))
    t0 = time.perf_counter()
    analyze(tenth, lambda: None)  # also does the imports: the budget below is all compiling
    tenth_s = time.perf_counter() - t0
    text = line * 200_000
    a = new_analysis(Request("file:///big.nc", "/big.nc", 1, text, "syntec", Settings()))
    job = Job(lambda check: analyze(a, check), max(0.5, 2 * tenth_s)).start()
    assert job.future.result(timeout=120) == "budget"
    assert 0 < len(a.line_time_s) < 200_000  # some lines were timed, not all
    first = a.line_time_s[0]
    assert abs(first - 1.0 / (6000.0 / 60.0)) < 1e-9  # 1 mm at 6000 mm/min


def test_analysis_keeps_partial_results_when_cancelled() -> None:
    import time

    text = "G91 G01 X1. F6000.\n" * 400_000
    a = new_analysis(Request("file:///big.nc", "/big.nc", 1, text, "syntec", Settings()))
    job = Job(lambda check: analyze(a, check), 600.0).start()
    while not a.line_time_s and not job.future.done():  # cancelled once it has made progress
        time.sleep(0.005)
    job.cancel()
    assert job.future.result(timeout=120) == "cancelled"
    assert 0 < len(a.line_time_s) < 400_000
    assert abs(a.line_time_s[0] - 1.0 / (6000.0 / 60.0)) < 1e-9


def test_config_file_is_found_upwards_and_merged(tmp_path: Path) -> None:
    (tmp_path / "cncc.toml").write_text('dialect = "syntec"\ntarget = "x.toml"\n[lsp]\ndebounce-ms = 5\n'
                                        '[options]\nrapid_type = "independent"\n', encoding="utf-8")
    sub = tmp_path / "a" / "b"
    sub.mkdir(parents=True)
    found = find_config(str(sub), str(tmp_path))
    assert found == str(tmp_path / "cncc.toml")
    data, error = read_config(found)
    assert error is None
    s = Settings().merged(data, root=str(tmp_path)).merged({"opt_level": 1})
    assert (s.dialect, s.debounce_ms, s.opt_level) == ("syntec", 5, 1)
    assert s.dialect_options == {"rapid_type": "independent"}
    assert s.path(s.target) == str(tmp_path / "x.toml")
    bad = tmp_path / "bad" / "cncc.toml"
    bad.parent.mkdir()
    bad.write_text("dialect = ", encoding="utf-8")
    assert read_config(str(bad))[1] is not None


def test_dialect_guess_order() -> None:
    assert guess_dialect("/p/a.nc", "(cncc: dialect=szgh)\nG1 X1\n", "syntec") == "szgh"  # modeline first
    assert guess_dialect("/p/a.nc", "G1 X1\n", "series8") == "series8"  # then the setting
    assert guess_dialect("/p/a.nc", "G1 X1\n", None) == "syntec"  # the default


def test_outline_keys_meet() -> None:
    assert program_key("0010") == program_key("O10") == "10"
    assert program_key("kg11") == "KG11"
    text = "O0001 (main)\nM98 H100 L2 ;\nGOTO 7\nN7 G00 X0\nM30\nN100\nM99 P7\n"
    out = outline(text, SYNTEC)
    assert [r.key for r in out.programs] == ["1"]
    assert sorted((r.what, r.key) for r in out.calls) == [("GOTO", "7"), ("M98 H", "100"), ("M99 P", "7")]
    assert sorted(r.key for r in out.labels) == ["100", "7"]


def test_traced_values_follow_jumps() -> None:
    text = "#1=1\nGOTO 10\n#1=99\nN10 G01 X#1 F100.\nM30\n"
    a = new_analysis(Request("file:///j.nc", "/j.nc", 1, text, "syntec", Settings()))
    analyze(a, lambda: None)
    used = text.index("X#1") + 1
    assert "= 1 when cncc ran this block" in hover_variable(text, a.index, SYNTEC, 1, used, a.trace)
    skipped = text.index("#1=99")
    assert "not reached" in hover_variable(text, a.index, SYNTEC, 1, skipped, a.trace)
    # without the run's record, the document-order reading takes the skipped assignment
    assert "= 99" in hover_variable(text, a.index, SYNTEC, 1, used, None)
