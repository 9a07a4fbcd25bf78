"""szgh.lark and series8.lark extend fanuc.lark (lark ``%import`` + ``%override``/``%extend``)
instead of copying it: they define no rule or terminal of their own that fanuc.lark has, and
what they import is what fanuc.lark defines for the same dialect."""

from __future__ import annotations

import re
from importlib import resources

import pytest

from cncc.dialects import load_dialect
from cncc.frontend.parser import _lark, family_text, grammar_text

_DEFINED = re.compile(r"^\??([A-Za-z_]\w*)(?:\.\d+)?[ \t]*:", re.MULTILINE)


def _source(family: str) -> str:
    return resources.files("cncc.grammar").joinpath(f"{family}.lark").read_text(encoding="utf-8")


@pytest.mark.parametrize("family", ["szgh", "series8"])
def test_the_grammar_extends_fanuc(family: str) -> None:
    text = _source(family)
    assert "%import fanuc (@all)" in text
    own = set(_DEFINED.findall(text))  # %override / %extend lines do not match: they start with '%'
    base = set(_DEFINED.findall(_source("fanuc")))
    assert not own & base, own & base
    assert len(text.splitlines()) < len(_source("fanuc").splitlines())


@pytest.mark.parametrize("name", ["szgh", "series8"])
def test_the_import_names_every_base_symbol(name: str) -> None:
    d = load_dialect(name)
    args = (d.comments, d.block_end, d.lexicon.abbreviations, d.lexicon.functions)
    imported = re.search(r"%import fanuc \(([^)]*)\)", grammar_text(d.grammar, *args))
    assert imported is not None
    names = {n.strip() for n in imported.group(1).split(",")}
    assert set(_DEFINED.findall(family_text("fanuc", *args))) <= names
    parser, _ = _lark(d.grammar, *args)
    # no symbol of the base came through renamed (lark mangles what is not imported by name)
    assert not [r for r in parser.rules if "fanuc__" in str(r.origin) or "fanuc__" in str(r.alias or "")]
    assert not [t for t in parser.terminals if "fanuc__" in t.name]
