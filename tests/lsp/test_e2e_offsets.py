"""End to end (issue 20): with a machine configured and no work offsets, a program written
for a fixture offset gets one clear warning (W0775), not one soft-limit error per block."""

from __future__ import annotations

from pathlib import Path

import pytest
from pytest_lsp import LanguageClient

from tests.lsp.conftest import DATA
from tests.lsp.lsp_client import open_doc

pytestmark = pytest.mark.asyncio(loop_scope="module")

# small-mill.toml: Z soft limits -50..1 mm.  Under G54 with an offset of Z-100 these moves
# are fine; without the table every Z-5 is taken as the machine position -5 ... and Z5 as +5.
PROGRAM = "G90 G54 G00 X0 Y0 Z5.\n" + "".join(f"G01 X{i}. Z-5. F300.\nG00 Z5.\n" for i in range(1, 21)) + "M30\n"


async def machine_diags(client: LanguageClient, folder: str, toml: str) -> list[object]:
    root: Path = client.root  # type: ignore[attr-defined]
    (root / folder).mkdir(exist_ok=True)
    (root / folder / "cncc.toml").write_text(toml, encoding="utf-8")
    uri, v = await open_doc(client, f"{folder}/prog.nc", PROGRAM)
    return await client.published.wait(  # type: ignore[attr-defined,no-any-return]
        uri, v, until=lambda ds: any(d.code in ("E0703", "W0775") for d in ds))


async def test_no_offsets_table_gives_one_warning(client: LanguageClient) -> None:
    found = await machine_diags(client, "nooff", f'machine = "{DATA / "small-mill.toml"}"\n')
    codes = [d.code for d in found]  # type: ignore[attr-defined]
    assert codes.count("W0775") == 1 and "E0703" not in codes
    (w,) = [d for d in found if d.code == "W0775"]  # type: ignore[attr-defined]
    assert w.range.start.line == 0  # the first move that crosses: the rapid to Z5. (above Z 1)
    assert "21 move(s)" in w.message and "offsets" in w.message  # Z5. on line 0 and the 20 G00 Z5.


async def test_unreadable_offsets_file_gives_one_warning(client: LanguageClient) -> None:
    found = await machine_diags(client, "badoff", f'machine = "{DATA / "small-mill.toml"}"\n'
                                'offsets = "missing-offsets.toml"\n')
    codes = [d.code for d in found]  # type: ignore[attr-defined]
    assert codes.count("W0775") == 1 and "E0703" not in codes
    assert codes.count("E0903") <= 1  # the table itself is named once, not per block


async def test_with_the_offsets_the_program_is_within_the_limits(client: LanguageClient) -> None:
    root: Path = client.root  # type: ignore[attr-defined]
    (root / "withoff").mkdir(exist_ok=True)
    (root / "withoff" / "offsets.toml").write_text("[work.G54]\nX = 10.0\nY = 10.0\nZ = -10.0\n", encoding="utf-8")
    (root / "withoff" / "cncc.toml").write_text(
        f'machine = "{DATA / "small-mill.toml"}"\noffsets = "offsets.toml"\n', encoding="utf-8")
    uri, v = await open_doc(client, "withoff/prog.nc", PROGRAM)
    import asyncio

    for _ in range(100):  # wait for the second publication (the machine phase)
        if len(client.published.all(uri, v)) >= 2:  # type: ignore[attr-defined]
            break
        await asyncio.sleep(0.1)
    pubs = client.published.all(uri, v)  # type: ignore[attr-defined]
    assert len(pubs) >= 2
    codes = [d.code for d in pubs[-1]]
    assert "E0703" not in codes and "W0775" not in codes and "E0903" not in codes


async def test_many_crossings_without_offsets_and_without_g54_give_one_warning(client: LanguageClient) -> None:
    text = PROGRAM.replace("G54 ", "")  # G54 is in force at power-on: the same program
    root: Path = client.root  # type: ignore[attr-defined]
    (root / "nog54").mkdir(exist_ok=True)
    (root / "nog54" / "cncc.toml").write_text(f'machine = "{DATA / "small-mill.toml"}"\n', encoding="utf-8")
    uri, v = await open_doc(client, "nog54/prog.nc", text)
    found = await client.published.wait(  # type: ignore[attr-defined]
        uri, v, until=lambda ds: any(d.code in ("E0703", "W0775") for d in ds))
    codes = [d.code for d in found]
    assert codes.count("W0775") == 1 and "E0703" not in codes  # 21 crossings > MANY_CROSSINGS


async def test_machine_checks_of_the_changed_region_come_first(client: LanguageClient) -> None:
    import asyncio

    from lsprotocol import types as lsp

    from tests.lsp.lsp_client import edit, pos

    # small-mill.toml: X soft limits -1..100.  Line 1 crosses (X120.); an edit on line 300 makes
    # X150. there; the quick step publishes both before the full second phase ends.
    lines = ["G90 G00 X0 Y0 Z0", "G01 X120. F300.", "G01 X10. F300."]
    lines += [f"G01 X{10 + i % 50}. Y{i % 40}. F300." for i in range(600)]
    lines += ["M30", ""]
    text = "\n".join(lines)
    root: Path = client.root  # type: ignore[attr-defined]
    (root / "region").mkdir(exist_ok=True)
    (root / "region" / "cncc.toml").write_text(f'machine = "{DATA / "small-mill.toml"}"\n', encoding="utf-8")
    uri, v = await open_doc(client, "region/prog.nc", text)
    await client.published.wait(uri, v, until=lambda ds: any(d.code == "E0703" for d in ds))  # type: ignore[attr-defined]
    target = 300
    col = lines[target].index("X") + 1
    old = lines[target][col:lines[target].index(".")]
    v2 = await edit(client, uri, lsp.Range(start=pos(target, col), end=pos(target, col + len(old))), "150")
    for _ in range(300):
        pubs = client.published.all(uri, v2)  # type: ignore[attr-defined]
        if len(pubs) >= 3:
            break
        await asyncio.sleep(0.05)
    pubs = client.published.all(uri, v2)  # type: ignore[attr-defined]
    assert len(pubs) >= 3  # first phase, the changed region's machine checks, the full second phase
    quick = sorted(d.range.start.line for d in pubs[1] if d.code == "E0703")
    final = sorted(d.range.start.line for d in pubs[-1] if d.code == "E0703")
    assert quick == [1, target] and final == [1, target]
