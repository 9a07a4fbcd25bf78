"""Bringing the target's units, plane, offsets and kept transforms to a command's frame.

:class:`FrameSync` writes the blocks that change them before a move: G20/G21, G17-G19, the work
system, G52/G92 (or the fold of offsets the target cannot set, :mod:`cncc.backends.gcode.frames`),
tool length, G10 L2 work tables, and G68/G51.1/G51 for the rotation, mirror and scaling records the
target keeps (:mod:`cncc.backends.gcode.keep_transforms`).
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from cncc import diagnostics as dg
from cncc.backends.gcode.frames import add, sub
from cncc.backends.gcode.keep_transforms import scale_codes, scale_words
from cncc.backends.gcode.numbers import fixed
from cncc.backends.gcode.writer import AXES, ROTATION_DECIMALS, BlockWriter
from cncc.ir import (
    Frame,
    Plane,
    Units,
    Vec6,
)
from cncc.ir.frame import Mirror, Rotation, Scaling

_PLANE_OPS = {Plane.XY: "plane_xy", Plane.ZX: "plane_zx", Plane.YZ: "plane_yz"}


class FrameSync(BlockWriter):
    """Units, plane, offsets and kept transforms brought to each command's frame."""

    # ---- frames ------------------------------------------------------------------------------
    def _sync(self, f: Frame, start: Vec6, cancel_cycle: bool) -> Iterator[str]:
        """Bring the target's units, plane and offsets to ``f``; update the fold."""
        lines: list[str] = []
        if cancel_cycle and self.cycle_initial is not None:
            lines.append(self.block([self.t.code("cycle_off")]))
            self.cycle_initial = None
        if self.forced is None and f.units is not self.units:
            if self.qpos is not None:  # where the target is, in mm: the last written numbers, in the old units
                k = 10.0 ** -self.decimals * self.units.mm_per_unit
                self.written_mm = [self.qpos[i] * k for i in range(3)]
            self.units = f.units
            self.sync_poison = True
            lines.append(self.block([self.code("inch" if f.units is Units.INCH else "metric", "units")]))
            self.feed = None
            self.qpos = None
        if f.plane is not self.plane:
            self.plane = f.plane
            lines.append(self.block([self.code(_PLANE_OPS[f.plane], "the plane")]))
        self.sync_poison = True  # units and offsets have no incremental form
        lines += self._offsets(f, start)
        self.sync_poison = False
        if lines and self.cycle_initial is not None:
            lines.insert(0, self.block([self.t.code("cycle_off")]))
            self.cycle_initial = None
        fold = self.tf.fold(f, False)
        if fold != self.fold:
            old_fold = self.fold or (0.0,) * 6
            # an axis whose folded offset changed moves with the next move: it names that axis even when
            # the number is the one written last (a G43 folded into Z: the tool goes up by the length)
            self.restate |= {i for i in range(3) if abs(fold[i] - old_fold[i]) > 1e-12 and i not in self.unknown}
            self.fold = fold
            self.qpos = None
        if any(abs(v) > 1e-12 for v in fold):
            self.warn(dg.XL_FOLDED, f"{self.t.name} output: an offset the target cannot set is added to the "
                                    "coordinates")
        mirror = f.mirror != self.mirror and self.t.has("mirror_on")
        rotation = f.rotation != self.rotation and self.t.has("rotate_on")
        scaling = f.scaling != self.scaling and self.t.has("scale_on")
        if (mirror or rotation or scaling) and self.cycle_initial is not None and not lines:
            lines.append(self.block([self.t.code("cycle_off")]))
            self.cycle_initial = None
        self.sync_poison = True
        if scaling and self.scaling is not None:  # off first: SYNTEC's G50 also cancels a mirror
            lines.append(self._scaling_block(None))
        if mirror:
            lines += self._mirror_blocks(f.mirror)
        if rotation:
            lines.append(self._rotation_block(f.rotation))
        if scaling and f.scaling is not None:
            lines.append(self._scaling_block(f.scaling, start))
        self.sync_poison = False
        yield from lines

    def _mirror_blocks(self, m: Mirror | None) -> list[str]:
        """G50.1 for the mirror in force, G51.1 with the kept record's axes at its centre."""
        out, old = [], self.mirror
        self.mirror = m
        self.qpos = None
        fold = self.fold or (0.0,) * 6
        if old is not None:
            out.append(self.block([self.t.code("mirror_off"),
                                   *(f"{AXES[k]}{self.length(old.center_mm[k] + fold[k])}" for k in range(3)
                                     if old.axes[k])]))
        if m is not None:
            out.append(self.block([self.t.code("mirror_on"),
                                   *(f"{AXES[k]}{self.length(m.center_mm[k] + fold[k])}" for k in range(3)
                                     if m.axes[k])]))
        return out

    def _scaling_block(self, s: Scaling | None, start: Vec6 | None = None) -> str:
        """G51 (SZGH G36, alone in its block) with the kept record's centre and factors, or G50 (G37).

        A centre coordinate of an axis whose position the output does not know, at the tool's position
        (``start``: the source omitted it), is left out: the target's centre is then where its tool is,
        as the source's; a number would assume where the machine started (and a scaled axis the
        program never moves would move)."""
        self.scaling = s
        self.qpos = None
        on, off = scale_codes(self.t)
        if s is None:
            return self.block([off])
        words = scale_words(self.t, s)
        assert words is not None, "keep_transforms keeps only writable scalings"
        fold = self.fold or (0.0,) * 6
        centre = [k for k in words[0]
                  if not (start is not None and k in self.unknown and abs(s.center_mm[k] - start[k]) <= 1e-9)]
        return self.block([on, *(f"{AXES[k]}{self.length(s.center_mm[k] + fold[k])}" for k in centre), *words[1]])

    def _rotation_block(self, r: Rotation | None) -> str:
        """G68 with the kept record (centre in the target's program coordinates, angle in degrees), or G69."""
        self.rotation = r
        self.qpos = None  # positions are read again from the commands under the new rotation
        if r is None:
            return self.block([self.t.code("rotate_off")])
        fold = self.fold or (0.0,) * 6
        i, j = r.plane.first, r.plane.second
        centre = [f"{AXES[k]}{self.text(self.counts(c + fold[k], k), k)}"
                  for k, c in zip((i, j), r.center_mm, strict=True)]
        return self.block([self.t.code("rotate_on"), *centre, f"R{fixed(r.angle_deg, ROTATION_DECIMALS)}"])

    def _offsets(self, f: Frame, start: Vec6) -> list[str]:
        tf, out = self.tf, []
        if tf.work_mm is None:  # the target's G54 is taken to be the source's (as its table had it)
            if f.work_index == 1:
                tf.work_tables.setdefault(1, f.work_offset_mm)
            tf.work_mm = tf.work_tables[1] if f.work_index == 1 else (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        if f.work_index != tf.work_index and f.work_index in self.t.work:
            out.append(self.block([self.t.work[f.work_index].name]))
            tf.adopt_work(f)
        g92 = self.t.code("set_origin") or self.t.code("set_origin_rs274")  # LinuxCNC's G92 presets alike
        g92_want = sub(f.g92_offset_mm, tf.g92_in_local_mm)  # what the target's G92 must hold
        if g92_want != tf.g92_mm and not self.g92_force and self.t.has("local_offset"):
            # A G92 *offset* change (LinuxCNC G52/G92.x, a cancel) of an axis whose position the output does
            # not know (or whose offset is already held there): the target's G92 would set it from wherever
            # the machine is, so the change goes into the target's local offset (G52), which moves the
            # origin by the same amount from any start.
            delta = sub(g92_want, tf.g92_mm)
            if any(abs(delta[i]) > 1e-12 and (i in self.unknown or tf.g92_in_local_mm[i]) for i in range(6)):
                tf.g92_in_local_mm = add(tf.g92_in_local_mm, delta)
                g92_want = tf.g92_mm
        elif g92_want != tf.g92_mm and not self.g92_force and any(
                abs(g92_want[i] - tf.g92_mm[i]) > 1e-12 and i in self.unknown for i in range(6)):
            # no local offset in the target: leave its G92 as it is and let the fold add the change to the
            # coordinates (the G92 is written once the axis has a known position)
            self.warn(dg.XL_FOLDED, f"{self.t.name} output: a G92 offset change of an axis with no known position "
                                    "is added to the coordinates")
            g92_want = tf.g92_mm
        local_want = add(f.local_offset_mm, tf.g92_in_local_mm)
        if local_want != tf.local_mm and self.t.has("local_offset"):
            out.append(self.block([self.t.code("local_offset"), *self._vector_words(local_want)]))
            tf.local_mm = local_want
        if (f.tool_length_mm, f.tool_length_index) != (tf.tool_mm, tf.tool_index):
            axis_before, length_before = tf.tool_axis, tf.tool_mm
            length = self._tool_length(f)
            if length:  # the next move names the tool axis (see ``restate``): E0208 on read-back without it
                self.restate |= {axis_before, tf.tool_axis}
                # where the tool is, in the target's terms once the block ran: the command's start is the
                # position before the change (the source applies the change with the move)
                shift = [0.0] * 6
                shift[axis_before] += length_before
                shift[tf.tool_axis] -= tf.tool_mm
                self.start_shift_mm = (shift[0], shift[1], shift[2], shift[3], shift[4], shift[5])
            out += length
        if (g92_want != tf.g92_mm or self.g92_force) and g92:
            machine = add(start, add(f.total_offset_mm, _tool(f)))
            old = tf.g92_mm
            tf.g92_mm = g92_want
            here = sub(machine, tf.offset())
            words = [f"{AXES[i]}{self.text(self.counts(here[i], i), i)}" for i in range(6)
                     if abs(g92_want[i] - old[i]) > 1e-12 or i in self.g92_force]
            self.unknown -= self.g92_force  # a preset gives the axis a program position where it is
            self.g92_force = set()
            out.append(self.block([g92, *words]))
        if out:
            self.qpos = None
        return out

    def _tool_length(self, f: Frame) -> list[str]:
        """The target's tool length block for ``f`` (G43/G44 H, G49, grbl's G43.1 Z), and the state it sets.

        An H number is written as the target's G43/G44 H even when its length is zero here (no --tools
        table, or H holds 0): the target's table value applies, as the source's does on its machine.
        The sign of a zero length is the sign of the zero (G44 stores -0.0)."""
        tf = self.tf
        op = "length_minus" if math.copysign(1.0, f.tool_length_mm) < 0 else "length_plus"
        if f.tool_length_index > 0 and self.t.has(op) and f.tool_length_axis == 2:
            tf.tool_mm, tf.tool_index, tf.tool_axis = f.tool_length_mm, f.tool_length_index, f.tool_length_axis
            return [self.block([self.t.code(op), f"H{f.tool_length_index}"])]
        if f.tool_length_mm == 0.0 and self.t.has("length_off"):
            # the state is the frame's (its H number too), so the next move does not write G49 again
            tf.tool_mm, tf.tool_index, tf.tool_axis = 0.0, f.tool_length_index, f.tool_length_axis
            return [self.block([self.t.code("length_off")])]
        if self.t.has("length_dynamic") and f.tool_length_axis == 2:  # grbl G43.1 Z<length>
            tf.tool_mm, tf.tool_index, tf.tool_axis = f.tool_length_mm, f.tool_length_index, 2
            return [self.block([self.t.code("length_dynamic"), f"Z{self.length(f.tool_length_mm)}"])]
        return []

    def _work_table(self, index: int, old: Vec6, new: Vec6) -> Iterator[str]:
        """G10 L2 (or L20, LinuxCNC's G10 L20) set a work offset: the target's ``G10 L2 Pn`` when it has one,
        else the target keeps its table value and the difference is folded into the coordinates (N0809)."""
        tf = self.tf
        tf.work_tables.setdefault(index, old)
        code = self.t.code("data_input") or self.t.code("data_input_rs274")
        if not code or not 1 <= index <= 6:
            return
        if self.cycle_initial is not None:
            yield self.block([self.t.code("cycle_off")])
            self.cycle_initial = None
        self.sync_poison = True
        yield self.block([code, "L2", f"P{index}", *self._vector_words(new)])
        self.sync_poison = False
        tf.work_tables[index] = new
        if tf.work_mm is not None and tf.work_index == index:
            tf.work_mm = new
            self.qpos = None


def _tool(f: Frame) -> Vec6:
    v = [0.0] * 6
    v[f.tool_length_axis] = f.tool_length_mm
    return (v[0], v[1], v[2], v[3], v[4], v[5])
