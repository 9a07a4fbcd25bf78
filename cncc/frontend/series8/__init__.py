"""The SERIES 8 front end (spec ``shared/spec/series8.md``; dialect ``series8``).

SERIES 8 is an RS-274-D lineage control, not a Fanuc one, so several codes and words
mean something else than in the other dialects.  This package holds what the shared
modal interpreter does not do by itself:

* :mod:`~cncc.frontend.series8.builder` - bare axis letters (``G00XZ`` = X0 Z0);
* :mod:`~cncc.frontend.series8.front` - the block loop (one-block coordinate modes,
  unit switches, strict-mode checks) and the stream of commands after it;
* :mod:`~cncc.frontend.series8.codes` - G04 X/F, G06, G10, G21-G23, G55-G58,
  G67-G69, G92/G98, the G41/G42 side, the codes the manual names without words;
* :mod:`~cncc.frontend.series8.arcs` - the modal arc radius, R enlarged to a half
  circle, unsigned single-quadrant I/J (``INVALID ARC``);
* :mod:`~cncc.frontend.series8.corners` - G10 inserted radius and chamfer, the
  perpendicular cutter-compensation start-up;
* :mod:`~cncc.frontend.series8.cycles` - G81-G89 with their own words.
* :mod:`~cncc.frontend.series8.lathe` - X as a diameter in lathe programs (A-25),
  the constant-surface-speed record on G95 moves under G96.

The submodules register into :mod:`cncc.frontend.ops` when
:func:`~cncc.frontend.series8.front.lower_series8` first imports them; their hooks act
only on interpreters of this dialect (those with a :class:`~.state.S8State`).
"""
