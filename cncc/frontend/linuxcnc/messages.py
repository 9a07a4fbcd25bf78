"""The text of a LinuxCNC ``(DEBUG,...)`` / ``(PRINT,...)`` comment as LinuxCNC 2.9 writes it.

The text after the comma is kept as written (blanks included).  ``#n`` and ``#<name>``
become the parameter's value, ``######`` for a named parameter that is not set.  A
format word sets how the values after it are written, up to the end of the text:

- none: six decimals (``%lf``);  ``%d``: no decimals (rounded);  ``%f``: four decimals;
- ``%.Nf`` with one digit N: N decimals;
- any other ``%.``: the ``%`` is dropped;  any other ``%``: kept as it is (``%%`` keeps the
  first and reads the second again, ``%lf`` is text).

Measured on LinuxCNC 2.9's ``rs274`` (``tests/oracle``, feature ``messages``).
"""

from __future__ import annotations

from collections.abc import Callable

from cncc.frontend.linuxcnc.builder import param_name

UNSET = "######"


def format_message(text: str, number: Callable[[int], float], name: Callable[[str], float | None]) -> str:
    """``text`` with its parameters substituted and its format words applied."""
    out: list[str] = []
    decimals = 6
    i, n = 0, len(text)
    while i < n:
        ch = text[i]
        nxt = text[i + 1] if i + 1 < n else ""
        if ch == "%":
            if nxt == "d":
                decimals, i = 0, i + 2
            elif nxt == "f":
                decimals, i = 4, i + 2
            elif nxt == "." and i + 3 < n and text[i + 2].isdigit() and text[i + 3] == "f":
                decimals, i = int(text[i + 2]), i + 4
            elif nxt == ".":
                i += 1
            else:
                out.append(ch)
                i += 1
        elif ch == "#" and nxt.isdigit():
            j = i + 1
            while j < n and text[j].isdigit():
                j += 1
            out.append(_text(number(int(text[i + 1:j])), decimals))
            i = j
        elif ch == "#" and nxt == "<" and ">" in text[i:]:
            j = text.index(">", i)
            got = name(param_name(text[i:j + 1]))
            out.append(UNSET if got is None else _text(got, decimals))
            i = j + 1
        else:
            out.append(ch)
            i += 1
    return "".join(out)


def _text(value: float, decimals: int) -> str:
    """printf's ``%.Nf``; a value within rounding noise of 0 (cncc's sums of offsets) is 0, not -0."""
    return f"{round(value, 12) + 0.0:.{decimals}f}"
