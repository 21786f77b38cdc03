#!/usr/bin/env python3
"""Generate the tool-length-offset programs of tests/fixtures/linuxcnc_tlo.

Each program exists in two spellings with identical line structure:

  NNN.ngc  for LinuxCNC's rs274:  G10 L1 P<n> Z<length>   G4 P<seconds>
  NNN.nc   for vcnc (fanuc):      G10 L10 P<n> R<length>  G4 X<seconds>

Everything else is the same text. Line 1 of both is
`(vcnc-args: --dialect fanuc --machine machine.toml)` (a comment to rs274).

The blocks are gen_programs.py's first-batch blocks (G0/G1, arcs and helices
in G17/G18/G19, G90/G91, G10 L2, G54-G59, G92, G53, G4) plus:

  * `G43 H<n>` always with a Z word and a G0/G1 motion in the block (a bare
    G43 or G49 moves Z on Fanuc and not on LinuxCNC), sometimes X/Y too,
    always under G90 (`G90` is written in the block when G91 was on): under
    G91 LinuxCNC re-expresses the position in the new offset without moving
    and then moves by the increment, Fanuc moves by the increment plus the
    change of offset. H changes while G43 is on. `G43 H0` now and then, but
    only before any M6 and any G10 L1: Fanuc's H0 is a zero offset,
    LinuxCNC's the tool in the spindle slot, which is empty (length 0)
    until an M6 loads a tool or a G10 L1 (rs274 writes the entry it sets
    into the spindle slot too while no tool is loaded);
  * `G49` with a Z word and G0/G1, like G43;
  * tool lengths set with G10 (only under G90, where vcnc's L10 R is the new
    value), and G43 H<n> again to use them (both latch the value at G43);
  * G28 with axis words (also `G91 G28 Z0.`) while an offset is active: the
    intermediate point includes the offset, the reference point (machine 0)
    does not. After it, while an offset is active, the next block is an
    absolute G0 naming X, Y and Z (Fanuc controls differ in what an
    incremental move right after a reference return does with the offset
    vector; an absolute block is the same everywhere);
  * `T<n> M6` (the spindle is never on in this set: LinuxCNC stops it on M6).

Machine = program + G5x + G92 + tool length offset (Z). `generate()`
returns (ngc, nc, trace, frames): trace = (line, kind, machine end point) of
every motion (both G28 legs), frames = (line, origin, tool length) of every
block that changes what a `frame` event reports; make_ext_fixtures.py
checks rs274's output against both.

Usage: gen_tlo.py [--count 60] [--seed 20240801] [--out DIR]
"""

import argparse
import os
import random
import sys

import gen_programs as gp
from gen_programs import AXES, MOVE_BOX, U, fmt

DEFAULT_SEED = 20240801
DEFAULT_COUNT = 60
DEFAULT_OUT = "/tmp/vcnc_linuxcnc_tlo"
ARGS_LINE = "(vcnc-args: --dialect fanuc --machine machine.toml)"

# Tool table: n -> (length mm, radius mm). LinuxCNC's table holds the same
# in inches, D as a diameter (rs274_events.tool_table_text).
TOOLS = {
    1: (50.0, 5.0),
    2: (125.5, 5.0),
    3: (-87.375, 3.0),
    4: (210.25, 4.0),
    5: (33.3333, 2.5),
    6: (0.0, 6.35),
}


def units(mm):
    return int(round(mm * U))


class TloProgram(gp.Program):
    def __init__(self, rng):
        super().__init__(rng)
        self.tools = {n: units(l) for n, (l, _) in TOOLS.items()}
        self.tlo = 0                   # latched length, 0.0001 mm
        self.frames = []
        self.reported = ([0, 0, 0], 0)
        self.after_g28 = False

    # machine = program + G5x + G92 + tool length (Z)
    def offset(self):
        o = super().offset()
        return [o[0], o[1], o[2] + self.tlo]

    def emit(self, ngc, nc=None):
        line = super().emit(ngc, nc)
        o = self.g5x[self.active]
        state = ([o[i] + self.g92[i] for i in range(3)], self.tlo)
        if state != self.reported:
            self.frames.append((line, list(state[0]), state[1]))
            self.reported = state
        return line

    def preset_g92(self):
        if not self.absolute:
            return self.toggle_distance(force_abs=True)
        new = [self.rng.randint(-m, m) for m in gp.G92_MAX]
        if self.rng.random() < 0.25:
            new = [0, 0, 0]
        o = self.g5x[self.active]
        val = [self.pos[i] - o[i] - new[i] for i in range(3)]
        val[2] -= self.tlo
        self.g92 = new
        self.emit("G92 X%s Y%s Z%s" % (fmt(val[0]), fmt(val[1]), fmt(val[2])))
        self.last_linear = None

    def length_change(self, h, word):
        """G43 H<h> (word "G43") or G49 (h None) with Z, G0/G1."""
        rng = self.rng
        # only under G90: under G91 LinuxCNC first re-expresses the position
        # in the new offset (no motion) and then moves by the increment,
        # while Fanuc moves by the increment plus the change of offset
        switch = [] if self.absolute else ["G90"]
        self.absolute = True
        self.tlo = self.tools[h] if h else 0
        new_off = self.offset()
        modal = self.last_linear in ("G0", "G1") and rng.random() < 0.3
        code = self.last_linear if modal else ("G0" if rng.random() < 0.6 else "G1")
        target = list(self.pos)
        lo, hi = MOVE_BOX[2]
        target[2] = rng.randint(lo, hi)
        if rng.random() < 0.3:
            target[2] = target[2] // 10000 * 10000
        axes = [2]
        if rng.random() < 0.3:
            i = rng.choice([0, 1])
            lo, hi = MOVE_BOX[i]
            target[i] = min(hi, max(lo, self.pos[i] + rng.randint(-30 * U, 30 * U)))
            axes = sorted([i, 2])
        words = [AXES[i] + fmt(target[i] - new_off[i]) for i in axes]
        head = switch + [word] + (["H%d" % h] if h is not None else [])
        motion = [] if modal else [code]
        order = rng.random()
        if order < 0.5:
            parts = head + motion + words
        elif order < 0.8:
            parts = motion + head + words
        else:
            parts = motion + words + head
        if code == "G1":
            parts += self.feed_word(force=rng.random() < 0.1)
        line = self.emit(" ".join(parts))
        self.trace.append((line, "rapid" if code == "G0" else "feed", list(target)))
        self.pos = target
        self.last_linear = code

    def g43(self):
        h = self.rng.choice([1, 2, 3, 4, 5, 6, 1, 2, 3, 4, 0])
        if h == 0 and self.h0_differs:
            h = 1       # LinuxCNC's H0 is the tool in the spindle, Fanuc's 0
        self.length_change(h, "G43")

    def g49(self):
        if self.tlo == 0 and self.rng.random() < 0.7:
            return self.g43()
        self.length_change(None, "G49")

    def set_length(self):
        if not self.absolute:
            return self.toggle_distance(force_abs=True)
        rng = self.rng
        n = rng.choice(sorted(self.tools))
        v = rng.randint(-150 * 1000, 220 * 1000) * 10     # 0.001 mm steps
        self.tools[n] = v
        # rs274 writes the new entry into its spindle slot too (no tool is
        # loaded, slot 0): its H0 has that length from now on
        self.h0_differs = True
        self.emit("G10 L1 P%d Z%s" % (n, fmt(v)), "G10 L10 P%d R%s" % (n, fmt(v)))
        self.last_linear = None
        if rng.random() < 0.6:
            # use it: G43 H<n> again
            self.length_change(n, "G43")

    def tool_change(self):
        self.h0_differs = True
        self.emit("T%d M6" % self.rng.choice(sorted(self.tools)))
        self.last_linear = None

    def g28(self):
        rng = self.rng
        words = []
        r = rng.random()
        if r < 0.3:
            self.absolute = False
            words.append("G91")
            axes = [2] if rng.random() < 0.7 else sorted(rng.sample(range(3), 2))
            mid = list(self.pos)
            words.append("G28")
            words += ["%s0." % AXES[i] for i in axes]
        else:
            if r < 0.4:
                self.absolute = not self.absolute
                words.append("G90" if self.absolute else "G91")
            axes = sorted(rng.sample(range(3), rng.choice([1, 2, 3, 3])))
            mid = list(self.pos)
            for i in axes:
                lo, hi = MOVE_BOX[i]
                mid[i] = min(hi, max(lo, self.pos[i] + rng.randint(-60 * U, 60 * U)))
            words.append("G28")
            words += self.axis_words(mid, axes)
        line = self.emit(" ".join(words))
        home = list(mid)
        for i in axes:
            home[i] = 0
        self.trace.append((line, "rapid", list(mid)))
        self.trace.append((line, "rapid", list(home)))
        self.pos = home
        self.last_linear = None
        self.after_g28 = self.tlo != 0

    def absolute_move(self):
        """After G28 with an offset on: G90 G0 X Y Z."""
        rng = self.rng
        target = [rng.randint(lo, hi) for lo, hi in MOVE_BOX]
        words = [] if self.absolute else ["G90"]
        self.absolute = True
        words += ["G0"] + self.axis_words(target, [0, 1, 2])
        line = self.emit(" ".join(words))
        self.trace.append((line, "rapid", list(target)))
        self.pos = target
        self.last_linear = "G0"
        self.after_g28 = False

    h0_differs = False


def generate(index, seed=DEFAULT_SEED):
    rng = random.Random("tlo:%d:%d" % (seed, index))
    p = TloProgram(rng)
    p.emit(ARGS_LINE)
    p.emit("G21 G17 G90 G94")
    weights = {
        p.linear: 26, p.arc: 16, p.dwell: 2, p.set_g10: 4, p.preset_g92: 4,
        p.select_wcs: 5, p.move_g53: 3, p.toggle_distance: 6,
        p.select_plane: 3, p.g43: 12, p.g49: 4, p.set_length: 5, p.g28: 5,
        p.tool_change: 2,
    }
    favourite = rng.choice(list(weights))
    weights[favourite] *= 2
    funcs = list(weights)
    w = [weights[f] for f in funcs]
    n_blocks = rng.randint(25, 60)
    first_g43 = rng.randint(3, 6)
    while len(p.ngc) < n_blocks:
        if p.after_g28:
            p.absolute_move()
        elif len(p.ngc) >= first_g43 and not any("G43" in l for l in p.ngc):
            p.g43()
        else:
            rng.choices(funcs, w)[0]()
    if p.after_g28:
        p.absolute_move()
    if p.tlo and rng.random() < 0.5:
        p.length_change(None, "G49")
    p.emit("M2")
    return p.ngc, p.nc, p.trace, p.frames


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, default=DEFAULT_COUNT)
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED)
    ap.add_argument("--out", default=DEFAULT_OUT)
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    for i in range(1, args.count + 1):
        ngc, nc, _, _ = generate(i, args.seed)
        for ext, lines in (("ngc", ngc), ("nc", nc)):
            with open(os.path.join(args.out, "%03d.%s" % (i, ext)), "w") as f:
                f.write("\n".join(lines) + "\n")
    print("wrote %d programs (x2 spellings) to %s" % (args.count, args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
