"""The SERIES 8 block loop: parse, interpret, insert corners.

``lower_series8`` is what the ``series8`` front end (:mod:`cncc.frontend.plugins`) runs for
the ``series8`` dialect.  Around each block it:

* refuses in strict mode what the manual never shows ('%', '/', O words, ( )
  comments, spec A-39);
* gives the G90/G91 state back after a G67/G68 block;
* converts the modal feed when G70/G71 switches units (the positions, R levels and
  the arc radius are kept in mm already) and warns if it happens after motion (A-30);
* hands the commands to :class:`~cncc.frontend.series8.corners.Stream` for G10.
"""

from __future__ import annotations

import functools
from collections.abc import Iterator

from cncc import diagnostics as dg
from cncc.diagnostics import DiagnosticSink
from cncc.dialects import Dialect
from cncc.frontend import ops
from cncc.frontend.handler_tables import core_table
from cncc.frontend.interp import InterpOptions, Interpreter
from cncc.frontend.parser import ParseOptions, Parser
from cncc.frontend.series8 import arcs as _arcs  # noqa: F401  (registers the arc rules)
from cncc.frontend.series8 import cavities as _cavities  # noqa: F401  (registers G34-G36)
from cncc.frontend.series8 import codes as _codes  # noqa: F401  (registers the SERIES 8 ops)
from cncc.frontend.series8 import cycles as _cycles  # noqa: F401  (registers G81-G89)
from cncc.frontend.series8 import lathe, state
from cncc.frontend.series8 import patterns as _patterns  # noqa: F401  (registers G49/G50)
from cncc.frontend.series8.corners import Stream
from cncc.frontend.series8.layer import LAYER
from cncc.frontend.syntax import Block
from cncc.ir import Arc, Command, Linear, Rapid, Units
from cncc.source import SourceFile, Span


@functools.cache
def handler_table() -> ops.HandlerTable:
    """The core table with the SERIES 8 layer on top (every registering module is imported above)."""
    return LAYER.compose(core_table())


def lower_series8(src: SourceFile, dialect: Dialect, sink: DiagnosticSink, options: InterpOptions) -> Iterator[Command]:
    parser = Parser(dialect, sink, ParseOptions(strict=options.strict))
    it = Interpreter(dialect, sink, src.source_id, options, table=handler_table())
    st = state.attach(it)
    st.x_diameter = bool(dialect.option("lathe_diameter_x", True)) and lathe.is_lathe_program(src.text)
    it.modal = it.modal.with_(cycle_return_initial=False)  # every SERIES 8 cycle returns to R
    stream = Stream(sink)
    for block in parser.blocks(src):
        if options.strict:
            _strict(it, block)
        units = it.frame.units
        st.corner = None
        st.feed_before = it.modal.feed
        cmds = lathe.with_css(it, it.execute(block))
        if st.restore_incremental is not None:
            it.modal = it.modal.with_(incremental=st.restore_incremental)
            st.restore_incremental = None
        if it.frame.units is not units:
            _units_switched(it, block, units)
        if any(isinstance(c, Rapid | Linear | Arc) for c in cmds):
            st.moved = True
            st.at_depth = False
        yield from stream.push(cmds, st.corner)
    yield from stream.finish()


def _strict(it: Interpreter, block: Block) -> None:
    span = Span(it.source_id, block.start, block.end)
    found = [what for what, present in (
        ("'%'", block.percent), ("block delete '/'", bool(block.block_delete)),
        ("O numbers", any(w.letter == "O" for w in block.words)),
        ("( ) comments", any(c.text.startswith("(") for c in block.comments))) if present]
    if found:
        it.sink.emit(dg.CONTROLLER_REJECTS, span, f"SERIES 8 programs have no {', '.join(found)} (strict mode, "
                                                  "spec A-39)")


def _units_switched(it: Interpreter, block: Block, old: Units) -> None:
    st = state.get(it)
    assert st is not None
    if it.modal.feed is not None and not any(w.letter == "F" for w in block.words):
        it.modal = it.modal.with_(feed=it.modal.feed * old.mm_per_unit / it.frame.units.mm_per_unit)
    if st.moved:
        it.sink.emit(dg.ASSUMED, Span(it.source_id, block.start, block.end),
                     "units switched after motion: the feed, levels and positions are converted (spec A-30)")
