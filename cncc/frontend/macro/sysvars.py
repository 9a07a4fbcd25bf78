"""System variables: the controller's state seen through ``#`` numbers.

Reads the interpreter's modal state, position and frame, the tool and work-offset
tables of :class:`~cncc.frontend.interp.InterpOptions`, and the ``--io`` input
values; writes go to the same tables.  Numbers follow Fanuc macro B (which the
SZGH manual's examples use for ``#4003``, ``#4014``, ``#5001``):

=================  ========================================================
``#1000-#1035``     Fanuc digital inputs (from ``--io``)
``#2001-#2200``     Fanuc tool length offsets H1-H200 (program units)
``#2201-#2400``     Fanuc tool radius offsets D1-D200
``#11001..``        Fanuc memory C: length geometry (``#10001..`` wear = 0)
``#13001..``        Fanuc memory C: radius geometry (``#12001..`` wear = 0)
``#3000``           alarm (write): stops with a diagnostic
``#3006``           stop with an operator message (write)
``#3001-#3005``     clocks and control flags (accepted, read 0)
``#4001-#4030``     modal G code of each group (number of the code in force)
``#4107 #4109``     D and F in force; ``#4111`` H, ``#4119`` S, ``#4120`` T
``#5001-#5006``     end point of the last block (work coordinates)
``#5021-#5026``     machine position; ``#5041-#5046`` current position
``#5061-#5066``     skip position (the last block end: no probe is simulated)
``#5201-#5326``     work offsets: external (#5201..) and G54-G59 (#5221.. step 20)
``#1001-#1799``     SZGH tool tables in um (X/Y/Z/A length, D1-D4 radius)
``#1800-#1804``     SZGH input bytes X00-X39; ``#1808-#1809`` output words
=================  ========================================================

A dialect with a ``[[system_variables]]`` table (Fanuc, Haas: :mod:`.systable`) uses
its table instead: the ranges say what exists and what is writable, by kind; a number
outside every range is unknown (a warning through :attr:`MachineVariables.warn`, read
vacant, a write ignored) rather than an error.  Wear memories are kept apart and
added to the geometry in the offsets the interpreter uses (memory C: H = geometry +
wear).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from cncc.dialects import code_tenths
from cncc.frontend.macro.systable import SystemRange, table_for
from cncc.frontend.macro.values import MacroError, Value

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter


@dataclass(slots=True)
class IoState:
    """Input values from ``--io`` and the outputs a program switched."""

    inputs: dict[str, float] = field(default_factory=dict)  # "X12", "M14", "#1800" -> value
    outputs: dict[str, bool] = field(default_factory=dict)

    def input_valid(self, name: str) -> bool | None:
        """True/False when the ``--io`` file says, None when it does not."""
        v = self.inputs.get(name.upper())
        if v is None and name[:1].upper() == "X" and name[1:].isdigit():
            v = self._bit("X", int(name[1:]))
        return None if v is None else v != 0

    def _bit(self, kind: str, n: int) -> float | None:
        byte = self.inputs.get(f"#{1800 + n // 8}")
        if byte is None:
            return None
        return float((int(byte) >> (n % 8)) & 1)

    def byte(self, k: int) -> float:
        """SZGH input register #1800+k (bits X(8k) .. X(8k+7))."""
        raw = self.inputs.get(f"#{1800 + k}")
        if raw is not None:
            return raw
        total = 0
        for bit in range(8):
            if self.inputs.get(f"X{8 * k + bit:02d}", 0.0):
                total |= 1 << bit
        return float(total)

    def output_word(self, k: int) -> float:
        total = 0
        for bit in range(16):
            if self.outputs.get(f"Y{16 * k + bit:02d}", False):
                total |= 1 << bit
        return float(total)


Alarm = Callable[[int, float | None], None]


class MachineVariables:
    """The :class:`~cncc.frontend.macro.values.SystemVariables` of one run."""

    def __init__(self, interp: Interpreter, flavour: str, io: IoState, on_control: Alarm) -> None:
        self.it = interp
        self.flavour = flavour
        self.io = io
        self.on_control = on_control  # #3000 / #3006 writes
        groups = interp.dialect.groups
        self.group_numbers: dict[int, list[str]] = {}
        for name, number in groups.items():
            self.group_numbers.setdefault(number, []).append(name)
        self.current_n = 0
        self.current_o = 0
        self.table = table_for(interp.dialect)
        self.warn: Callable[[str], None] | None = None  # unknown system variables (set by the executor)
        self.stored: dict[int, float] = {}  # written values of the kinds cncc does not model
        self.wear: dict[tuple[str, int], float] = {}  # ("length"|"radius", offset number) -> mm
        self._warned: set[int] = set()

    # ---- helpers
    @property
    def _unit_mm(self) -> float:
        return self.it.frame.units.mm_per_unit

    def _axis(self, k: int, vec: tuple[float, ...]) -> float:
        return vec[k] / self._unit_mm if k < 3 else vec[k]

    # ---- the dialect's table
    def _unknown(self, n: int, what: str) -> None:
        if self.warn is not None and n not in self._warned:
            self._warned.add(n)
            self.warn(f"#{n} is not a {self.it.dialect.name} system variable cncc knows; {what}")

    def _table_read(self, r: SystemRange, n: int) -> Value:
        k = n - r.first
        kind = r.kind
        if kind == "io_input":
            return self.io.inputs.get(f"#{n}", self.stored.get(n, 0.0))
        if kind in ("output", "constant", "alarm", "message_stop"):
            return self.stored.get(n, 0.0)
        if kind == "modal_g":
            return self._modal_g(n % 100)
        if kind == "modal_other":
            return self._modal_other(n % 100)
        if kind == "position":
            return self._axis(k, self.it.pos) if k < 6 else 0.0
        if kind == "machine_position":
            return self._axis(k, self._machine_pos()) if k < 6 else 0.0
        if kind == "work":
            return self._work_read(n)
        if kind == "work_extended":
            index, axis = divmod(k, 20)
            off = self.it.options.work_offsets_mm.get(7 + index, (0.0,) * 6)
            return self._axis(axis, off) if axis < 6 else 0.0
        table, wear = kind.removeprefix("tool_").removesuffix("_wear"), kind.endswith("_wear")
        w = self.wear.get((table, k + 1), 0.0)
        if wear:
            return w / self._unit_mm
        values = self.it.options.tool_lengths_mm if table == "length" else self.it.options.tool_radii_mm
        return (values.get(k + 1, 0.0) - w) / self._unit_mm

    def _table_write(self, r: SystemRange, n: int, value: Value) -> bool:
        if not r.writable:
            return False
        v = 0.0 if value is None else value
        k = n - r.first
        kind = r.kind
        opts = self.it.options
        if kind in ("alarm", "message_stop"):
            self.on_control(n, value)
        elif kind == "work" and n >= 5221:
            return self.write_work(n, v)
        elif kind == "work_extended":
            index, axis = divmod(k, 20)
            if axis < 6:
                off = list(opts.work_offsets_mm.get(7 + index, (0.0,) * 6))
                off[axis] = v * (self._unit_mm if axis < 3 else 1.0)
                opts.work_offsets_mm[7 + index] = tuple(off)  # type: ignore[assignment]
        elif kind.startswith("tool_"):
            table = kind.removeprefix("tool_").removesuffix("_wear")
            values = opts.tool_lengths_mm if table == "length" else opts.tool_radii_mm
            old = self.wear.get((table, k + 1), 0.0)
            mm = v * self._unit_mm
            if kind.endswith("_wear"):
                self.wear[(table, k + 1)] = mm
                values[k + 1] = values.get(k + 1, 0.0) - old + mm
            else:
                values[k + 1] = mm + old
        else:
            self.stored[n] = v
        return True

    # ---- reading
    def read(self, n: int) -> Value:
        if self.table is not None:
            r = self.table.find(n)
            if r is None:
                if f"#{n}" in self.io.inputs:
                    return self.io.inputs[f"#{n}"]
                self._unknown(n, "read as vacant")
                return None
            return self._table_read(r, n)
        if self.flavour == "szgh" and 1001 <= n <= 1809:
            return self._szgh_read(n)
        if 1000 <= n <= 1035:
            return self.io.inputs.get(f"#{n}", 0.0)
        if 2001 <= n <= 2400 or 10001 <= n <= 13999:
            return self._tool_read(n)
        if 3000 <= n <= 3999:
            return 0.0
        if 4001 <= n <= 4030 or 4201 <= n <= 4230:
            return self._modal_g(n % 100)
        if 4100 <= n <= 4130 or 4300 <= n <= 4330:
            return self._modal_other(n % 100)
        if 5001 <= n <= 5006 or 5041 <= n <= 5046 or 5061 <= n <= 5066:
            return self._axis((n - 1) % 20, self.it.pos)
        if 5021 <= n <= 5026:
            return self._axis(n - 5021, self._machine_pos())
        if 5201 <= n <= 5346:
            return self._work_read(n)
        if f"#{n}" in self.io.inputs:
            return self.io.inputs[f"#{n}"]
        raise MacroError("E0302", f"system variable #{n} is not available")

    def _machine_pos(self) -> tuple[float, ...]:
        f = self.it.frame
        off = f.total_offset_mm
        p = [self.it.pos[i] + off[i] for i in range(6)]
        p[f.tool_length_axis] += f.tool_length_mm
        return tuple(p)

    def _modal_g(self, group: int) -> Value:
        names = self.group_numbers.get(group, [])
        codes: dict[str, str] = getattr(self.it, "group_codes", None) or dict(getattr(self.it.modal, "codes", ()))
        for name in names:
            code = codes.get(name)
            if code:
                return code_tenths(code[1:]) / 10.0
        return None

    def _modal_other(self, k: int) -> Value:
        m = self.it.modal
        f = self.it.frame
        if k == 7:
            return float(f.comp_index)
        if k == 9:
            return m.feed
        if k == 11:
            return float(f.tool_length_index)
        if k == 14:
            return float(self.current_n)
        if k == 15:
            return float(self.current_o)
        if k == 19:
            return m.spindle_rpm
        if k == 20:
            return float(m.tool_selected)
        return None

    def _tool_read(self, n: int) -> Value:
        opts = self.it.options
        if 2001 <= n <= 2200 or 11001 <= n <= 11999:
            return opts.tool_lengths_mm.get(n % 1000 if n > 10000 else n - 2000, 0.0) / self._unit_mm
        if 2201 <= n <= 2400 or 13001 <= n <= 13999:
            return opts.tool_radii_mm.get(n % 1000 if n > 10000 else n - 2200, 0.0) / self._unit_mm
        return 0.0  # wear tables

    def _work_read(self, n: int) -> Value:
        k, axis = divmod(n - 5201, 20)
        if axis >= 6:
            return 0.0
        off = self.it.options.work_offsets_mm.get(k, (0.0,) * 6) if k > 0 else (0.0,) * 6
        return self._axis(axis, off)

    def _szgh_read(self, n: int) -> Value:
        if 1800 <= n <= 1804:
            return self.io.byte(n - 1800)
        if n in (1808, 1809):
            return self.io.output_word(n - 1808)
        table, tool = divmod(n - 1000, 100)
        if not 1 <= tool <= 99 or table > 7:
            raise MacroError("E0302", f"system variable #{n} is not available")
        opts = self.it.options
        if table == 4:  # Z length
            return round(opts.tool_lengths_mm.get(tool, 0.0) * 1000.0, 6)
        if table == 1:  # D1 radius
            return round(opts.tool_radii_mm.get(tool, 0.0) * 1000.0, 6)
        return 0.0

    # ---- writing
    def write(self, n: int, value: Value) -> bool:
        if self.table is not None:
            r = self.table.find(n)
            if r is None:
                self._unknown(n, "the write is ignored")
                return True
            return self._table_write(r, n, value)
        v = 0.0 if value is None else value
        if n in (3000, 3006):
            self.on_control(n, value)
            return True
        if 3001 <= n <= 3005 or 3007 <= n <= 3999:
            return True
        opts = self.it.options
        if self.flavour == "szgh" and 1001 <= n <= 1799:
            table, tool = divmod(n - 1000, 100)
            if table == 4:
                opts.tool_lengths_mm[tool] = v / 1000.0
            elif table == 1:
                opts.tool_radii_mm[tool] = v / 1000.0
            return 1 <= tool <= 99
        if 2001 <= n <= 2200 or 11001 <= n <= 11999:
            opts.tool_lengths_mm[n % 1000 if n > 10000 else n - 2000] = v * self._unit_mm
            return True
        if 2201 <= n <= 2400 or 13001 <= n <= 13999:
            opts.tool_radii_mm[n % 1000 if n > 10000 else n - 2200] = v * self._unit_mm
            return True
        if 5221 <= n <= 5346:
            return self.write_work(n, v)
        return False

    def write_work(self, n: int, v: float) -> bool:
        """G54-G59 (#5221 ... step 20): the offset of one axis, in program units."""
        opts = self.it.options
        k, axis = divmod(n - 5201, 20)
        if axis >= 6:
            return False
        off = list(opts.work_offsets_mm.get(k, (0.0,) * 6))
        off[axis] = v * (self._unit_mm if axis < 3 else 1.0)
        opts.work_offsets_mm[k] = tuple(off)  # type: ignore[assignment]
        return True
