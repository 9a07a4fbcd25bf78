"""LinuxCNC's system parameters: the numbered ones the interpreter keeps and the read-only ``#<_name>`` ones.

Read from the interpreter's state when the program reads them (LinuxCNC 2.9's numbers,
checked against its ``rs274`` by ``tests/oracle``):

- ``#5161-#5169`` / ``#5181-#5189``: the G28 / G30 points (machine coordinates);
- ``#5210`` G92 in force (1/0), ``#5211-#5219`` the G92 (or G52) offset, kept by G92.2;
- ``#5220`` the active work system (1 = G54 ... 9 = G59.3);
- ``#5221-#5230``, ``#5241-#5250``, ... ``#5381-#5390``: G54 ... G59.3, X Y Z A B C U V W and R;
- ``#5400`` the loaded tool, ``#5401-#5409`` its offsets, ``#5410`` its diameter (read-only);
- ``#5420-#5428``: the current position in the program's units and work system (read-only).

Lengths of the offset, reference and tool parameters are in the machine's units (the
dialect option ``parameter_units``: the stand-alone rs274 has inch machine units); the
position parameters and ``#<_x>`` ... are in the program's units.  The parameters are
LinuxCNC's tables: a value the program writes into a work offset is the one the next G10
or selection of that system uses (:meth:`SystemParameters.write`); a value written into
another system parameter reads back until the interpreter's own value changes.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from cncc.frontend.linuxcnc.lathe import diameter_mode
from cncc.ir import Command, CompSide, Coolant, CoolantState, Plane, Spindle, SpindleState, ToolChange, Vec6

if TYPE_CHECKING:
    from cncc.frontend.interp import Interpreter

READ_ONLY_NUMBERS = (range(5400, 5414), range(5420, 5429))
_PLANE = {Plane.XY: 170.0, Plane.ZX: 180.0, Plane.YZ: 190.0}
_COMP = {CompSide.OFF: 400.0, CompSide.LEFT: 410.0, CompSide.RIGHT: 420.0}
_SYSTEM_CODE = (0.0, 540.0, 550.0, 560.0, 570.0, 580.0, 590.0, 591.0, 592.0, 593.0)
_AXES = "xyzabcuvw"


def read_only_number(n: int) -> bool:
    return any(n in r for r in READ_ONLY_NUMBERS)


def coolant_after(state: CoolantState, flood: bool, mist: bool) -> tuple[bool, bool]:
    """Flood and mist after an M7/M8/M9 (``state``): M9 turns both off, M7 and M8 add theirs."""
    if state is CoolantState.OFF:
        return False, False
    if state is CoolantState.FLOOD:
        return True, mist
    return flood, True


class SystemParameters:
    """The values of LinuxCNC's system parameters for one running program."""

    def __init__(self, it: Interpreter, call_level: Callable[[], int]) -> None:
        self.it = it
        self.call_level = call_level
        self.inch = str(it.dialect.option("parameter_units", "mm")) == "inch"
        self.constants = {str(k): float(v) for k, v in it.dialect.raw.get("named_parameters", {}).items()}
        self.spindle = SpindleState.OFF
        self.flood = self.mist = False
        self.named = self._named_table()

    # ---- what the program did that the interpreter's modes do not keep
    def observe(self, commands: list[Command]) -> None:
        for c in commands:
            if isinstance(c, Spindle):
                self.spindle = c.state
            elif isinstance(c, ToolChange):
                self.spindle = SpindleState.OFF  # LinuxCNC stops the spindle for M6
            elif isinstance(c, Coolant):
                self.flood, self.mist = coolant_after(c.state, self.flood, self.mist)

    # ---- numbered
    def number(self, n: int) -> float | None:
        """The interpreter's value of parameter ``n``, or None when it is not a system parameter."""
        if 5161 <= n <= 5169:
            return self._machine_len(self._reference(1), n - 5161)
        if 5181 <= n <= 5189:
            return self._machine_len(self._reference(2), n - 5181)
        if 5210 <= n <= 5390:
            return self._offsets(n)
        if 5400 <= n <= 5413:
            return self._tool(n)
        if 5420 <= n <= 5428:
            return self._position(n - 5420)
        return None

    def _offsets(self, n: int) -> float | None:
        from cncc.frontend.rs274 import state

        it = self.it
        st = state(it)
        if n == 5210:
            return 1.0 if st.g92_applied else 0.0
        if 5211 <= n <= 5219:
            return self._machine_len(st.g92_saved_mm, n - 5211)
        if n == 5220:
            return float(it.frame.work_index)
        system, slot = divmod(n - 5201, 20)
        if not 1 <= system <= 9:
            return None
        if slot == 9:
            return st.rotation_deg.get(system, 0.0)
        return self._machine_len(it.options.work_offsets_mm.get(system, (0.0,) * 6), slot)

    def write(self, n: int, value: float) -> bool:
        """``#n = value`` into the table LinuxCNC keeps in parameter ``n`` (the work offsets, the G92
        offset G92.3 restores, the G28/G30 points, the rotations); False when ``n`` is not one.
        LinuxCNC applies a written work offset when the system is selected or set by G10 again."""
        from cncc.frontend.rs274 import state

        st = state(self.it)
        if 5161 <= n <= 5166 or 5181 <= n <= 5186:
            which, axis = (1, n - 5161) if n < 5170 else (2, n - 5181)
            st.stored_mm[which] = _with(self._reference(which), axis, self._from_machine(value, axis))
            return True
        if 5211 <= n <= 5216:
            st.g92_saved_mm = _with(st.g92_saved_mm, n - 5211, self._from_machine(value, n - 5211))
            return True
        system, slot = divmod(n - 5201, 20)
        if 5221 <= n <= 5390 and 1 <= system <= 9 and (slot < 6 or slot == 9):
            if slot == 9:
                st.rotation_deg[system] = value
                return True
            table = self.it.options.work_offsets_mm
            table[system] = _with(table.get(system, (0.0,) * 6), slot, self._from_machine(value, slot))
            return True
        return False

    def _from_machine(self, value: float, axis: int) -> float:
        return value * 25.4 if self.inch and axis < 3 else value

    def _reference(self, which: int) -> Vec6:
        from cncc.frontend.rs274 import state

        got = state(self.it).stored_mm.get(which)
        if got is not None:
            return got
        refs = self.it.options.reference_mm
        return refs[which - 1] if which - 1 < len(refs) else (0.0,) * 6

    def _tool(self, n: int) -> float:
        it = self.it
        tool = it.modal.tool_loaded
        if n == 5400:
            return float(tool)
        if n == 5403:
            return self._machine(it.options.tool_lengths_mm.get(tool, 0.0)) if tool else 0.0
        if n == 5410:
            return self._machine(2.0 * it.options.tool_radii_mm.get(tool, 0.0)) if tool else 0.0
        return 0.0  # X, A-W offsets, angles and orientation: lathe tools (not kept by cncc)

    def _position(self, axis: int) -> float:
        it = self.it
        if axis >= 6:
            return 0.0
        v = it.pos[axis]
        return v / it.frame.units.mm_per_unit if axis < 3 else v

    def _machine(self, mm: float) -> float:
        return mm / 25.4 if self.inch else mm

    def _machine_len(self, v: Vec6, axis: int) -> float:
        if axis >= 6:
            return 0.0
        return self._machine(v[axis]) if axis < 3 else v[axis]

    # ---- named, read-only
    def name(self, name: str) -> float | None:
        fn = self.named.get(name)
        if fn is not None:
            return fn()
        return self.constants.get(name)

    def read_only_name(self, name: str) -> bool:
        return name in self.named or name in self.constants

    def _named_table(self) -> dict[str, Callable[[], float]]:
        from cncc.frontend.rs274 import state

        it = self.it

        def flag(test: Callable[[], bool]) -> Callable[[], float]:
            return lambda: 1.0 if test() else 0.0

        def k() -> float:
            return it.frame.units.mm_per_unit

        table: dict[str, Callable[[], float]] = {
            "_motion_mode": self._motion_mode,
            "_plane": lambda: _PLANE[it.frame.plane],
            "_ccomp": lambda: _COMP[it.frame.comp_side],
            "_metric": flag(lambda: k() == 1.0), "_imperial": flag(lambda: k() != 1.0),
            "_absolute": flag(lambda: not it.modal.incremental), "_incremental": flag(lambda: it.modal.incremental),
            "_inverse_time": flag(lambda: state(it).inverse_time),
            "_units_per_minute": flag(lambda: not state(it).inverse_time and not it.modal.per_rev),
            "_units_per_rev": flag(lambda: it.modal.per_rev),
            "_coord_system": lambda: _SYSTEM_CODE[it.frame.work_index] if it.frame.work_index < 10 else 0.0,
            "_tool_offset": flag(lambda: it.frame.tool_length_mm != 0.0 or it.frame.tool_length_index != 0),
            "_retract_r_plane": flag(lambda: not it.modal.cycle_return_initial),
            "_retract_old_z": flag(lambda: it.modal.cycle_return_initial),
            "_spindle_rpm_mode": flag(lambda: not it.modal.css), "_spindle_css_mode": flag(lambda: it.modal.css),
            "_ijk_absolute_mode": flag(lambda: state(it).arc_absolute),
            "_spindle_on": flag(lambda: self.spindle is not SpindleState.OFF),
            "_spindle_cw": flag(lambda: self.spindle is SpindleState.CW),
            "_mist": flag(lambda: self.mist), "_flood": flag(lambda: self.flood),
            "_feed": lambda: it.modal.feed or 0.0, "_rpm": lambda: it.modal.spindle_rpm,
            "_current_tool": lambda: float(it.modal.tool_loaded),
            "_selected_tool": lambda: float(it.modal.tool_selected),
            "_call_level": lambda: float(self.call_level()),
            "_lathe_diameter_mode": flag(lambda: diameter_mode(it)),
            "_lathe_radius_mode": flag(lambda: not diameter_mode(it)),
        }
        for i, axis in enumerate(_AXES):
            table[f"_{axis}"] = self._reader(self._position, i)
            if i < 6:
                table[f"_abs_{axis}"] = self._reader(self._absolute, i)
        return table

    @staticmethod
    def _reader(fn: Callable[[int], float], axis: int) -> Callable[[], float]:
        return lambda: fn(axis)

    def _motion_mode(self) -> float:
        it = self.it
        code = it.group_codes.get("cycle") if it.modal.cycle else None
        if it.modal.motion == "none" and not it.modal.cycle:
            return 800.0
        name = code or it.group_codes.get("motion", "G0")
        try:
            return round(float(name.lstrip("Gg")) * 10.0)
        except ValueError:
            return 0.0

    def _absolute(self, axis: int) -> float:
        """``#<_abs_x>`` ...: the machine position, in the program's units."""
        from cncc.frontend.linuxcnc.rotation import placement

        it = self.it
        f = it.frame
        if axis < 2:
            v = placement(it).machine(it.pos[0], it.pos[1])[axis]
        else:
            v = it.pos[axis] + f.total_offset_mm[axis] + (f.tool_length_mm if axis == f.tool_length_axis else 0.0)
        return v / f.units.mm_per_unit if axis < 3 else v


def _with(v: Vec6, i: int, x: float) -> Vec6:
    q = list(v)
    q[i] = x
    return (q[0], q[1], q[2], q[3], q[4], q[5])
