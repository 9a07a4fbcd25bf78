"""End to end, second part: machine checks (the second phase), traced variable values,
the grbl target, the call chain of macro errors, dialect guesses, selection conversion."""

from __future__ import annotations

import asyncio
from pathlib import Path

import pytest
from lsprotocol import types as lsp
from pytest_lsp import LanguageClient

from cncc.dialects import load_dialect
from tests.lsp.conftest import DATA
from tests.lsp.lsp_client import actions_for, apply, diags, edit, edits_of, hover_text, open_doc, pos

pytestmark = pytest.mark.asyncio(loop_scope="module")


def codes_at(found: list[lsp.Diagnostic], code: str) -> list[tuple[int, str]]:
    return sorted((d.range.start.line, d.message) for d in found if d.code == code)


# ---- machine checks -------------------------------------------------------------------
MACHINE_PROGRAM = """G90 G00 X0 Y0 Z0
G01 X50. F300.
G01 X120. F300.
G01 X10. F1500.
G01 Y50. F2000.
M30
"""


async def test_machine_checks_come_in_a_second_publication(client: LanguageClient) -> None:
    root: Path = client.root  # type: ignore[attr-defined]
    (root / "mach").mkdir(exist_ok=True)
    (root / "mach" / "cncc.toml").write_text(f'machine = "{DATA / "small-mill.toml"}"\n', encoding="utf-8")
    uri, v = await open_doc(client, "mach/prog.nc", MACHINE_PROGRAM)
    found = await client.published.wait(  # type: ignore[attr-defined]
        uri, v, until=lambda ds: any(d.code == "E0703" for d in ds))
    # small-mill.toml: X soft limits -1..100 mm; X at 800 steps/mm and at most 10 kHz; Y at most 1000 mm/min
    soft = codes_at(found, "E0703")
    assert [line for line, _ in soft] == [2]  # only the move that ends beyond the limit
    assert "X reaches 120.000" in soft[0][1] and "soft limit 100.000" in soft[0][1]
    rate_hz = 1500.0 / 60.0 * 800.0  # F1500 along X
    step = codes_at(found, "E0701")
    assert [line for line, _ in step] == [3]
    assert f"{rate_hz / 1000:.1f} kHz" in step[0][1] and "10.0 kHz" in step[0][1]
    assert f"({10_000 / 800 * 60:.0f} mm/min)" in step[0][1]  # the feed the step rate allows
    fast = codes_at(found, "E0610")
    assert [line for line, _ in fast] == [4] and "2000 mm/min" in fast[0][1]
    first = client.published.all(uri, v)[0]  # type: ignore[attr-defined]
    assert not {"E0701", "E0703", "E0610"} & {str(d.code) for d in first}  # phase one came first, without them


async def test_an_edit_replaces_the_machine_diagnostics(client: LanguageClient) -> None:
    uri, v = await open_doc(client, "mach/prog2.nc", MACHINE_PROGRAM)
    await client.published.wait(uri, v, until=lambda ds: any(d.code == "E0703" for d in ds))  # type: ignore[attr-defined]
    v2 = await edit(client, uri, lsp.Range(start=pos(2, 5), end=pos(2, 8)), "90")  # X120. -> X90.
    for _ in range(600):  # both phases of the new version
        if len(client.published.all(uri, v2)) >= 2:  # type: ignore[attr-defined]
            break
        await asyncio.sleep(0.05)
    last = client.published.all(uri, v2)[-1]  # type: ignore[attr-defined]
    assert not codes_at(last, "E0703")
    assert [line for line, _ in codes_at(last, "E0701")] == [3]  # the step rate is still too high there


# ---- hover: the values the run saw -------------------------------------------------------
LOOP = """#1=0
#2=0
WHILE [#1 LT 5] DO1
#1=#1+1
#2=#2+#1
END1
G01 X#2 F100.
M30
"""


async def test_hover_shows_values_from_the_run(client: LanguageClient) -> None:
    uri, v = await open_doc(client, "values.nc", LOOP)
    await diags(client, uri, v)
    lines = LOOP.split("\n")
    after_loop = await hover_text(client, uri, 6, lines[6].index("#2") + 1)
    assert f"= {sum(range(1, 6)):g}" in after_loop  # 1 + 2 + 3 + 4 + 5, not the 0 assigned above
    inside = await hover_text(client, uri, 4, lines[4].rindex("#1") + 1)
    assert "= 5 on the last of 5 passes" in inside and "from 1 to 5" in inside


CALLED = """O0001
#100=2
M98 P10
G01 X#100 F100.
M30
O0010
#100=#100*3
M99
"""


async def test_hover_value_after_a_call(client: LanguageClient) -> None:
    uri, v = await open_doc(client, "called.nc", CALLED)
    await diags(client, uri, v)
    body = await hover_text(client, uri, 3, CALLED.split("\n")[3].index("#100") + 1)
    assert f"= {2 * 3:g}" in body  # the subprogram tripled it


# ---- target check with the real grbl dialect -------------------------------------------------
async def test_target_grbl_quotes_grbls_reasons(client: LanguageClient) -> None:
    root: Path = client.root  # type: ignore[attr-defined]
    (root / "tgrbl").mkdir(exist_ok=True)
    (root / "tgrbl" / "cncc.toml").write_text('target = "grbl"\n', encoding="utf-8")
    text = "G90 G00 X0 Y0\nG83 X1. Y1. Z-2. R1. Q0.5 F100.\n#1=3\nG01 X#1 F100.\nM30\n"
    uri, v = await open_doc(client, "tgrbl/drill.nc", text)
    found = [d for d in await diags(client, uri, v) if d.code == "W0890"]
    grbl = load_dialect("grbl")
    g83 = [d for d in found if d.range.start == pos(1, 0)]
    assert len(g83) == 1 and "grbl cannot run G83" in g83[0].message
    why = grbl.unsupported_reason("G", 830)
    assert why and why in g83[0].message
    variables = [d for d in found if d.range.start.line == 2]
    assert len(variables) == 1 and str(grbl.unsupported_reason("#")) in variables[0].message


# ---- macro errors carry their call chain ------------------------------------------------------
NESTED = """O0001
M98 P20
M30
O0020
M98 P30
M99
O0030
#3000=7 (TOO DEEP)
M99
"""


async def test_alarm_in_a_subprogram_has_the_call_chain(client: LanguageClient) -> None:
    uri, v = await open_doc(client, "chain.nc", NESTED)
    alarm = [d for d in await diags(client, uri, v) if d.code == "E0311"]
    assert len(alarm) == 1 and alarm[0].range.start.line == 7 and "TOO DEEP" in alarm[0].message
    related = alarm[0].related_information or []
    assert [(r.location.uri, r.location.range.start.line) for r in related] == [(uri, 4), (uri, 1)]  # innermost first


async def test_alarm_in_a_subprogram_file(client: LanguageClient) -> None:
    root: Path = client.root  # type: ignore[attr-defined]
    (root / "files").mkdir(exist_ok=True)
    other = root / "files" / "O0030.nc"
    other.write_text("O0030\n#3000=7 (TOO DEEP)\nM99\n", encoding="utf-8")
    uri, v = await open_doc(client, "files/main.nc", "O0001\nM98 P20\nM30\nO0020\nM98 P30\nM99\n")
    alarm = [d for d in await diags(client, uri, v) if d.code == "E0311"]
    assert len(alarm) == 1 and alarm[0].range.start.line == 4  # shown on the call that leads there
    related = alarm[0].related_information or []
    assert (related[0].location.uri, related[0].location.range.start.line) == (other.as_uri(), 1)
    assert [(r.location.uri, r.location.range.start.line) for r in related[1:]] == [(uri, 4), (uri, 1)]


# ---- dialect guesses -------------------------------------------------------------------------
async def test_dialect_guessed_from_extension_and_content(client: LanguageClient) -> None:
    async def dialect_of(name: str, text: str) -> str:
        uri, v = await open_doc(client, name, text)
        await diags(client, uri, v)
        body = await hover_text(client, uri, 0, 1)
        return body.rsplit("(", 1)[1].rstrip(").")  # "cncc operation: `op` (dialect)."

    assert await dialect_of("guess/a.ngc", "G01 X1. F100.\n") == "linuxcnc"
    assert await dialect_of("guess/b.gcode", "G01 X1. F100.\n") == "grbl"
    assert await dialect_of("guess/c.nc", "G01 X1. F100.\nWAT+ X1\n") == "szgh"
    assert await dialect_of("guess/d.nc", "G01 X1. F100.\n") == "syntec"


# ---- convert a selection -----------------------------------------------------------------------
async def test_convert_selection_keeps_the_document_modes(client: LanguageClient) -> None:
    text = "G90 G00 X0 Y0\nG91 G01 X10. Y5. F300.\nX1.\nM30\n"
    uri, v = await open_doc(client, "convsel.nc", text)
    await diags(client, uri, v)
    acts = await actions_for(client, uri, lsp.Range(start=pos(2, 0), end=pos(2, 3)), [])
    conv = [a for a in acts if a.title.startswith("Convert selection to grbl")]
    assert len(conv) == 1
    new = apply(text, edits_of(conv[0], uri))
    # under G91 the emitter's absolute X11. needs G90 first, and G91 again after it; no preamble
    assert new.split("\n")[2:5] == ["G90", "G01 X11. F300.", "G91"]
    assert "G17" not in new and "G21" not in new
