"""Dialect data read from the TOML: the front-end key, extensions and detection marks.

Every expected value below is written in the TOML text of the test (or read from the
built-in file with tomllib, independently of the loader), so a loader that drops or
changes a value fails.
"""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path

import pytest

from cncc.api import compile_commands
from cncc.dialects import DialectError, available, load_dialect, parse_dialect
from cncc.frontend.detect import detect
from cncc.frontend.plugins import FRONT_ENDS, front_end

USER = '''
name = "shopmill"
title = "A shop's own dialect"
grammar = "fanuc"
macro_flavour = "fanuc"
extensions = [".shp", ".nc"]
[detect]
extensions = { ".shp" = 5 }
[[detect.rule]]
points = 7
why = "the shop's header"
view = "comments"
needs = ["SHOPMILL"]
pattern = "\\\\bSHOPMILL\\\\b"
[[detect.rule]]
points = 3
why = "G700 macro calls"
pattern = "G700"
unless = "G7000"
'''


def _builtin_raw(name: str) -> dict[str, object]:
    return tomllib.loads(resources.files("cncc.dialects").joinpath(f"{name}.toml").read_text(encoding="utf-8"))


def test_detection_data_round_trips_from_the_toml() -> None:
    raw = tomllib.loads(USER)
    d = parse_dialect(raw)
    assert d.extensions == (".shp", ".nc")
    assert d.detection.extensions == {".shp": 5}
    got = [(r.points, r.why, r.view, r.pattern.pattern, r.needs) for r in d.detection.rules]
    assert got == [(7, "the shop's header", "comments", r"\bSHOPMILL\b", ("SHOPMILL",)),
                   (3, "G700 macro calls", "code", "G700", ())]
    assert d.detection.rules[1].unless is not None and d.detection.rules[1].unless.pattern == "G7000"


def test_a_user_dialects_marks_decide_the_guess() -> None:
    user = parse_dialect(tomllib.loads(USER))
    everyone = (*(load_dialect(n) for n in available()), user)
    found = detect("part.shp", "(SHOPMILL post)\nG700 P1\nM30\n", everyone)
    assert found.dialect == "shopmill"
    mine = {(e.why, e.points) for e in found.evidence if e.dialect == "shopmill"}
    assert {("file extension .shp", 5), ("the shop's header", 7), ("G700 macro calls", 3)} <= mine
    assert found.scores["shopmill"] >= 15 - 3  # at most the code-set penalty off (G700 is in no table)
    # G7000 is the rule's 'unless': the rule does not fire
    found = detect("part.nc", "G7000\n", everyone)
    assert ("G700 macro calls", 3) not in {(e.why, e.points) for e in found.evidence}


@pytest.mark.parametrize("name", available())
def test_builtin_detection_data_is_the_files(name: str) -> None:
    raw = _builtin_raw(name)
    d = load_dialect(name)
    table = raw.get("detect", {})
    assert isinstance(table, dict)
    assert d.detection.extensions == {str(k): int(v) for k, v in table.get("extensions", {}).items()}
    assert [r.why for r in d.detection.rules] == [str(r["why"]) for r in table.get("rule", [])]
    if "extensions" in raw:
        assert list(d.extensions) == raw["extensions"]
    # an extension that gives points is one the dialect claims
    assert set(d.detection.extensions) <= set(d.extensions)


def test_no_dialect_claims_an_extension_detection_gives_to_another() -> None:
    # .ngc is LinuxCNC's: detection gives it 4 points, and the Fanuc-family files no longer claim it
    assert load_dialect("linuxcnc").detection.extensions[".ngc"] > 0
    assert ".ngc" not in load_dialect("syntec").extensions
    assert ".ngc" not in load_dialect("fanuc").extensions
    points = {n: load_dialect(n).detection.extensions for n in available()}
    for n in available():
        for ext in load_dialect(n).extensions:
            owners = [o for o, exts in points.items() if exts.get(ext, 0) > 0]
            # either nobody gets points for it, or the dialect is grbl reading LinuxCNC's .ngc
            assert not owners or n in owners or (n, ext) == ("grbl", ".ngc"), (n, ext, owners)


def test_an_extension_with_points_must_be_claimed() -> None:
    raw = tomllib.loads(USER.replace('extensions = [".shp", ".nc"]', 'extensions = [".nc"]'))
    with pytest.raises(DialectError, match=r"detect\.extensions"):
        parse_dialect(raw)


def test_a_bad_rule_is_a_dialect_error() -> None:
    with pytest.raises(DialectError, match=r"detect.rule\[1\].pattern"):
        parse_dialect(tomllib.loads(USER.replace('pattern = "G700"', 'pattern = "G700("')))
    with pytest.raises(DialectError, match=r"detect.rule\[0\].view"):
        parse_dialect(tomllib.loads(USER.replace('view = "comments"', 'view = "tape"')))


# ---- the front-end key ---------------------------------------------------------------------
@pytest.mark.parametrize("name", available())
def test_frontend_key_names_a_registered_front_end(name: str) -> None:
    raw = _builtin_raw(name)
    d = load_dialect(name)
    want = raw.get("frontend", "linuxcnc" if raw.get("macro_flavour") == "linuxcnc" else "fanuc")
    if name == "haas":  # base = "fanuc" and no key of its own
        want = "fanuc"
    assert d.frontend == want
    assert front_end(d) is FRONT_ENDS[want]
    assert "checker" not in raw  # the old spelling is gone from the built-in files


def test_the_front_ends_lower_what_their_dialects_say() -> None:
    assert {load_dialect(n).frontend for n in ("series8", "grbl", "linuxcnc", "syntec", "szgh")} == {
        "series8", "grbl", "linuxcnc", "fanuc"}
    assert [n for n, fe in FRONT_ENDS.items() if fe.fast_path] == ["fanuc"]
    for fe in FRONT_ENDS.values():
        assert callable(fe.function())


def _user_file(tmp_path: Path, extra: str) -> str:
    path = tmp_path / "mine.toml"
    path.write_text(USER + extra, encoding="utf-8")
    return str(path)


def test_a_user_dialect_selects_the_grbl_front_end(tmp_path: Path) -> None:
    # grbl's block checks (its front end) refuse a macro assignment with grbl error:1 (E0250);
    # the same dialect on the fanuc front end runs it
    program = "#1 = 5\nG00 X#1\n"
    _, fanuc_r = compile_commands(program, dialect=_user_file(tmp_path, ""))
    assert "E0250" not in [d.code for d in fanuc_r.sink]
    grbl = _user_file(tmp_path, "").replace("mine.toml", "grbl_like.toml")
    Path(grbl).write_text(USER.replace('name = "shopmill"', 'name = "shopmill"\nfrontend = "grbl"'), encoding="utf-8")
    _, grbl_r = compile_commands(program, dialect=grbl)
    assert "E0250" in [d.code for d in grbl_r.sink]
    old = parse_dialect(tomllib.loads(USER.replace('name = "shopmill"', 'name = "shopmill"\nchecker = "grbl"')))
    assert old.frontend == "grbl"  # the old key name still reads


def test_an_unknown_front_end_is_a_diagnostic_not_a_traceback(tmp_path: Path) -> None:
    path = tmp_path / "odd.toml"
    path.write_text(USER.replace('name = "shopmill"', 'name = "shopmill"\nfrontend = "heidenhain"'), encoding="utf-8")
    _, r = compile_commands("G00 X1.\nM30\n", dialect=str(path))
    assert "E0940" in [d.code for d in r.sink]
    with pytest.raises(DialectError, match="frontend"):
        parse_dialect(tomllib.loads(USER.replace('name = "shopmill"', 'name = "shopmill"\nfrontend = 3')))
