#!/usr/bin/env python3
"""Generate the grbl-style programs of tests/fixtures/linuxcnc_grbl.

The programs look like what hobby CAM sends to grbl 1.1 — `;` comments to
the end of the line and `( )` comments, integers without a decimal point
(whole mm or inches: `X5` is 5 mm) mixed with decimals, `G00`/`G0`, lines
without blanks (`G1X5Y3F300`), modal lines without a G word — and use the
part of grbl's G-code that LinuxCNC's rs274 defines the same way:

  * G0/G1, G2/G3 with I/J/K (incremental, G91.1) and R (negative R over
    180 degrees), I/J/K full circles and helices, in G17/G18/G19;
  * G90/G91 (incremental stretches), G20/G21 (inch segments, or a program
    in inches from the start), F in units/min (G94) and inverse time (G93,
    F on every G1/G2/G3 block);
  * G10 L2 and L20 with P0 (the active system) to P6 and any subset of
    X/Y/Z, also under G91 (absolute in both), G54-G59, G92 (also under G91,
    any subset of axes), G92.1, G53 G0;
  * G28/G30 with and without axis words, G28.1/G30.1 storing the position;
  * G43.1 Z (dynamic tool length offset, also while G91 is on) and G49;
  * G4 P<seconds>, M3/M4/M5 with S, S changes while turning, M7/M8/M9,
    M0 (with the spindle and coolant off), M1, T<n> (no M6), M2/M30.

Both spellings are the same text: NNN.nc (vcnc, `--dialect grbl`) and
NNN.ngc (rs274) are identical, line 1 `(vcnc-args: --dialect grbl)` (with
`--optional-stop` for a quarter of the programs, so that M1 stops).

What the generator keeps out of (see tests/fixtures/linuxcnc_grbl/README.md):

  * a feed carried across G20/G21: the first G1/G2/G3 after a unit change
    has its own F and F never shares a block with G20/G21 (grbl and
    LinuxCNC keep the physical feed, vcnc's Fanuc dialects keep F's number);
  * G93 in inches (rs274 prints the equivalent feed in in/min to 4
    decimals, 0.00127 mm/min coarse once converted), and I/J/K arcs under
    G93 whose end point is not exactly on the circle (the path length, so
    the feed, would depend on which radius a controller takes): under G93
    the end vector is the start vector turned by a multiple of 90 degrees
    or mirrored on an axis or a diagonal, or the arc is in R form;
  * G53 under G91 (an error in LinuxCNC, machine coordinates in grbl);
  * a tool length offset across a unit change: G49 comes first (rs274
    keeps the offset's number and later takes it in the new units;
    GrblProgram.toggle_units);
  * G28.1/G30.1 with axis words, G43.1 with other words, M0 with the
    spindle or coolant on (controllers differ on what M0 stops), M3/M4 in
    the direction the spindle already turns;
  * anything printed in inches that is not exact in mm: as in the second
    batch of tests/fixtures/linuxcnc, inside inch segments every point and
    offset is a multiple of 0.0005 in, all offsets (G5x, G92, G43.1) are on
    that grid always, and G28/G30 go to a stored position in inches only
    when it is on the grid (the power-on G30 position 200,150,0 mm is not).

The G28/G30 positions at power-on are the built-in mill's reference points
p1 (0,0,0) and p2 (200,150,0) (crates/vcnc_core/src/default_mill.toml);
VAR_TEXT gives rs274 the same in its parameters 5161-5163 / 5181-5183
(in inches, like its tool table).

All geometry is integer 0.0001 mm units (gen_programs.U). `generate()`
returns (lines, trace, frames, feeds): trace = (line, kind, machine end
point) of every motion (one rapid for a G28/G30 without axis words, two
with), frames = (line, origin, tool length) of every block that changes
what a `frame` event reports, feeds = (line, mm/min) of every G93 move;
make_ext_fixtures.py --set grbl checks rs274's output against all three.

Usage: gen_grbl.py [--count 80] [--seed 20240901] [--out DIR]
"""

import argparse
import math
import os
import random
import sys

import gen_programs as gp
from gen_programs import (ARC_BOX, AXES, CENTER_WORD, INCH_GRID, MOVE_BOX,
                          OFFSET_MAX, G92_MAX, PLANES, U, snap)

DEFAULT_SEED = 20240901
DEFAULT_COUNT = 80
DEFAULT_OUT = "/tmp/vcnc_linuxcnc_grbl"
ARGS_LINE = "(vcnc-args: --dialect grbl)"
ARGS_LINE_OPT = "(vcnc-args: --dialect grbl --optional-stop)"

# G28 and G30 positions at power-on, machine coordinates (default_mill.toml
# [reference] p1 and p2).
HOME_START = {"G28": [0, 0, 0], "G30": [200 * U, 150 * U, 0]}
# rs274's parameter file: the same positions in inches (12 decimals, so that
# 25.4 x the value prints as the exact mm value).
VAR_TEXT = "".join("%d\t%.12f\n" % (5161 + k, HOME_START["G28"][k] / U / 25.4)
                   for k in range(3)) + \
    "".join("%d\t%.12f\n" % (5181 + k, HOME_START["G30"][k] / U / 25.4)
            for k in range(3))
# T words need the tool in rs274's table: n -> (length mm, radius mm).
TOOLS = {1: (0.0, 1.5875), 2: (0.0, 3.175), 3: (0.0, 0.5)}

MM_FEEDS = [100, 250, 300, 400, 500, 600, 750, 800, 1000, 1200, 1500, 2000,
            87.5, 1200.5, 333.3]
INCH_FEEDS = [4, 10, 15.5, 20, 25, 39.37, 60, 3.5, 7.25, 50, 12]
# Inverse-time F values (1/min); one is picked so that the move's
# equivalent feed stays between 20 and 4000 mm/min.
INVERSE_F = [0.5, 1, 1.5, 2, 2.5, 4, 5, 6, 8, 10, 12, 15, 20, 25, 30, 40, 50,
             60, 75, 100, 120, 150, 200, 250, 300, 400, 500, 750, 1000]
RPMS = [8000, 10000, 12000, 16000, 18000, 24000, 1000, 2500, 5000, 9999]
DWELLS = [0.1, 0.25, 0.5, 1, 1.5, 2, 3, 0.05]       # seconds

# Comments in our own words, the kind CAM output carries. None starts with a
# word LinuxCNC gives a meaning to (MSG, DEBUG, PRINT, LOG..., PROBE...).
COMMENTS = [
    "Pocket1", "Contour 2", "Facing", "Engrave text", "Drill holes",
    "Layer 1", "Layer 2 of 3", "Pass 3", "rapid to safe height",
    "plunge", "retract", "tab", "lead-in", "finishing pass", "outline",
    "tool: 1/8 in flat end mill", "tool 2 - 6 mm ball", "spindle on",
    "coolant", "work zero at stock corner", "stock 100 x 80 x 12",
    "set offsets", "go home", "park", "inverse time block",
    "units: mm", "units: inch", "relative moves", "arc fitting on",
]
HEADERS = [
    "Generated by vcnc gen_grbl.py, program %03d",
    "vcnc gen_grbl.py test program %03d",
    "grbl-style test program %03d",
]


class Style:
    """How one program spells things: the habits of one CAM post."""

    def __init__(self, rng):
        self.rng = rng
        # minimal: 5, 2.5 / point: 5., 2.5 / fixed: 5.000 / mixed: any
        self.numbers = rng.choice(["minimal", "minimal", "fixed", "point", "mixed"])
        self.decimals = rng.choice([3, 4])
        self.lead_zero = rng.random() < 0.7        # 0.5 or .5
        self.padded = rng.random() < 0.35          # G00 G01 M03
        self.compact = rng.random() < 0.2          # G1X5Y3F300
        self.comment_rate = rng.choice([0.0, 0.04, 0.1, 0.2])
        self.semicolon = rng.random() < 0.75       # ; comments, else ( )
        self.whole_rate = rng.choice([0.15, 0.35, 0.6])

    def number(self, v):
        """Integer count of 0.0001 units (mm, inch, s, 1/min) -> text."""
        sign = "-" if v < 0 else ""
        whole, frac = divmod(abs(v), 10000)
        digits = ("%04d" % frac).rstrip("0")
        mode = self.numbers
        if mode == "mixed":
            mode = self.rng.choice(["minimal", "point", "fixed"])
        if mode == "minimal":
            s = "%d.%s" % (whole, digits) if digits else "%d" % whole
        elif mode == "point":
            s = "%d.%s" % (whole, digits)
        else:
            s = "%d.%s" % (whole, digits.ljust(self.decimals, "0"))
        if not self.lead_zero and s.startswith("0.") and len(s) > 2:
            s = s[1:]
        return sign + s if v else s

    def comment(self):
        text = self.rng.choice(COMMENTS)
        return ("; " if self.rng.random() < 0.7 else ";") + text \
            if self.semicolon else "(" + text + ")"


def pad(word, style):
    """G0..G4 and M0..M9 as G00 / M03 when the post pads them."""
    if style.padded and len(word) == 2 and word[0] in "GM" and word[1].isdigit():
        if word[0] == "M" or word[1] in "01234":
            return word[0] + "0" + word[1]
    return word


class GrblProgram(gp.MixedProgram):
    """gen_programs' blocks (G0/G1, arcs, G10, G92, G53, G54-G59, planes,
    G90/G91, G20/G21 segments) in grbl style, plus grbl's own blocks."""

    def __init__(self, rng, style):
        super().__init__(rng)
        self.style = style
        self.tlo = 0                               # G43.1 Z, 0.0001 mm
        self.stored = {k: list(v) for k, v in HOME_START.items()}
        self.frames = []
        self.reported = ([0, 0, 0], 0)
        self.feeds = []                            # (line, mm/min) under G93
        self.spindle = "stop"
        self.coolant = False
        self.optional_stop = False
        self.inverse = False                       # G93 on

    # -- spelling -------------------------------------------------------------
    def L(self, u):
        """A length in the units in force, spelled in the program's style."""
        if self.inch:
            if u % INCH_GRID:
                raise ValueError("%d is not a multiple of 0.0005 in" % u)
            return self.style.number(u // INCH_GRID * 5)
        return self.style.number(u)

    def value(self, x):
        """A plain number (feed, seconds, 1/min) in the program's style."""
        return self.style.number(int(round(x * 10000)))

    def emit(self, text, nc=None, raw=False):
        """One line; unless `raw`, in the program's style with now and then
        a comment. Records a frame when the block changed the offsets."""
        st = self.style
        if not raw:
            words = [pad(w, st) for w in text.split(" ")]
            text = ("" if st.compact else " ").join(words)
            r = self.rng.random()
            if r < st.comment_rate:
                c = st.comment()
                text = text + ("" if st.compact and c[0] == ";" else " ") + c
            elif r < st.comment_rate * 1.15 and not st.semicolon:
                text = st.comment() + " " + text
        line = super().emit(text)
        o = self.g5x[self.active]
        state = ([o[i] + self.g92[i] for i in range(3)], self.tlo)
        if state != self.reported:
            self.frames.append((line, list(state[0]), state[1]))
            self.reported = state
        return line

    def comment_line(self):
        self.emit(self.style.comment(), raw=True)

    def feed_word(self, force=False):
        if not self.feed_set or force:
            self.feed_set = True
            return ["F" + self.value(self.rng.choice(INCH_FEEDS if self.inch else MM_FEEDS))]
        return []

    # machine = program + G5x + G92 + tool length offset (Z)
    def offset(self):
        o = super().offset()
        return [o[0], o[1], o[2] + self.tlo]

    def check_offsets(self):
        super().check_offsets()
        assert self.tlo % INCH_GRID == 0, self.tlo

    # -- motion ------------------------------------------------------------------
    def pick(self, i, g):
        """A target on axis i: near the tool or anywhere, often whole units."""
        rng = self.rng
        lo, hi = MOVE_BOX[i]
        if rng.random() < 0.5:
            t = min(hi, max(lo, self.pos[i] + rng.randint(-20 * U, 20 * U)))
        else:
            t = rng.randint(lo, hi)
        if rng.random() < self.style.whole_rate:
            # whole mm / whole 0.1 in in program coordinates (no decimal
            # point in "minimal" style); machine = program + offset
            step = 254000 if self.inch else U      # 1 in / 1 mm
            if rng.random() < 0.3:
                step //= 10
            off = 0 if not self.absolute else self.offset()[i]
            base = self.pos[i] if not self.absolute else off
            t = base + (t - base) // step * step
            t = min(hi, max(lo, t))
        return snap(t, g, lo, hi)

    def linear(self, grid=None, must=(), prefix=None, code=None):
        """G0/G1 (gen_programs.MixedProgram.linear with grbl-style targets
        and, now and then, F on a G0 line as some posts write it)."""
        rng = self.rng
        g = grid or self.grid()
        if code is None:
            code = "G0" if rng.random() < 0.35 else "G1"
        k = rng.choice([1, 2, 3, 3])
        axes = sorted(set(rng.sample(range(3), k)) | set(must))
        target = list(self.pos)
        for i in axes:
            target[i] = self.pick(i, g)
        if target == self.pos:
            i = axes[0]
            target[i] += g * (1 if target[i] < 0 else -1) * (1 if g != 1 else U)
        words = [prefix] if prefix else []
        modal = (prefix is None and self.last_linear == code and rng.random() < 0.4)
        if not modal:
            if rng.random() < 0.08:
                self.absolute = not self.absolute
                words.append("G90" if self.absolute else "G91")
            words.append(code)
        words += self.axis_words(target, axes)
        if code == "G1":
            words += self.feed_word(force=rng.random() < 0.08)
        elif prefix is None and not self.inverse and rng.random() < 0.05:
            words += self.feed_word(force=True)      # F on a rapid sets the feed
        line = self.emit(" ".join(words))
        self.trace.append((line, "rapid" if code == "G0" else "feed", list(target)))
        self.pos = target
        self.last_linear = code

    def incremental_stretch(self):
        """G91, a few moves and arcs, G90: the relative moves of an
        engraving or a repeated pocket."""
        if self.absolute:
            self.toggle_distance()
        for _ in range(self.rng.randint(2, 6)):
            (self.arc if self.rng.random() < 0.4 else self.linear)()
        if not self.absolute:
            self.toggle_distance(force_abs=True)

    # -- offsets -------------------------------------------------------------------
    def set_g10(self):
        """G10 L2 (the offset) or L20 (the offset that makes the current
        point the given one) of P0 (the active system) to P6, any subset of
        axes, under G90 or (absolute in grbl and LinuxCNC alike) G91."""
        rng = self.rng
        if not self.absolute and rng.random() < 0.5:
            return self.toggle_distance(force_abs=True)
        p = rng.choice([0, 1, 2, 3, 4, 5, 6, 1, 2])
        sys_n = self.active if p == 0 else p
        axes = sorted(rng.sample(range(3), rng.choice([1, 2, 3, 3, 3])))
        l20 = rng.random() < 0.45
        new = list(self.g5x[sys_n])
        words = ["G10", "L20" if l20 else "L2", "P%d" % p]
        for i in axes:
            m = OFFSET_MAX[i]
            v = snap(rng.randint(-m, m), INCH_GRID, -m, m)
            if rng.random() < 0.4:
                v = v // 127000 * 127000            # whole 10 mm / 0.5 in
            new[i] = v
            if l20:
                # the given value is the current point in the new system
                tl = self.tlo if i == 2 else 0
                words.append(AXES[i] + self.L(self.pos[i] - self.g92[i] - tl - v))
            else:
                words.append(AXES[i] + self.L(v))
        self.g5x[sys_n] = new
        self.check_offsets()
        self.emit(" ".join(words))
        self.last_linear = None

    def preset_g92(self):
        """G92 on any subset of axes (the others keep their G92 offset),
        now and then under G91 (absolute in grbl and LinuxCNC), or G92.1."""
        rng = self.rng
        if rng.random() < 0.2 and any(self.g92):
            self.g92 = [0, 0, 0]
            self.emit("G92.1")
            self.last_linear = None
            return
        if not self.absolute and rng.random() < 0.5:
            return self.toggle_distance(force_abs=True)
        axes = sorted(rng.sample(range(3), rng.choice([1, 2, 3, 3])))
        words = ["G92"]
        o = self.g5x[self.active]
        for i in axes:
            m = G92_MAX[i]
            new = 0 if rng.random() < 0.2 else snap(rng.randint(-m, m), INCH_GRID, -m, m)
            tl = self.tlo if i == 2 else 0
            self.g92[i] = new
            words.append(AXES[i] + self.L(self.pos[i] - o[i] - tl - new))
        self.check_offsets()
        self.emit(" ".join(words))
        self.last_linear = None

    def tool_length(self):
        """G43.1 Z<length> (dynamic tool length offset) or G49."""
        rng = self.rng
        if self.tlo and rng.random() < 0.35:
            self.tlo = 0
            self.emit("G49")
        else:
            v = self.tlo
            while v == self.tlo:
                v = snap(rng.randint(-50 * U, 50 * U), INCH_GRID, -50 * U, 50 * U)
                if rng.random() < 0.4:
                    v = v // 127000 * 127000
            self.tlo = v
            self.emit("G43.1 Z" + self.L(v))
        self.last_linear = None

    # -- G28 / G30 ----------------------------------------------------------------
    def store_home(self):
        """G28.1 / G30.1: the current machine point becomes the position."""
        code = self.rng.choice(["G28", "G30"])
        self.stored[code] = list(self.pos)
        self.emit(code + ".1")
        self.last_linear = None

    def on_grid(self, p):
        return all(v % INCH_GRID == 0 for v in p)

    def home(self):
        """G28/G30 without axis words (all axes straight to the stored
        position) or with them (the named axes through the intermediate
        point, G90 or G91, then to the stored position)."""
        rng = self.rng
        codes = ["G28", "G30"]
        rng.shuffle(codes)
        if self.inch:
            codes = [c for c in codes if self.on_grid(self.stored[c])]
            if not codes:
                return self.linear()
        code = codes[0]
        stored = self.stored[code]
        words = []
        if rng.random() < 0.45:
            if rng.random() < 0.15:
                self.absolute = not self.absolute
                words.append("G90" if self.absolute else "G91")
            line = self.emit(" ".join(words + [code]))
            self.trace.append((line, "rapid", list(stored)))
            self.pos = list(stored)
            self.last_linear = None
            return
        g = self.grid()
        r = rng.random()
        if r < 0.25:
            # the `G91 G28 Z0` idiom: the intermediate point is the tool's
            self.absolute = False
            words.append("G91")
        elif r < 0.35:
            self.absolute = not self.absolute
            words.append("G90" if self.absolute else "G91")
        axes = sorted(rng.sample(range(3), rng.choice([1, 1, 2, 3])))
        mid = list(self.pos)
        if not (r < 0.25 or rng.random() < 0.1):
            for i in axes:
                mid[i] = self.pick(i, g)
        words.append(code)
        words += self.axis_words(mid, axes)
        line = self.emit(" ".join(words))
        home = list(mid)
        for i in axes:
            home[i] = stored[i]
        self.trace.append((line, "rapid", list(mid)))
        self.trace.append((line, "rapid", list(home)))
        self.pos = home
        self.last_linear = None

    # -- inverse time ---------------------------------------------------------------
    def inverse_f(self, length_mm):
        """An F (1/min) giving 20-4000 mm/min on a move of `length_mm`."""
        ok = [f for f in INVERSE_F if 20 <= f * length_mm <= 4000]
        if not ok:
            ok = [min(INVERSE_F, key=lambda f: abs(math.log(f * length_mm / 500)))]
        return self.rng.choice(ok)

    def inverse_line(self, prefix):
        rng = self.rng
        k = rng.choice([1, 2, 3, 3])
        axes = sorted(rng.sample(range(3), k))
        target = list(self.pos)
        for i in axes:
            target[i] = self.pick(i, 1)
        if target == self.pos:
            target[axes[0]] += U
        length = math.dist(target, self.pos) / U
        f = self.inverse_f(length)
        words = prefix + (["G1"] if prefix or self.last_linear != "G1"
                          or rng.random() < 0.5 else [])
        words += self.axis_words(target, axes) + ["F" + self.value(f)]
        line = self.emit(" ".join(words))
        self.trace.append((line, "feed", list(target)))
        self.feeds.append((line, length * f))
        self.pos = target
        self.last_linear = "G1"

    def inverse_arc(self, prefix):
        """An arc whose end point is exactly on its circle (I/J/K: the start
        vector turned by k x 90 degrees or mirrored; or R form)."""
        rng = self.rng
        words = list(prefix)
        plane = self.plane
        if rng.random() < 0.3:
            plane = rng.choice(sorted(PLANES))
            words.append(plane)
        a, b, n = PLANES[plane]
        S = self.pos
        for _attempt in range(300):
            ccw = rng.random() < 0.5
            r_form = rng.random() < 0.35
            E = list(S)
            if r_form:
                for i in (a, b):
                    E[i] = S[i] + rng.randint(-40 * U, 40 * U)
                chord = math.hypot(E[a] - S[a], E[b] - S[b])
                if chord < 2 * U:
                    continue
                R = int(round(chord / 2 * rng.uniform(1.02, 3.0)))
                big = rng.random() < 0.3
                half = math.asin(chord / (2 * R))
                sweep = 2 * math.pi - 2 * half if big else 2 * half
                # centre: on the chord's bisector, left of S->E for a
                # counter-clockwise arc of at most 180 degrees
                h = math.sqrt(R * R - chord * chord / 4)
                side = 1 if ccw != big else -1
                ux, uy = (E[a] - S[a]) / chord, (E[b] - S[b]) / chord
                ca = (S[a] + E[a]) / 2 - side * h * uy
                cb = (S[b] + E[b]) / 2 + side * h * ux
                rad = R
            else:
                r = rng.uniform(3.0, 60.0) * U
                th = rng.uniform(0, 2 * math.pi)
                dx, dy = int(round(r * math.cos(th))), int(round(r * math.sin(th)))
                ends = [(dx, dy), (-dy, dx), (-dx, -dy), (dy, -dx),
                        (dy, dx), (-dy, -dx), (dx, -dy), (-dx, dy)]
                ex, ey = rng.choice(ends)
                ca, cb = S[a] - dx, S[b] - dy
                E[a], E[b] = ca + ex, cb + ey
                ps, pe = math.atan2(dy, dx), math.atan2(ey, ex)
                sweep = ((pe - ps) if ccw else (ps - pe)) % (2 * math.pi)
                if (ex, ey) == (dx, dy):
                    sweep = 2 * math.pi
                elif not 0.1 < sweep < 2 * math.pi - 0.1:
                    continue
                rad = math.hypot(dx, dy)
            if rng.random() < 0.3:
                E[n] = S[n] + rng.randint(-20 * U, 20 * U)
            ok = all(ARC_BOX[i][0] <= c - rad and c + rad <= ARC_BOX[i][1]
                     for i, c in ((a, ca), (b, cb)))
            if ok and MOVE_BOX[n][0] <= E[n] <= MOVE_BOX[n][1]:
                break
        else:
            return self.inverse_line(prefix)
        self.plane = plane
        length = math.hypot(rad * sweep, E[n] - S[n]) / U
        f = self.inverse_f(length)
        words.append("G3" if ccw else "G2")
        off = self.offset()
        helix = E[n] != S[n]
        for ax in sorted((a, b)) + ([n] if helix else []):
            words.append(AXES[ax] + self.L(E[ax] - (off[ax] if self.absolute else S[ax])))
        if r_form:
            words.append("R" + self.L(-R if big else R))
        else:
            for ax, c in sorted(((a, ca), (b, cb))):
                words.append(CENTER_WORD[ax] + self.L(c - S[ax]))
        words.append("F" + self.value(f))
        line = self.emit(" ".join(words))
        self.trace.append((line, "arc", list(E)))
        self.feeds.append((line, length * f))
        self.pos = E
        self.last_linear = None

    def inverse_time(self):
        """G93, two to six moves with F on every G1/G2/G3 (rapids need
        none), G94; in mm only."""
        rng = self.rng
        if self.inch:
            return self.linear()
        prefix = ["G93"]
        self.inverse = True
        if rng.random() < 0.5:
            self.emit("G93")
            prefix = []
        for _ in range(rng.randint(2, 6)):
            r = rng.random()
            if r < 0.15 and not prefix:
                self.linear(code="G0")
            elif r < 0.6:
                self.inverse_line(prefix)
                prefix = []
            else:
                self.inverse_arc(prefix)
                prefix = []
        self.emit("G94")
        self.inverse = False
        self.feed_set = False            # grbl and LinuxCNC forget F here
        self.last_linear = None

    # -- spindle, coolant, stops ------------------------------------------------------
    def spindle_block(self):
        rng = self.rng
        r = rng.random()
        if self.spindle != "stop" and r < 0.35:
            self.spindle = "stop"
            self.emit("M5")
        elif self.spindle != "stop" and r < 0.6:
            self.emit("S%d" % rng.choice(RPMS))
        else:
            d = "ccw" if (self.spindle == "cw" or rng.random() < 0.2) else "cw"
            if d == self.spindle:
                d = "cw" if d == "ccw" else "ccw"
            self.spindle = d
            m = "M3" if d == "cw" else "M4"
            s = "S%d" % rng.choice(RPMS)
            self.emit(" ".join([m, s] if rng.random() < 0.6 else [s, m]))
        self.last_linear = None

    def coolant_block(self):
        if self.coolant and self.rng.random() < 0.6:
            self.coolant = False
            self.emit("M9")
        else:
            self.coolant = True
            self.emit(self.rng.choice(["M8", "M8", "M7"]))
        self.last_linear = None

    def stop_block(self):
        rng = self.rng
        if rng.random() < 0.5 and self.spindle == "stop" and not self.coolant:
            self.emit("M0")
        elif rng.random() < 0.5:
            self.emit("M1")
        else:
            self.emit("T%d" % rng.choice(sorted(TOOLS)))
        self.last_linear = None

    def toggle_units(self):
        """G20/G21 (gen_programs.MixedProgram), after a G49 when a tool
        length offset is on. rs274 keeps the offset's number, not its
        length, across a unit change: moves that go through it afterwards
        (G53, G28/G30's second leg, the re-expression of the position on
        G43.1/G49) take it in the new units. `G21 G43.1 Z-50.8 G20 G53 G0
        Z0` prints Z50.8000 (50.8 in) for 2.0000; `G20 G43.1 Z-.5 G21 G28`
        ends at machine Z-12.2 mm for 0."""
        if self.tlo:
            self.tlo = 0
            self.emit("G49")
            self.last_linear = None
        super().toggle_units()

    def dwell(self):
        self.emit("G4 P" + self.value(self.rng.choice(DWELLS)))
        self.last_linear = None


PREAMBLES = [
    ["G21 G90 G94"],
    ["G90 G94 G91.1 G17", "G21"],
    ["G21", "G90"],
    ["G17 G21 G90 G94 G54"],
    ["G90", "G21", "G17"],
    ["G91.1", "G21 G90 G17 G94"],
]


def generate(index, seed=DEFAULT_SEED):
    rng = random.Random("grbl:%d:%d" % (seed, index))
    style = Style(rng)
    p = GrblProgram(rng, style)
    p.optional_stop = rng.random() < 0.25
    p.emit(ARGS_LINE_OPT if p.optional_stop else ARGS_LINE, raw=True)
    header = rng.choice(HEADERS) % index
    p.emit((";" + header) if style.semicolon else "(" + header + ")", raw=True)
    inch_start = rng.random() < 0.2
    for text in rng.choice(PREAMBLES):
        if inch_start:
            text = text.replace("G21", "G20")
        p.emit(text)
    p.inch = inch_start
    if rng.random() < 0.6:
        if rng.random() < 0.4:
            p.emit("T%d" % rng.choice(sorted(TOOLS)))
        p.spindle = "cw"
        p.emit("M3 S%d" % rng.choice(RPMS) if rng.random() < 0.7
               else "S%d M3" % rng.choice(RPMS))
    weights = {
        p.linear: 26, p.arc: 18, p.dwell: 2, p.set_g10: 4, p.preset_g92: 4,
        p.select_wcs: 4, p.move_g53: 2, p.toggle_distance: 3,
        p.incremental_stretch: 3, p.select_plane: 3, p.home: 5,
        p.store_home: 3, p.tool_length: 4, p.inverse_time: 4,
        p.spindle_block: 3, p.coolant_block: 2, p.stop_block: 2,
        p.comment_line: 2,
    }
    favourite = rng.choice(list(weights))
    weights[favourite] *= 2
    funcs = list(weights)
    w = [weights[f] for f in funcs]
    n_blocks = rng.randint(30, 80)
    segments = rng.choice([0, 1, 1, 2])
    marks = sorted(rng.sample(range(6, n_blocks - 2), 2 * segments))
    for i in range(1, len(marks)):
        marks[i] = max(marks[i], marks[i - 1] + 4)
    while len(p.ngc) < n_blocks:
        if marks and len(p.ngc) >= marks[0]:
            marks.pop(0)
            p.toggle_units()
            continue
        rng.choices(funcs, w)[0]()
    # the usual ending: spindle and coolant off, maybe home, end
    if p.spindle != "stop" or rng.random() < 0.3:
        p.spindle = "stop"
        p.emit("M5")
    if p.coolant:
        p.coolant = False
        p.emit("M9")
    if rng.random() < 0.4:
        p.home()
    p.emit(rng.choice(["M2", "M30", "M30", "M02"]))
    return p.ngc, p.trace, p.frames, p.feeds


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, default=DEFAULT_COUNT)
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED)
    ap.add_argument("--out", default=DEFAULT_OUT)
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    for i in range(1, args.count + 1):
        lines = generate(i, args.seed)[0]
        for ext in ("ngc", "nc"):
            with open(os.path.join(args.out, "%03d.%s" % (i, ext)), "w") as f:
                f.write("\n".join(lines) + "\n")
    print("wrote %d programs (x2 spellings) to %s" % (args.count, args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
