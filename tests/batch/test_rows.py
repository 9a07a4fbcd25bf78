"""cncc batch: the per-program row, the results files, the sandbox's limits, the command line."""

from __future__ import annotations

import json
import math
import os
import signal
import threading
import time
from pathlib import Path

import pytest

from cncc.batch import sandbox as sb
from cncc.batch.command import main as batch_main
from cncc.batch.options import RowOptions, Task
from cncc.batch.results import ResultsError, ResultsWriter, csv_line, read_rows
from cncc.batch.row import COLUMNS, program_row

ROOT = Path(__file__).resolve().parents[2]
OFFSETS = (ROOT / "examples" / "offsets.toml").read_text(encoding="utf-8")

# From X0 Y0 Z5: a feed of 10 mm, a clockwise half circle of radius 5 over the top
# (10,0) -> (15,5) -> (20,0), then a full counter-clockwise circle about (15,0).
SHAPE = "G90 G00 X0. Y0. Z5.\nT1 M06\nT2\nG01 X10. F600.\nG02 X20. Y0. I5. J0.\nG03 X20. Y0. I-5. J0.\nM30\n"


def row(text: str, machine: str = "generic-mill", dialect: str = "syntec", **opts: object) -> dict[str, object]:
    return program_row(Task("p.nc", text, machine, RowOptions(**opts), dialect))  # type: ignore[arg-type]


def test_nominal_times_tools_and_extents_of_a_known_shape() -> None:
    r = row(SHAPE, opt_level=0)
    assert r["status"] == "ok" and r["errors"] == 0 and r["codes"] == {}
    assert r["feed_s"] == pytest.approx(10 / 600 * 60)  # 10 mm at 600 mm/min
    assert r["arc_s"] == pytest.approx((math.pi * 5 + 2 * math.pi * 5) / 600 * 60, abs=1e-6)
    assert r["tools"] == [1, 2]
    ext = {k: r[k] for k in COLUMNS if k.endswith("_mm")}
    assert ext == {"x_min_mm": 0.0, "x_max_mm": 20.0, "y_min_mm": -5.0, "y_max_mm": 5.0,
                   "z_min_mm": 0.0, "z_max_mm": 5.0}  # the circles' bulges, not only their end points


def test_the_cycle_time_is_the_sum_of_its_categories() -> None:
    r = row(SHAPE, opt_level=1)
    parts = [r[c] for c in COLUMNS if c.endswith("_s") and c not in ("cycle_s", "cpu_s")]
    assert r["cycle_s"] == pytest.approx(sum(parts), abs=1e-8)  # type: ignore[arg-type]
    assert r["feed_s"] > 1.0  # type: ignore[operator]  # acceleration: slower than the nominal 1 s


def test_diagnostics_are_counted_by_code() -> None:
    r = row("G90 G01 X1..5 F100.\nG145 X1.\nG01 X2..5\nM30\n", opt_level=1)
    assert r["status"] == "error"
    assert r["codes"] == {"E0101": 2, "E0201": 1} and r["errors"] == 3
    assert str(r["reason"]).endswith("[E0101]")


def test_soft_limits_are_counted_with_offsets() -> None:
    # G54 puts X0 at machine X250; generic-mill's X ends at 600: X400 is 50 mm past it.
    prog = "G90 G54 G00 X0. Y0. Z5.\nG01 X400. F3000.\nX0.\nM30\n"
    assert row(prog, opt_level=1)["soft_limit_violations"] == 0  # no offsets: no machine positions
    r = row(prog, opt_level=1, offsets_text=OFFSETS)
    assert r["soft_limit_violations"] > 0 and r["status"] == "error"  # type: ignore[operator]
    assert set(r["codes"]) == {"E0615"}  # type: ignore[arg-type]


def test_lint_has_diagnostics_and_no_time() -> None:
    r = row(SHAPE.replace("M30", "G145\nM30"), emit="lint")
    assert r["cycle_s"] is None and r["codes"] == {"E0201": 1} and r["x_max_mm"] == 20.0


def test_a_program_that_cannot_be_read_gets_a_row() -> None:
    r = program_row(Task("gone.nc", "", "generic-mill", RowOptions(), read_error="cannot read gone.nc"))
    assert r["status"] == "error" and r["codes"] == {"E0901": 1}


def test_the_key_follows_content_machine_dialect_and_options() -> None:
    base = Task("a.nc", SHAPE, "generic-mill", RowOptions(opt_level=1), "syntec")
    same = RowOptions(opt_level=1, time_limit_s=300)  # an int limit, the default is 300.0
    assert Task("b/other.nc", SHAPE, "generic-mill", same, "syntec").key == base.key
    assert Task("a.nc", SHAPE + " ", "generic-mill", RowOptions(opt_level=1), "syntec").key != base.key
    assert Task("a.nc", SHAPE, "syntec-900m", RowOptions(opt_level=1), "syntec").key != base.key
    assert Task("a.nc", SHAPE, "generic-mill", RowOptions(opt_level=2), "syntec").key != base.key
    assert Task("a.nc", SHAPE, "generic-mill", RowOptions(opt_level=1), "fanuc").key != base.key


# ---- results files ------------------------------------------------------------------------------
@pytest.mark.parametrize("ext", ["csv", "jsonl", "parquet"])
def test_rows_round_trip_through_each_format(tmp_path: Path, ext: str) -> None:
    if ext == "parquet":
        pytest.importorskip("pyarrow")
    rows = [row(SHAPE, opt_level=0), row("G145\nM30\n", opt_level=0)]
    rows[1]["path"] = "q.nc"
    out = str(tmp_path / f"r.{ext}")
    w = ResultsWriter(out)
    for r in rows:
        w.write(r)
    w.close()
    assert read_rows(out) == rows


def test_a_torn_last_line_is_cut_off(tmp_path: Path) -> None:
    out = tmp_path / "r.csv"
    w = ResultsWriter(str(out))
    w.write(row(SHAPE, opt_level=0))
    w.close()
    whole = out.read_bytes()
    out.write_bytes(whole + csv_line(row("G145\n", opt_level=0)).encode()[:40])  # a write cut short
    assert len(read_rows(str(out))) == 1
    assert out.read_bytes() == whole


def test_a_foreign_results_file_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "r.csv").write_text("a,b\n1,2\n")
    with pytest.raises(ResultsError):
        read_rows(str(tmp_path / "r.csv"))
    (tmp_path / "p.nc").write_text(SHAPE)
    assert batch_main([str(tmp_path / "p.nc"), "-o", str(tmp_path / "r.csv")]) == 1
    assert "E0999" in capsys.readouterr().err


def test_command_line_problems_have_codes(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "p.nc").write_text(SHAPE)
    assert batch_main([str(tmp_path / "none*.nc"), "-o", str(tmp_path / "r.csv")]) == 1
    assert "E0995" in capsys.readouterr().err
    assert batch_main([str(tmp_path), "-o", str(tmp_path / "r.xlsx")]) == 1
    assert "E0999" in capsys.readouterr().err
    assert batch_main([str(tmp_path), "-m", "no-such-machine", "-o", str(tmp_path / "r.csv")]) == 1
    assert "E0904" in capsys.readouterr().err
    assert not (tmp_path / "r.csv").exists()


def test_parquet_without_pyarrow_says_so(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    import sys

    monkeypatch.setitem(sys.modules, "pyarrow", None)  # import pyarrow now raises ImportError
    (tmp_path / "p.nc").write_text(SHAPE)
    assert batch_main([str(tmp_path), "-o", str(tmp_path / "r.parquet")]) == 1
    err = capsys.readouterr().err
    assert "E0999" in err and "pyarrow" in err


def test_the_command_writes_one_row_per_program_and_machine(tmp_path: Path,
                                                             capsys: pytest.CaptureFixture[str]) -> None:
    lib = tmp_path / "lib"
    (lib / "sub").mkdir(parents=True)
    (lib / "a.nc").write_text(SHAPE)
    (lib / "sub" / "b.ngc").write_text("G21 G90\nG01 X5 F100\nM2\n")
    (lib / "notes.md").write_text("not a program\n")
    out = tmp_path / "r.jsonl"
    args = [str(lib), "-m", "generic-mill", "-m", "syntec-900m", "-O1", "-o", str(out)]
    assert batch_main(args) == 0
    rows = [json.loads(ln) for ln in out.read_text().splitlines()]
    assert sorted((Path(r["path"]).name, r["machine"]) for r in rows) == [
        ("a.nc", "generic-mill"), ("a.nc", "syntec-900m"), ("b.ngc", "generic-mill"), ("b.ngc", "syntec-900m")]
    assert {Path(r["path"]).name: r["dialect"] for r in rows} == {"a.nc": "syntec", "b.ngc": "linuxcnc"}
    assert "4 rows written" in capsys.readouterr().err
    assert batch_main(args) == 0  # a rerun: nothing new
    assert len(out.read_text().splitlines()) == 4
    err = capsys.readouterr().err
    assert "0 rows written" in err and "4 already in the results file" in err


# ---- the sandbox -------------------------------------------------------------------------------
def cam(n_lines: int) -> str:
    import sys

    sys.path.insert(0, str(ROOT / "bench"))
    from gen import cam_program

    return cam_program(n_lines)


def test_a_program_over_the_time_limit_gets_a_row_and_the_next_one_runs() -> None:
    box = sb.Sandbox()
    try:
        t = time.process_time()
        slow = box.run(Task("big.nc", cam(40_000), "generic-mill", RowOptions(opt_level=1, time_limit_s=0.5)))
        assert slow["status"] == "timeout" and slow["codes"] == {"E0996": 1}
        assert 0.4 < slow["cpu_s"] < 5  # type: ignore[operator]
        ok = box.run(Task("p.nc", SHAPE, "generic-mill", RowOptions(opt_level=0, time_limit_s=0.5)))
        assert ok["status"] == "ok" and ok["arc_s"] == pytest.approx(4.71238898, abs=1e-6)
        assert time.process_time() - t < 5  # the parent only waits
    finally:
        box.close()


def test_a_program_over_the_memory_limit_gets_a_row() -> None:
    box = sb.Sandbox()
    try:
        first = box.run(Task("p.nc", SHAPE, "generic-mill", RowOptions(opt_level=0, memory_limit_mb=100_000)))
        assert first["status"] == "ok"
        pid = box.pid
        assert pid is not None
        used_mb = int(Path(f"/proc/{pid}/status").read_text().split("VmSize:")[1].split()[0]) // 1024
        tight = RowOptions(opt_level=0, memory_limit_mb=used_mb + 40)  # 40 MB more than the warmed-up child
        r = box.run(Task("big.nc", cam(20_000), "generic-mill", tight))
        assert r["status"] in ("memory", "crash"), r  # MemoryError, or the child died trying
        assert set(r["codes"]) & {"E0997", "E0998"}  # type: ignore[arg-type]
        assert box.run(Task("p.nc", SHAPE, "generic-mill", RowOptions(opt_level=0)))["status"] == "ok"
    finally:
        box.close()


def test_a_child_killed_mid_program_gives_a_crash_row() -> None:
    box = sb.Sandbox()
    try:
        box.run(Task("p.nc", SHAPE, "generic-mill", RowOptions(opt_level=0)))
        pid = box.pid
        assert pid is not None
        big = Task("big.nc", cam(40_000), "generic-mill", RowOptions(opt_level=1, time_limit_s=60))  # > 2 s CPU
        threading.Timer(0.5, os.kill, (pid, signal.SIGKILL)).start()
        r = box.run(big)
        assert r["status"] == "crash" and r["codes"] == {"E0998": 1} and "SIGKILL" in str(r["reason"])
    finally:
        box.close()


def test_an_exception_in_the_compiler_gives_a_crash_row(monkeypatch: pytest.MonkeyPatch) -> None:
    def broken(task: Task) -> dict[str, object]:
        raise ZeroDivisionError("a bug")

    monkeypatch.setattr(sb, "program_row", broken)
    r, restart = sb.compute(Task("p.nc", SHAPE, "generic-mill"), set())
    assert restart and r["status"] == "crash" and "ZeroDivisionError: a bug" in str(r["reason"])


def test_offsets_per_machine(tmp_path: Path) -> None:
    # generic-mill with examples/offsets.toml: X400 is machine X650, past its X end at 600;
    # syntec-900m has no offsets here, so its soft limits are not checked.
    (tmp_path / "p.nc").write_text("G90 G54 G00 X0. Y0. Z5.\nG01 X400. F3000.\nX0.\nM30\n")
    out = tmp_path / "r.jsonl"
    args = [str(tmp_path / "p.nc"), "-m", "generic-mill", "-m", "syntec-900m", "-O1",
            "--offsets", f"generic-mill={ROOT / 'examples' / 'offsets.toml'}", "-o", str(out)]
    assert batch_main(args) == 0
    rows = {r["machine"]: r for r in map(json.loads, out.read_text().splitlines())}
    assert rows["generic-mill"]["soft_limit_violations"] > 0 and rows["syntec-900m"]["soft_limit_violations"] == 0
    assert batch_main([*args[:-2], "--offsets", "other=x.toml", "-o", str(out)]) == 1
