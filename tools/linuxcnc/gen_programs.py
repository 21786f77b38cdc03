#!/usr/bin/env python3
"""Generate random G-code programs for the LinuxCNC comparison fixtures.

Each program exists in two spellings with identical line structure:

  NNN.ngc  for LinuxCNC's rs274 (dwell: G4 P<seconds>)
  NNN.nc   for vcnc's fanuc dialect (dwell: G4 X<seconds>)

Those are the only differences. The subset is what both dialects define the
same way: G0, G1, G2/G3 (I/J/K and R form, negative R for arcs over 180
degrees, I/J/K full circles, helices) in G17/G18/G19, G90/G91, G54-G59
selected and set with G10 L2 P1..P6 (only in G90), G92 presets (only in G90),
G53 G0 (only in G90), G4, F, and M2 at the end.

Two batches:
  001-300  (--count)      the subset above, all in mm;
  301-400  (--ext-count)  the same plus G28 with axis words (G90 and G91) and
                          inch segments: G20 ... G21 in the middle of the
                          program (see MixedProgram for the extra rules).
A program's text depends only on its number and the seed, so adding the
second batch left the first one byte-for-byte unchanged.

Rules the generator keeps:
  * every length and feed carries a decimal point (vcnc reads X5500 as 5.5 mm);
  * one command per line, no N numbers, no comments, so a block's 1-based
    line number is its line in the file;
  * every point of every move (arcs: the whole circle, so the swept path too)
    stays inside x,y in [-400,400] and z in [-200,200] MACHINE coordinates;
  * arc end points are computed from centre, radius and angle and rounded to
    4 decimals; start and end radius differ by less than 0.001 mm;
  * R arcs never have a chord within 1% of 2R, and no arc has zero length
    except the deliberate I/J/K full circles.

Usage: gen_programs.py [--count 300] [--ext-count 100] [--seed 20240601] [--out DIR]
(DIR defaults to /tmp/vcnc_linuxcnc_programs, where make_fixtures.py looks.)

`generate(index, seed)` is importable: it returns (ngc_lines, nc_lines, trace),
where trace is the generator's own idea of the machine end point of every
motion block (both legs of a G28), handy to cross-check the converter.
Numbers from EXT_FIRST (301) on are second-batch programs.
"""

import argparse
import math
import os
import random
import sys

DEFAULT_OUT = "/tmp/vcnc_linuxcnc_programs"
DEFAULT_SEED = 20240601
DEFAULT_COUNT = 300
# The second batch (G28, inch segments) is numbered from here.
EXT_FIRST = 301
DEFAULT_EXT_COUNT = 100

# All geometry is kept in integer units of 0.0001 mm, so that rounding to the
# 4 decimals rs274 prints is exact and G91 increments add up exactly.
U = 10000

# Linear targets are chosen in this machine box ...
MOVE_BOX = [(-300 * U, 300 * U), (-300 * U, 300 * U), (-150 * U, 150 * U)]
# ... and every arc's full circle must stay inside this one.
ARC_BOX = [(-380 * U, 380 * U), (-380 * U, 380 * U), (-180 * U, 180 * U)]
# Work offsets (G54-G59) and the G92 offset are kept within these magnitudes.
OFFSET_MAX = [100 * U, 100 * U, 40 * U]
G92_MAX = [60 * U, 60 * U, 25 * U]

AXES = "XYZ"
# plane -> (first axis, second axis, normal axis) as indices into XYZ; "ccw"
# means a positive rotation from the first towards the second axis.
PLANES = {
    "G17": (0, 1, 2),
    "G18": (2, 0, 1),
    "G19": (1, 2, 0),
}
CENTER_WORD = {0: "I", 1: "J", 2: "K"}
FEEDS = ["F100.0", "F250.0", "F400.0", "F500.0", "F750.0", "F1000.0",
         "F1200.5", "F1500.0", "F2000.0", "F87.5"]


def fmt(u):
    """Integer 0.0001 mm units -> a number that always has a decimal point."""
    sign = "-" if u < 0 else ""
    u = abs(u)
    whole, frac = divmod(u, U)
    frac_s = ("%04d" % frac).rstrip("0") or "0"
    return "%s%d.%s" % (sign, whole, frac_s)


class Program:
    def __init__(self, rng):
        self.rng = rng
        self.pos = [0, 0, 0]                       # machine, units
        self.g5x = {p: [0, 0, 0] for p in range(1, 7)}
        self.active = 1                            # G54
        self.g92 = [0, 0, 0]
        self.absolute = True
        self.plane = "G17"
        self.feed_set = False
        self.ngc = []
        self.nc = []
        self.trace = []          # (line, kind, machine end point)
        self.last_linear = None  # "G0"/"G1" when the previous line may continue modally

    # -- helpers -----------------------------------------------------------
    def offset(self):
        o = self.g5x[self.active]
        return [o[i] + self.g92[i] for i in range(3)]

    def emit(self, ngc, nc=None):
        self.ngc.append(ngc)
        self.nc.append(ngc if nc is None else nc)
        return len(self.ngc)

    def axis_words(self, target, axes):
        """Words for a linear move to machine point `target` on `axes`."""
        off = self.offset()
        words = []
        for i in axes:
            if self.absolute:
                words.append(AXES[i] + fmt(target[i] - off[i]))
            else:
                words.append(AXES[i] + fmt(target[i] - self.pos[i]))
        return words

    def feed_word(self, force=False):
        if not self.feed_set or force:
            self.feed_set = True
            return [self.rng.choice(FEEDS)]
        return []

    def rand_in(self, lo, hi):
        return self.rng.randint(lo, hi)

    # -- blocks ------------------------------------------------------------
    def linear(self):
        rng = self.rng
        code = "G0" if rng.random() < 0.35 else "G1"
        k = rng.choice([1, 2, 3, 3, 3])
        axes = sorted(rng.sample(range(3), k))
        target = list(self.pos)
        for i in axes:
            lo, hi = MOVE_BOX[i]
            if rng.random() < 0.5:
                # a short move near the current point
                d = rng.randint(-20 * U, 20 * U)
                target[i] = min(hi, max(lo, self.pos[i] + d))
            else:
                target[i] = rng.randint(lo, hi)
            if rng.random() < 0.3:          # coarser numbers now and then
                target[i] = (target[i] // 1000) * 1000
        if target == self.pos:
            target[axes[0]] += U if target[axes[0]] < 0 else -U
        words = []
        modal = self.last_linear == code and rng.random() < 0.3
        if not modal:
            if rng.random() < 0.1:
                # distance mode change on the motion line itself
                self.absolute = not self.absolute
                words.append("G90" if self.absolute else "G91")
            words.append(code)
        words += self.axis_words(target, axes)
        if code == "G1":
            words += self.feed_word(force=rng.random() < 0.08)
        line = self.emit(" ".join(words))
        self.trace.append((line, "rapid" if code == "G0" else "feed", list(target)))
        self.pos = target
        self.last_linear = code

    def arc(self):
        rng = self.rng
        words = []
        plane = self.plane
        if rng.random() < 0.3:
            # a plane word on the arc's own line
            plane = rng.choice(sorted(PLANES))
            words.append(plane)
        a, b, n = PLANES[plane]
        S = self.pos
        for _attempt in range(200):
            full = rng.random() < 0.12
            r_form = (not full) and rng.random() < 0.45
            r = rng.uniform(2.0, 90.0) * U
            th0 = rng.uniform(0, 2 * math.pi)
            ca = S[a] - int(round(r * math.cos(th0)))
            cb = S[b] - int(round(r * math.sin(th0)))
            rs = math.hypot(S[a] - ca, S[b] - cb)
            if rs < 1 * U:
                continue
            ccw = rng.random() < 0.5
            if full:
                sweep = 2 * math.pi
            elif r_form:
                deg = rng.choice([rng.uniform(10, 155), rng.uniform(205, 340)])
                sweep = math.radians(deg)
            else:
                sweep = math.radians(rng.uniform(5, 355))
            th_s = math.atan2(S[b] - cb, S[a] - ca)
            th1 = th_s + (sweep if ccw else -sweep)
            E = list(S)
            if not full:
                E[a] = ca + int(round(rs * math.cos(th1)))
                E[b] = cb + int(round(rs * math.sin(th1)))
                re = math.hypot(E[a] - ca, E[b] - cb)
                if abs(re - rs) >= 0.001 * U * 0.5:
                    continue
                if E[a] == S[a] and E[b] == S[b]:
                    continue
            helix = rng.random() < 0.3
            if helix:
                E[n] = S[n] + rng.randint(-20 * U, 20 * U)
            # the whole circle and both normal-axis ends inside the box
            ok = True
            for ax, c in ((a, ca), (b, cb)):
                lo, hi = ARC_BOX[ax]
                if c - rs < lo or c + rs > hi:
                    ok = False
            lo, hi = MOVE_BOX[n]
            if not (lo <= E[n] <= hi):
                ok = False
            if not ok:
                continue
            if r_form:
                chord = math.hypot(E[a] - S[a], E[b] - S[b])
                R = int(round(rs))
                if chord > 0.99 * 2 * R or chord < 1 * U:
                    continue
                big = sweep > math.pi
            break
        else:
            return self.linear()
        self.plane = plane
        words.append("G3" if ccw else "G2")
        off = self.offset()
        for ax in sorted((a, b)) + ([n] if helix else []):
            if self.absolute:
                words.append(AXES[ax] + fmt(E[ax] - off[ax]))
            else:
                words.append(AXES[ax] + fmt(E[ax] - S[ax]))
        if r_form:
            words.append("R" + fmt(-R if big else R))
        else:
            for ax, c in sorted(((a, ca), (b, cb))):
                words.append(CENTER_WORD[ax] + fmt(c - S[ax]))
        words += self.feed_word(force=rng.random() < 0.08)
        line = self.emit(" ".join(words))
        self.trace.append((line, "arc", list(E)))
        self.pos = E
        self.last_linear = None

    def dwell(self):
        s = self.rng.choice(["0.1", "0.25", "0.5", "1.0", "1.5", "2.0", "0.05", "3.0"])
        self.emit("G4 P" + s, "G4 X" + s)
        self.last_linear = None

    def set_g10(self):
        if not self.absolute:
            return self.toggle_distance(force_abs=True)
        p = self.rng.randint(1, 6)
        val = [self.rng.randint(-m, m) for m in OFFSET_MAX]
        if self.rng.random() < 0.3:
            val = [(v // 10000) * 10000 for v in val]
        self.g5x[p] = val
        self.emit("G10 L2 P%d X%s Y%s Z%s" % (p, fmt(val[0]), fmt(val[1]), fmt(val[2])))
        self.last_linear = None

    def preset_g92(self):
        if not self.absolute:
            return self.toggle_distance(force_abs=True)
        new = [self.rng.randint(-m, m) for m in G92_MAX]
        if self.rng.random() < 0.25:
            new = [0, 0, 0]
        o = self.g5x[self.active]
        val = [self.pos[i] - o[i] - new[i] for i in range(3)]
        self.g92 = new
        self.emit("G92 X%s Y%s Z%s" % (fmt(val[0]), fmt(val[1]), fmt(val[2])))
        self.last_linear = None

    def select_wcs(self):
        p = self.rng.randint(1, 6)
        self.active = p
        self.emit("G%d" % (53 + p))
        self.last_linear = None

    def move_g53(self):
        if not self.absolute:
            return self.toggle_distance(force_abs=True)
        rng = self.rng
        k = rng.choice([1, 2, 3, 3])
        axes = sorted(rng.sample(range(3), k))
        target = list(self.pos)
        for i in axes:
            lo, hi = MOVE_BOX[i]
            target[i] = rng.randint(lo, hi)
        if target == self.pos:
            target[axes[0]] += U if target[axes[0]] < 0 else -U
        words = ["G53", "G0"] + [AXES[i] + fmt(target[i]) for i in axes]
        line = self.emit(" ".join(words))
        self.trace.append((line, "rapid", list(target)))
        self.pos = target
        self.last_linear = None   # G53 is one-shot; do not continue modally

    def toggle_distance(self, force_abs=False):
        self.absolute = True if force_abs else not self.absolute
        self.emit("G90" if self.absolute else "G91")
        self.last_linear = None

    def select_plane(self):
        self.plane = self.rng.choice(sorted(PLANES))
        self.emit(self.plane)
        self.last_linear = None


# -- second batch: G28 and inch segments ------------------------------------
#
# rs274 prints every length in the units in force, with 4 decimals. In inch a
# 4-decimal print is 0.00254 mm coarse, so inside an inch segment every value
# rs274 prints (all three axes of every end point, the offsets it reports)
# must be exact in BOTH units: a multiple of 0.0005 in = 0.0127 mm = 127 of our
# units. The second batch therefore keeps
#   * every work offset and the G92 offset on that grid, always (values set in
#     mm too, since an inch segment may select or print them later);
#   * the machine point on the grid when G20 takes effect: if it is not, a mm
#     move to a grid point comes first;
#   * every point, centre and increment inside an inch segment on the grid.
# Then program coordinates are grid values too, the inch words have at most 4
# decimals, and the mm numbers after G21 are exact again. The only inexact
# prints left are the centres rs274 computes for R arcs (0.0001 in, i.e.
# 0.00127 mm at most).
#
# Feeds: F is always written on the first G1/G2/G3 after a unit change, and
# G20/G21 never share a block with F. LinuxCNC executes F before G20/G21 in a
# block, and on a unit change its motion layer keeps the physical feed (the
# interpreter re-reads it with GET_EXTERNAL_FEED_RATE) while vcnc keeps F's
# number: a feed carried across a unit change is not defined the same way.

INCH_GRID = 127            # 0.0005 in = 0.0127 mm, in 0.0001 mm units
INCH_FEEDS = ["F4.0", "F10.0", "F15.5", "F20.0", "F25.0", "F39.37", "F60.0",
              "F3.5", "F7.25", "F50.0"]


def fmt_in(u):
    """Integer 0.0001 mm units on INCH_GRID -> inches with a decimal point."""
    if u % INCH_GRID:
        raise ValueError("%d is not a multiple of 0.0005 in" % u)
    return fmt(u // INCH_GRID * 5)     # 0.0001 in units print like 0.0001 mm


def snap(u, g, lo=None, hi=None):
    """Nearest multiple of g, kept inside [lo, hi] when given."""
    v = (u + g // 2) // g * g
    if hi is not None and v > hi:
        v -= g
    if lo is not None and v < lo:
        v += g
    return v


class MixedProgram(Program):
    """Second-batch program: Program's blocks plus G28 and G20/G21 segments."""

    def __init__(self, rng):
        super().__init__(rng)
        self.inch = False

    def grid(self):
        return INCH_GRID if self.inch else 1

    def L(self, u):
        """A length (0.0001 mm units) as a word value in the current units."""
        return fmt_in(u) if self.inch else fmt(u)

    def check_offsets(self):
        for o in list(self.g5x.values()) + [self.g92]:
            assert all(v % INCH_GRID == 0 for v in o), o

    def axis_words(self, target, axes):
        off = self.offset()
        words = []
        for i in axes:
            if self.absolute:
                words.append(AXES[i] + self.L(target[i] - off[i]))
            else:
                words.append(AXES[i] + self.L(target[i] - self.pos[i]))
        return words

    def feed_word(self, force=False):
        if not self.feed_set or force:
            self.feed_set = True
            return [self.rng.choice(INCH_FEEDS if self.inch else FEEDS)]
        return []

    def linear(self, grid=None, must=(), prefix=None, code=None):
        """G0/G1. `grid`: targets on that grid (default: the units' grid);
        `must`: axes that have to be named; `prefix`: a word put first (G20/G21)."""
        rng = self.rng
        g = grid or self.grid()
        if code is None:
            code = "G0" if rng.random() < 0.35 else "G1"
        k = rng.choice([1, 2, 3, 3, 3])
        axes = sorted(set(rng.sample(range(3), k)) | set(must))
        target = list(self.pos)
        for i in axes:
            lo, hi = MOVE_BOX[i]
            if rng.random() < 0.5:
                d = rng.randint(-20 * U, 20 * U)
                t = min(hi, max(lo, self.pos[i] + d))
            else:
                t = rng.randint(lo, hi)
            if rng.random() < 0.3:          # coarser numbers now and then
                step = 2540 if (self.inch or g != 1) else 1000   # 0.01 in / 0.1 mm
                t = (t // step) * step
            target[i] = snap(t, g, lo, hi)
        if target == self.pos:
            i = axes[0]
            target[i] += g * (1 if target[i] < 0 else -1) * (1 if g != 1 else U)
        words = [prefix] if prefix else []
        modal = (prefix is None and self.last_linear == code
                 and rng.random() < 0.3)
        if not modal:
            if rng.random() < 0.1:
                self.absolute = not self.absolute
                words.append("G90" if self.absolute else "G91")
            words.append(code)
        words += self.axis_words(target, axes)
        if code == "G1":
            words += self.feed_word(force=rng.random() < 0.08)
        line = self.emit(" ".join(words))
        self.trace.append((line, "rapid" if code == "G0" else "feed", list(target)))
        self.pos = target
        self.last_linear = code

    def arc(self):
        rng = self.rng
        g = self.grid()
        words = []
        plane = self.plane
        if rng.random() < 0.3:
            plane = rng.choice(sorted(PLANES))
            words.append(plane)
        a, b, n = PLANES[plane]
        S = self.pos
        for _attempt in range(300):
            full = rng.random() < 0.12
            r_form = (not full) and rng.random() < 0.45
            r = rng.uniform(2.0, 90.0) * U
            th0 = rng.uniform(0, 2 * math.pi)
            ca = snap(S[a] - int(round(r * math.cos(th0))), g)
            cb = snap(S[b] - int(round(r * math.sin(th0))), g)
            rs = math.hypot(S[a] - ca, S[b] - cb)
            if rs < 1 * U:
                continue
            ccw = rng.random() < 0.5
            th_s = math.atan2(S[b] - cb, S[a] - ca)
            E = list(S)
            found = full
            # on the inch grid few end points lie on the circle: try angles
            for _try in range(0 if full else 60):
                if r_form:
                    deg = rng.choice([rng.uniform(10, 155), rng.uniform(205, 340)])
                    sweep = math.radians(deg)
                else:
                    sweep = math.radians(rng.uniform(5, 355))
                th1 = th_s + (sweep if ccw else -sweep)
                E[a] = ca + snap(int(round(rs * math.cos(th1))), g)
                E[b] = cb + snap(int(round(rs * math.sin(th1))), g)
                re = math.hypot(E[a] - ca, E[b] - cb)
                if abs(re - rs) >= 0.001 * U * 0.5:
                    continue
                if E[a] == S[a] and E[b] == S[b]:
                    continue
                found = True
                break
            if not found:
                continue
            if full:
                sweep = 2 * math.pi
            helix = rng.random() < 0.3
            E[n] = S[n]
            if helix:
                E[n] = S[n] + snap(rng.randint(-20 * U, 20 * U), g)
            ok = True
            for ax, c in ((a, ca), (b, cb)):
                lo, hi = ARC_BOX[ax]
                if c - rs < lo or c + rs > hi:
                    ok = False
            lo, hi = MOVE_BOX[n]
            if not (lo <= E[n] <= hi):
                ok = False
            if not ok:
                continue
            if r_form:
                chord = math.hypot(E[a] - S[a], E[b] - S[b])
                R = snap(int(round(rs)), g)
                if chord > 0.99 * 2 * R or chord < 1 * U:
                    continue
                big = sweep > math.pi
            break
        else:
            return self.linear()
        self.plane = plane
        words.append("G3" if ccw else "G2")
        off = self.offset()
        for ax in sorted((a, b)) + ([n] if helix else []):
            if self.absolute:
                words.append(AXES[ax] + self.L(E[ax] - off[ax]))
            else:
                words.append(AXES[ax] + self.L(E[ax] - S[ax]))
        if r_form:
            words.append("R" + self.L(-R if big else R))
        else:
            for ax, c in sorted(((a, ca), (b, cb))):
                words.append(CENTER_WORD[ax] + self.L(c - S[ax]))
        words += self.feed_word(force=rng.random() < 0.08)
        line = self.emit(" ".join(words))
        self.trace.append((line, "arc", list(E)))
        self.pos = E
        self.last_linear = None

    def set_g10(self):
        if not self.absolute:
            return self.toggle_distance(force_abs=True)
        rng = self.rng
        p = rng.randint(1, 6)
        val = [snap(rng.randint(-m, m), INCH_GRID, -m, m) for m in OFFSET_MAX]
        if rng.random() < 0.3:               # whole 0.1 in / 1.27 mm
            step = 25400 if self.inch else 12700
            val = [(v // step) * step for v in val]
        self.g5x[p] = val
        self.check_offsets()
        self.emit("G10 L2 P%d X%s Y%s Z%s"
                  % (p, self.L(val[0]), self.L(val[1]), self.L(val[2])))
        self.last_linear = None

    def preset_g92(self):
        if not self.absolute:
            return self.toggle_distance(force_abs=True)
        rng = self.rng
        new = [snap(rng.randint(-m, m), INCH_GRID, -m, m) for m in G92_MAX]
        if rng.random() < 0.25:
            new = [0, 0, 0]
        o = self.g5x[self.active]
        val = [self.pos[i] - o[i] - new[i] for i in range(3)]
        self.g92 = new
        self.check_offsets()
        self.emit("G92 X%s Y%s Z%s" % (self.L(val[0]), self.L(val[1]), self.L(val[2])))
        self.last_linear = None

    def move_g53(self):
        if not self.absolute:
            return self.toggle_distance(force_abs=True)
        rng = self.rng
        g = self.grid()
        k = rng.choice([1, 2, 3, 3])
        axes = sorted(rng.sample(range(3), k))
        target = list(self.pos)
        for i in axes:
            lo, hi = MOVE_BOX[i]
            target[i] = snap(rng.randint(lo, hi), g, lo, hi)
        if target == self.pos:
            i = axes[0]
            target[i] += (g if g != 1 else U) * (1 if target[i] < 0 else -1)
        words = ["G53", "G0"] + [AXES[i] + self.L(target[i]) for i in axes]
        line = self.emit(" ".join(words))
        self.trace.append((line, "rapid", list(target)))
        self.pos = target
        self.last_linear = None

    def g28(self):
        """G28 with axis words: rapid to the intermediate point (named axes,
        G90 or G91), then the named axes to reference point 1 = machine 0."""
        rng = self.rng
        g = self.grid()
        words = []
        r = rng.random()
        if r < 0.25:
            # the classic `G91 G28 Z0.` spelling: incremental zero, so the
            # intermediate point is where the tool already is
            self.absolute = False
            words.append("G91")
        elif r < 0.35:
            self.absolute = not self.absolute
            words.append("G90" if self.absolute else "G91")
        k = rng.choice([1, 1, 2, 3])
        axes = sorted(rng.sample(range(3), k))
        mid = list(self.pos)
        zero = r < 0.25 or rng.random() < 0.1
        for i in axes:
            lo, hi = MOVE_BOX[i]
            if zero:
                continue
            if rng.random() < 0.5:
                t = min(hi, max(lo, self.pos[i] + rng.randint(-50 * U, 50 * U)))
            else:
                t = rng.randint(lo, hi)
            mid[i] = snap(t, g, lo, hi)
        words.append("G28")
        words += self.axis_words(mid, axes)
        line = self.emit(" ".join(words))
        home = list(mid)
        for i in axes:
            home[i] = 0                     # reference point 1: machine 0
        self.trace.append((line, "rapid", list(mid)))
        self.trace.append((line, "rapid", list(home)))
        self.pos = home
        self.last_linear = None

    def toggle_units(self):
        """Start (G20) or end (G21) an inch segment."""
        rng = self.rng
        if not self.inch:
            self.check_offsets()
            off_grid = [i for i in range(3) if self.pos[i] % INCH_GRID]
            if off_grid:
                # bring the machine point onto the grid while still in mm
                self.linear(grid=INCH_GRID, must=off_grid)
        self.inch = not self.inch
        self.feed_set = False               # F again on the next cutting move
        word = "G20" if self.inch else "G21"
        if rng.random() < 0.3:
            self.linear(prefix=word, code="G0")
        else:
            self.emit(word)
            self.last_linear = None


def feature_weights(rng, p, extra=None):
    """The block kinds and their weights, one of them doubled so that some
    programs lean on one feature (draws from `rng` in a fixed order)."""
    weights = {
        p.linear: 30,
        p.arc: 30,
        p.dwell: 3,
        p.set_g10: 4,
        p.preset_g92: 3,
        p.select_wcs: 5,
        p.move_g53: 3,
        p.toggle_distance: 5,
        p.select_plane: 4,
    }
    weights.update(extra or {})
    favourite = rng.choice(list(weights))
    weights[favourite] *= 2
    funcs = list(weights)
    return funcs, [weights[f] for f in funcs]


def generate_ext(index, seed=DEFAULT_SEED):
    """A second-batch program: the first batch's blocks, G28 and inch segments."""
    rng = random.Random("%d:%d" % (seed, index))
    p = MixedProgram(rng)
    p.emit("G21 G17 G90 G94")
    n_blocks = rng.randint(30, 80)
    funcs, w = feature_weights(rng, p, {p.g28: 4})
    # 1-3 inch segments, each at least a few blocks long
    segments = rng.choice([1, 1, 2, 2, 3])
    marks = sorted(rng.sample(range(3, n_blocks - 2), 2 * segments))
    for i in range(1, len(marks)):
        marks[i] = max(marks[i], marks[i - 1] + 4)
    while len(p.ngc) < n_blocks:
        if marks and len(p.ngc) >= marks[0]:
            marks.pop(0)
            p.toggle_units()
            continue
        rng.choices(funcs, w)[0]()
    if p.inch:
        p.emit("G21")          # the segment ends before the program does
        p.inch = False
    p.emit("M2")
    return p.ngc, p.nc, p.trace


def generate(index, seed=DEFAULT_SEED):
    if index >= EXT_FIRST:
        return generate_ext(index, seed)
    rng = random.Random("%d:%d" % (seed, index))
    p = Program(rng)
    p.emit("G21 G17 G90 G94")
    n_blocks = rng.randint(20, 75)
    funcs, w = feature_weights(rng, p)
    while len(p.ngc) < n_blocks:
        rng.choices(funcs, w)[0]()
    p.emit("M2")
    return p.ngc, p.nc, p.trace


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, default=DEFAULT_COUNT,
                    help="first-batch programs, numbered from 1")
    ap.add_argument("--ext-count", type=int, default=DEFAULT_EXT_COUNT,
                    help="second-batch programs (G28, inch), numbered from %d" % EXT_FIRST)
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED)
    ap.add_argument("--out", default=DEFAULT_OUT)
    args = ap.parse_args(argv)
    if args.count >= EXT_FIRST:
        ap.error("--count must stay below %d, where the second batch starts" % EXT_FIRST)
    os.makedirs(args.out, exist_ok=True)
    for name in os.listdir(args.out):
        if name.endswith((".nc", ".ngc")):
            os.remove(os.path.join(args.out, name))
    numbers = list(range(1, args.count + 1))
    numbers += list(range(EXT_FIRST, EXT_FIRST + args.ext_count))
    for i in numbers:
        ngc, nc, _ = generate(i, args.seed)
        assert len(ngc) == len(nc)
        for ext, lines in (("ngc", ngc), ("nc", nc)):
            with open(os.path.join(args.out, "%03d.%s" % (i, ext)), "w") as f:
                f.write("\n".join(lines) + "\n")
    print("wrote %d + %d programs (x2 spellings) to %s"
          % (args.count, args.ext_count, args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
