#!/usr/bin/env python3
"""Convert rs274 canonical calls to vcnc events (docs/events.md), in machine
coordinates and mm: the converter of every LinuxCNC fixture set
(make_fixtures.py: linuxcnc; make_ext_fixtures.py: linuxcnc_tlo,
linuxcnc_cycles, linuxcnc_comp, linuxcnc_grbl). It also runs rs274 and
parses its output.

  * motion: STRAIGHT_TRAVERSE -> rapid, STRAIGHT_FEED -> feed (the feed of
    the last SET_FEED_RATE), ARC_FEED -> arc, DWELL -> dwell, PROGRAM_END ->
    end M02 (the axis order of ARC_FEED by plane: PLANES). rs274 prints
    positions in program coordinates: machine = program + G5x offset
    (SET_G5X_OFFSET) + G92 offset (SET_G92_OFFSET) + tool length offset;
  * units: after USE_LENGTH_UNITS(CANON_UNITS_INCHES) every length rs274
    prints (points, centres, offsets, feeds) is in inches and is multiplied
    by 25.4; it re-sends nothing on a unit change, and what it printed in mm
    stays valid. Only with `inch=True` (the linuxcnc set; the other sets are
    mm only, and refuse G20). Two checks keep inch exact: an end point or
    offset printed in inches must be a multiple of 0.0005 in, so that
    25.4 x the 4-decimal print is the exact mm value (R-arc centres, which
    rs274 computes, are exempt), and a cutting move must be in the units
    its F was set in (rs274 does not re-send F on G20/G21, and LinuxCNC,
    which keeps the physical feed, and vcnc, which keeps F's number, differ
    there). SET_XY_ROTATION must be 0;
  * the tool length offset: USE_TOOL_LENGTH_OFFSET(x y z, ...) gives the
    offset, printed like every length in the units in force (checked: a
    tool of 1 in gives 25.4000 after G21 and 1.0000 after G20, and
    `G20 G43.1 Z1` gives 1.0000), so it is converted like the others and
    must be exact in inches too. rs274 keeps the offset's number across a
    unit change and later misreads it (G53, G28/G30, G43.1/G49 after
    G20/G21 with an offset on: tests/fixtures/linuxcnc_grbl/README.md), so
    a set must not carry an offset across G20/G21;
  * G28 / G30 without axis words (`home_lines`): rs274 prints two
    traverses, the first to where the tool already is (its intermediate
    point is the current point); that zero-length one is dropped, so the
    block is one rapid to the stored position, as grbl moves. With axis
    words both legs stay, even when one has zero length;
  * inverse-time feed (G93): rs274 turns F into the equivalent feed of each
    move (path length x F, helix length for a helix) and prints it with
    SET_FEED_RATE before the move, so the event's `feed` is that mm/min
    value (SET_FEED_MODE itself has nothing for the trace);
  * coolant: MIST_ON and FLOOD_ON (M7, M8) -> coolant on; M9's MIST_OFF and
    FLOOD_OFF -> one coolant off. PROGRAM_STOP (M0) -> stop M00;
    OPTIONAL_PROGRAM_STOP (M1) -> stop M01 only with `optional_stop` (vcnc
    reports M01 only with --optional-stop). PROGRAM_END -> end with the
    program's own code (`end_code`, M02 or M30);
  * `frame` events (the project's conventions, /work/notes/conventions.md):
    one whenever origin (G5x + G92) or tool offset differs from the last one
    reported, emitted before the first event of the block that changed it,
    or alone at the end of that block when it makes no other event. The
    run starts with origin 0 and no tool offset reported (the fresh
    parameter file makes every start-up offset 0, which is checked).
    Offsets the M2 block resets (LinuxCNC re-selects G54 at program end) are
    not reported;
  * `spindle` events: SET_SPINDLE_SPEED while turning (when the speed
    changes; a START in the same block replaces it: one event a block),
    START_SPINDLE_CLOCKWISE / COUNTERCLOCKWISE, and
    STOP_SPINDLE_TURNING when the spindle turns or the block says M5 (the
    stops rs274 makes on its own at M6 and M2 with the spindle already
    stopped, or at M2, are not events);
  * in canned-cycle blocks, zero-length moves are dropped (LinuxCNC's G85
    under G99 ends with a rapid from R to R);
  * `tool_change` on CHANGE_TOOL, with the tool of the last SELECT_TOOL;
  * `hole` events in canned-cycle blocks (lines the caller names, with the
    cycle's G code): a hole starts at each rapid of the block that moves in
    the plane of the cycle, and its event goes before that rapid with
    `at` = the hole's position in the plane and, on the drilling axis, the
    deepest point its feeds reach (the Z point); a zero DWELL in a G86
    block (LinuxCNC needs a P word there, Fanuc G86 has none) is dropped.

Anything else unexpected is an error (ConvertError), never skipped.
"""

import json
import math
import os
import re
import subprocess
import tempfile
from decimal import Decimal


class ConvertError(Exception):
    pass


# "   12 N34    STRAIGHT_FEED(1.0000, 2.0000, ...)"; the N column is "N....."
# for calls not made by a numbered block, and has no trailing blank once the
# number has 6 digits or more.
CANON_RE = re.compile(r"^\s*(\d+)\s+N(\.\.\.\.\.|\d+)\s*([A-Z_0-9]+)\((.*)\)\s*$")

PLANES = {
    # canon plane -> (vcnc name, first axis, second axis, normal axis)
    "CANON_PLANE_XY": ("xy", "x", "y", "z"),
    "CANON_PLANE_XZ": ("zx", "z", "x", "y"),
    "CANON_PLANE_YZ": ("yz", "y", "z", "x"),
}

AXES = ("x", "y", "z")
Q = Decimal("0.0001")
MM_PER = {"CANON_UNITS_MM": Decimal(1), "CANON_UNITS_INCHES": Decimal("25.4")}
ZERO = {a: Decimal(0) for a in AXES}

# Calls with nothing for the event trace in these sets.
IGNORED = {
    "SET_FEED_REFERENCE", "ON_RESET", "COMMENT", "PALLET_SHUTTLE",
    "SET_FEED_MODE", "SET_SPINDLE_MODE", "SET_MOTION_CONTROL_MODE",
    "SET_NAIVECAM_TOLERANCE", "SET_TOOL_TABLE_ENTRY", "START_CHANGE",
    # tapping (G74/G84) holds the overrides
    "DISABLE_FEED_OVERRIDE", "ENABLE_FEED_OVERRIDE",
    "DISABLE_SPEED_OVERRIDE", "ENABLE_SPEED_OVERRIDE",
}

# The tapping cycles: the spindle reverses at the bottom and back at R.
TAPS = ("G74", "G84")

# Drilling axis (the plane's normal) and the two plane axes, by canon plane.
CYCLE_AXES = {
    "CANON_PLANE_XY": ("z", ("x", "y")),
    "CANON_PLANE_XZ": ("y", ("z", "x")),
    "CANON_PLANE_YZ": ("x", ("y", "z")),
}


def num(s):
    return Decimal(s.strip())


def out_num(d):
    """Decimal -> float rounded to 4 decimals, never -0.0."""
    f = float(d.quantize(Q))
    return 0.0 if f == 0 else f


def point(d):
    return {a: out_num(d[a]) for a in AXES}


def tool_table_text(tools):
    """LinuxCNC tool table for {n: (length_mm, radius_mm)}.

    rs274 2.9 (standalone, no INI units) reads the table in INCHES: Z is the
    length and D the DIAMETER, both / 25.4 here, printed with 12 decimals so
    that 25.4 x the value rounds to the mm value at rs274's 4 decimals."""
    lines = []
    for n in sorted(tools):
        length, radius = tools[n]
        lines.append("T%d P%d D%.12f Z%+.12f ;" % (
            n, n, Decimal(2) * Decimal(str(radius)) / Decimal("25.4"),
            Decimal(str(length)) / Decimal("25.4")))
    return "\n".join(lines) + "\n"


def run_rs274(rs274, lines, table_text, name, var_text=""):
    """rs274 -g on `lines` (each prefixed with N<line number>), with its own
    tool table and a fresh parameter file (empty, or `var_text`: lines
    "<number> <value>", lengths in inches like the tool table); returns
    stdout."""
    with tempfile.TemporaryDirectory(prefix="vcnc_rs274_") as tmp:
        prog = os.path.join(tmp, "prog.ngc")
        with open(prog, "w") as f:
            for i, text in enumerate(lines, 1):
                f.write("N%d %s\n" % (i, text))
        tbl = os.path.join(tmp, "tool.tbl")
        with open(tbl, "w") as f:
            f.write(table_text)
        var = os.path.join(tmp, "params.var")
        with open(var, "w") as f:
            f.write(var_text)
        env = dict(os.environ, HOME=tmp)   # rs274 writes ~/.tool.mmap
        r = subprocess.run([rs274, "-g", "-t", tbl, "-v", var, prog],
                           stdin=subprocess.DEVNULL, capture_output=True,
                           text=True, env=env, cwd=tmp)
        err = r.stderr.replace("executing", "").strip()
        if r.returncode != 0 or err:
            raise ConvertError("%s: rs274 failed (exit %d): %s"
                               % (name, r.returncode, err or r.stdout[-500:]))
        return r.stdout


class Converter:
    """One program's canonical calls -> events. `end_line`: the M2 block;
    `cycles`: {line: "G81", ...} for the canned-cycle blocks; `m5_lines`:
    lines whose block says M5; `inch`: accept G20 (USE_LENGTH_UNITS inches);
    `end_code`: the end event's code; `home_lines`: G28/G30 blocks without
    axis words; `optional_stop`: report M1 (vcnc's --optional-stop)."""

    def __init__(self, name, end_line, cycles=None, m5_lines=(), inch=False,
                 end_code="M02", home_lines=(), optional_stop=False,
                 start_offsets=False, exact_inch=True):
        self.name = name
        self.inch = inch
        # `start_offsets`: the parameter file sets G54 (the flatten set):
        # rs274's start-up SET_G5X_OFFSET is taken, not refused.
        self.start_offsets = start_offsets
        # `exact_inch`: refuse inch values whose 4-decimal print is not the
        # exact mm value (off for programs whose points are computed, such
        # as a compensated path; their tolerance is then rs274's print).
        self.exact_inch = exact_inch
        self.end_code = end_code
        self.home_lines = set(home_lines)
        self.optional_stop = optional_stop
        self.coolant_off_line = None  # M9 prints MIST_OFF and FLOOD_OFF: one event
        self.home_first = None        # the G28/G30 block whose first leg is pending
        self.unit = MM_PER["CANON_UNITS_MM"]   # mm per printed length unit
        self.end_line = end_line
        self.cycles = cycles or {}
        self.m5_lines = set(m5_lines)
        self.g5x = dict(ZERO)
        self.g92 = dict(ZERO)
        self.tlo = dict(ZERO)
        self.reported = (dict(ZERO), dict(ZERO))
        self.frame_line = None        # block whose offsets are not reported yet
        self.pos = dict(ZERO)         # machine
        self.plane = "CANON_PLANE_XY"
        self.feed = None              # mm/min
        self.feed_unit = self.unit    # the units F was set in
        self.spindle_dir = "stop"
        self.rpm = Decimal(0)
        self.selected_tool = None
        self.events = []
        self.hole = None              # events of the current hole, buffered
        self.line = None
        self.ended = False

    # -- helpers -------------------------------------------------------------
    def err(self, msg):
        raise ConvertError("%s:%s: %s" % (self.name, self.line, msg))

    def mm(self, s, exact=True):
        """A printed length -> Decimal mm; `exact`: refuse an inch value
        whose 4-decimal print cannot be the exact length."""
        v = num(s) * self.unit
        if exact and self.exact_inch and v != v.quantize(Q):
            self.err("%s in is not a multiple of 0.0005 in: its 4-decimal "
                     "print is not exact in mm" % s.strip())
        return v

    def check_feed(self, what):
        if not self.feed:
            self.err("%s with no feed" % what)
        if self.feed_unit != self.unit:
            self.err("%s: feed set before a unit change" % what)

    def machine(self, prog):
        return {a: prog[a] + self.g5x[a] + self.g92[a] + self.tlo[a] for a in AXES}

    def origin(self):
        return {a: self.g5x[a] + self.g92[a] for a in AXES}

    def flush_frame(self):
        state = (self.origin(), dict(self.tlo))
        if self.frame_line is not None and state != self.reported:
            ev = {"type": "frame", "line": self.frame_line, "origin": point(state[0])}
            if any(state[1][a] != 0 for a in AXES):
                ev["tool_offset"] = point(state[1])
            self.events.append(ev)
            self.reported = state
        self.frame_line = None

    def flush_hole(self):
        if self.hole is None:
            return
        line, cycle, evs = self.hole
        self.hole = None
        drill, _ = CYCLE_AXES[self.plane]
        feeds = [e["to"] for e in evs if e["type"] == "feed"]
        if not feeds:
            self.err("hole without a feed")
        at = dict(feeds[0])     # the hole's position in the plane
        at[drill] = min(f[drill] for f in feeds)
        self.events.append({"type": "hole", "line": line, "cycle": cycle, "at": at})
        self.events.extend(evs)

    def emit(self, ev):
        self.flush_frame()
        if self.hole is not None:
            self.hole[2].append(ev)
        else:
            self.events.append(ev)

    def new_block(self, line):
        """Called when the calls of another block begin."""
        self.flush_hole()
        self.flush_frame()
        self.line = line

    # -- calls -----------------------------------------------------------------
    def straight(self, call, args):
        to = self.machine(dict(zip(AXES, map(self.mm, args[0:3]))))
        if self.line in self.home_lines and self.home_first != self.line:
            # G28/G30 without axis words: the first traverse is rs274's
            # intermediate point, which is where the tool already is
            self.home_first = self.line
            if call != "STRAIGHT_TRAVERSE" or to != self.pos:
                self.err("G28/G30 without axis words: first leg %s to %s is not "
                         "zero-length" % (call, to))
            return
        ev = {"type": "rapid" if call == "STRAIGHT_TRAVERSE" else "feed",
              "line": self.line, "to": point(to)}
        if call == "STRAIGHT_FEED":
            self.check_feed("feed move")
            ev["feed"] = out_num(self.feed)
        cycle = self.cycles.get(self.line)
        if cycle:
            _, plane_axes = CYCLE_AXES[self.plane]
            moves_in_plane = any(to[a] != self.pos[a] for a in plane_axes)
            if to == self.pos:
                return      # LinuxCNC's G85/G89 under G99 rapid "to R" at R
            raised_only = self.hole is not None and not any(
                e["type"] == "feed" for e in self.hole[2])
            if call == "STRAIGHT_TRAVERSE" and moves_in_plane:
                if not raised_only:
                    self.flush_hole()
                    self.flush_frame()
                    self.hole = (self.line, cycle, [])
            elif moves_in_plane:
                self.err("a cycle feed moves in the plane")
            elif self.hole is None and call == "STRAIGHT_TRAVERSE":
                # LinuxCNC: a cycle that started below R first goes
                # straight to R where the tool is, then to the hole
                self.flush_frame()
                self.hole = (self.line, cycle, [])
            elif self.hole is None:
                self.err("cycle move before the first positioning")
        self.emit(ev)
        self.pos = to

    def arc(self, args):
        if self.cycles.get(self.line):
            self.err("arc in a cycle block")
        pname, fa, sa, na = PLANES[self.plane]
        prog_end = {fa: self.mm(args[0]), sa: self.mm(args[1]), na: self.mm(args[5])}
        to = self.machine(prog_end)
        off = {a: self.g5x[a] + self.g92[a] + self.tlo[a] for a in AXES}
        # rs274 computes R-arc centres: rounded, so not exact in inches
        center = {fa: self.mm(args[2], False) + off[fa],
                  sa: self.mm(args[3], False) + off[sa], na: self.pos[na]}
        rotation = int(args[4])
        if rotation == 0:
            self.err("arc rotation 0")
        self.check_feed("arc")
        for to_k in self.turns(to, center, fa, sa, rotation):
            self.emit({"type": "arc", "line": self.line, "to": point(to_k),
                       "center": point(center), "plane": pname,
                       "dir": "ccw" if rotation > 0 else "cw",
                       "feed": out_num(self.feed)})
            center = dict(center, **{na: to_k[na]})
            self.pos = to_k

    def turns(self, to, center, fa, sa, rotation):
        """The end points of an ARC_FEED of |rotation| turns (G2/G3 P, a
        multi-turn arc): |rotation| - 1 full circles back to the start in
        the plane, then the arc to `to`. The axes off the plane move
        linearly with the angle turned over the whole path, as LinuxCNC's
        motion runs its one helix of that total angle. One turn: `to`."""
        n = abs(rotation)
        if n == 1:
            return [to]
        c = (center[fa], center[sa])
        a0 = math.atan2(self.pos[sa] - c[1], self.pos[fa] - c[0])
        a1 = math.atan2(to[sa] - c[1], to[fa] - c[0])
        same = math.hypot(to[fa] - self.pos[fa], to[sa] - self.pos[sa]) < 1e-9
        sweep = 2 * math.pi if same else (a1 - a0) % (2 * math.pi)
        if rotation < 0 and not same:
            sweep = 2 * math.pi - sweep
        total = (n - 1) * 2 * math.pi + sweep
        out = []
        for k in range(1, n):
            f = Decimal(k * 2 * math.pi / total)
            p = {a: self.pos[a] + (to[a] - self.pos[a]) * f for a in AXES}
            p[fa], p[sa] = self.pos[fa], self.pos[sa]
            out.append(p)
        return out + [to]

    def rigid_tap(self, args):
        """G33.1: LinuxCNC's RIGID_TAP(x, y, z) is the whole tap, as its
        G-code reference describes it: in to the point locked to the
        spindle (the lead of START_SPEED_FEED_SYNC), the spindle reversed,
        back out to where the tap started (where the interpreter then
        stands), the spindle's direction restored. The overrun while the
        spindle reverses is the machine's, not the program's."""
        if getattr(self, "sync_lead", None) is None:
            self.err("RIGID_TAP without START_SPEED_FEED_SYNC")
        if self.spindle_dir not in ("cw", "ccw"):
            self.err("RIGID_TAP with the spindle stopped")
        start = self.pos
        to = self.machine(dict(zip(AXES, map(self.mm, args[0:3]))))
        lead = out_num(self.sync_lead)
        fwd = self.spindle_dir
        rev = "ccw" if fwd == "cw" else "cw"
        self.emit({"type": "thread", "line": self.line, "to": point(to), "lead_mm": lead})
        self.emit({"type": "spindle", "line": self.line, "dir": rev, "rpm": out_num(self.rpm)})
        self.emit({"type": "thread", "line": self.line, "to": point(start), "lead_mm": lead})
        self.emit({"type": "spindle", "line": self.line, "dir": fwd, "rpm": out_num(self.rpm)})
        self.pos = start

    def spindle(self, call, args):
        if call == "SET_SPINDLE_SPEED":
            rpm = num(args[1])
            if self.spindle_dir != "stop" and rpm != self.rpm:
                self.rpm = rpm
                self.emit({"type": "spindle", "line": self.line,
                           "dir": self.spindle_dir, "rpm": out_num(rpm)})
            self.rpm = rpm
        elif call == "STOP_SPINDLE_TURNING":
            if self.spindle_dir != "stop" or self.line in self.m5_lines:
                self.spindle_dir = "stop"
                self.emit({"type": "spindle", "line": self.line, "dir": "stop",
                           "rpm": 0.0})
        else:
            self.spindle_dir = "cw" if call == "START_SPINDLE_CLOCKWISE" else "ccw"
            # `S.. M4` on a turning spindle is one spindle change in vcnc's
            # contract: the speed change of the same block is replaced.
            last = self.events[-1] if self.events and self.hole is None else None
            if last and last["type"] == "spindle" and last["line"] == self.line:
                self.events.pop()
            # A tap's reversal (stop, then the other way) is one change.
            buf = self.hole[2] if self.hole is not None else self.events
            last = buf[-1] if buf else None
            if self.cycles.get(self.line) in TAPS and last and last["type"] == "spindle" \
                    and last["line"] == self.line and last["dir"] == "stop":
                buf.pop()
            self.emit({"type": "spindle", "line": self.line,
                       "dir": self.spindle_dir, "rpm": out_num(self.rpm)})

    def call(self, call, args):
        if call == "USE_LENGTH_UNITS":
            if len(args) != 1 or args[0] not in MM_PER:
                self.err("units %r" % args)
            if args[0] != "CANON_UNITS_MM" and not self.inch:
                self.err("only mm programs in this set: %r" % args)
            self.unit = MM_PER[args[0]]
        elif call == "SET_XY_ROTATION":
            if num(args[0]) != 0:
                self.err("XY rotation %s" % args[0])
        elif call == "SET_G5X_OFFSET":
            # (index, x, y, z, a, b, c)
            self.g5x = dict(zip(AXES, map(self.mm, args[1:4])))
            self.frame_line = self.line
        elif call == "SET_G92_OFFSET":
            self.g92 = dict(zip(AXES, map(self.mm, args[0:3])))
            self.frame_line = self.line
        elif call == "USE_TOOL_LENGTH_OFFSET":
            # "x y z, a b c, u v w": the first group, blank separated, in
            # the units in force
            xyz = args[0].split()
            self.tlo = dict(zip(AXES, map(self.mm, xyz[0:3])))
            self.frame_line = self.line
        elif call == "SET_FEED_RATE":
            self.feed = self.mm(args[0], exact=False)   # quantized on output
            self.feed_unit = self.unit
        elif call == "SELECT_PLANE":
            if args[0] not in PLANES:
                self.err("plane %r" % args[0])
            self.plane = args[0]
        elif call in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED"):
            self.straight(call, args)
        elif call == "ARC_FEED":
            self.arc(args)
        elif call == "START_SPEED_FEED_SYNC":
            self.sync_lead = self.mm(args[0].split(",")[0], exact=False)
        elif call == "STOP_SPEED_FEED_SYNCH":
            self.sync_lead = None
        elif call == "RIGID_TAP":
            self.rigid_tap(args)
        elif call == "DWELL":
            s = num(args[0])
            if s == 0 and self.cycles.get(self.line) in ("G86",) + TAPS:
                return          # the P0 LinuxCNC's G86 needs; a tap's P0
            if s == 0:
                self.err("zero dwell outside G86")
            self.emit({"type": "dwell", "line": self.line, "seconds": out_num(s)})
        elif call in ("SET_SPINDLE_SPEED", "STOP_SPINDLE_TURNING",
                      "START_SPINDLE_CLOCKWISE", "START_SPINDLE_COUNTERCLOCKWISE"):
            self.spindle(call, args)
        elif call == "SELECT_TOOL":
            self.selected_tool = int(args[0])
        elif call == "CHANGE_TOOL":
            if self.selected_tool is None:
                self.err("CHANGE_TOOL without SELECT_TOOL")
            self.emit({"type": "tool_change", "line": self.line,
                       "tool": self.selected_tool})
        elif call in ("MIST_ON", "FLOOD_ON"):
            self.emit({"type": "coolant", "line": self.line, "on": True})
        elif call in ("MIST_OFF", "FLOOD_OFF"):
            if self.coolant_off_line != self.line:
                self.coolant_off_line = self.line
                self.emit({"type": "coolant", "line": self.line, "on": False})
        elif call == "PROGRAM_STOP":
            self.emit({"type": "stop", "line": self.line, "code": "M00"})
        elif call == "OPTIONAL_PROGRAM_STOP":
            if self.optional_stop:
                self.emit({"type": "stop", "line": self.line, "code": "M01"})
        elif call in IGNORED:
            pass
        else:
            self.err("unexpected canonical call %s(%s)" % (call, ", ".join(args)))

    def convert(self, canon_text):
        for raw in canon_text.splitlines():
            if not raw.strip():
                continue
            m = CANON_RE.match(raw)
            if not m:
                raise ConvertError("%s: cannot parse rs274 line %r" % (self.name, raw))
            _, nword, call, args_s = m.groups()
            args = [a.strip() for a in args_s.split(",")] if args_s.strip() else []
            line = None if nword == "....." else int(nword)
            if self.ended:
                continue
            if line is None:
                # start-up calls: everything zero, nothing to report
                if call == "SET_G5X_OFFSET" and self.start_offsets:
                    self.g5x = dict(zip(AXES, map(self.mm, args[1:4])))
                    continue
                if call in ("SET_G5X_OFFSET", "SET_G92_OFFSET"):
                    if any(num(a) != 0 for a in args[1 if call == "SET_G5X_OFFSET" else 0:]):
                        self.err("non-zero offset at start-up")
                    continue
                if call in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED", "DWELL",
                            "PROGRAM_END"):
                    self.err("%s without a line number" % call)
            elif line != self.line:
                self.new_block(line)
            if call == "PROGRAM_END":
                self.flush_hole()
                self.frame_line = None     # M2's reset of G5x is not reported
                self.events.append({"type": "end", "line": line, "code": self.end_code})
                self.ended = True
                continue
            if line is not None and line == self.end_line and call in (
                    "STOP_SPINDLE_TURNING", "SET_G5X_OFFSET", "SET_G92_OFFSET"):
                continue        # M2's own spindle stop and G54 reset
            self.call(call, args)
        if not self.ended:
            raise ConvertError("%s: no PROGRAM_END in rs274 output" % self.name)
        return self.events


def convert(canon_text, name, end_line, cycles=None, m5_lines=(), inch=False, **kw):
    """`kw`: end_code, home_lines, optional_stop (see Converter)."""
    return Converter(name, end_line, cycles, m5_lines, inch, **kw).convert(canon_text)


def write_jsonl(path, rows):
    with open(path, "w") as f:
        for r in rows:
            f.write(json.dumps(r, separators=(",", ":")) + "\n")


def program_facts(ngc_lines):
    """From the LinuxCNC spelling: the M2 line, the lines saying M5, and the
    canned-cycle blocks {line: "G8x"} (a block with X/Y/Z words while a cycle
    is the modal motion). Programs of these sets write one motion G code per
    block at most and never rely on anything subtler."""
    motion = None
    cycles = {}
    m5 = []
    end = None
    for i, text in enumerate(ngc_lines, 1):
        code = strip_comments(text)
        gs = []
        for g in re.findall(r"G\s*(\d+(?:\.\d*)?)", code):
            v = float(g)
            gs.append(str(int(v)) if v == int(v) else g)
        for g in gs:
            if g in ("0", "1", "2", "3", "80", "73", "81", "82", "83", "85", "86", "89"):
                motion = g
        if re.search(r"M0*5(?![\d.])", code):
            m5.append(i)
        if re.search(r"M0*2(?![\d.])|M30(?![\d.])", code):
            end = i
        if motion in ("73", "81", "82", "83", "85", "86", "89") and re.search(r"[XYZ]", code) \
                and not re.search(r"G(10|28|30|53|92)(?![\d.])", code):
            cycles[i] = "G" + motion
    return end, cycles, m5


def strip_comments(text):
    """A line without its ( ) comments and its ; comment, upper case."""
    return re.sub(r"\([^)]*\)", "", text).split(";")[0].upper()


def end_code(ngc_lines, end_line):
    """"M30" when the program's end block says M30, else "M02"."""
    code = strip_comments(ngc_lines[end_line - 1])
    return "M30" if re.search(r"M30(?![\d.])", code) else "M02"


def home_lines(ngc_lines):
    """Lines of G28/G30 blocks (not G28.1/G30.1) without X/Y/Z words."""
    out = []
    for i, text in enumerate(ngc_lines, 1):
        code = strip_comments(text)
        if re.search(r"G0*(28|30)(?![\d.])", code) and not re.search(r"[XYZ]", code):
            out.append(i)
    return out
