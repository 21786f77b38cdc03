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

Usage: gen_programs.py [--count 300] [--seed 20240601] [--out DIR]
(DIR defaults to /tmp/vcnc_linuxcnc_programs, where make_fixtures.py looks.)

`generate(index, seed)` is importable: it returns (ngc_lines, nc_lines, trace),
where trace is the generator's own idea of the machine end point of every
motion block, handy to cross-check the converter.
"""

import argparse
import math
import os
import random
import sys

DEFAULT_OUT = "/tmp/vcnc_linuxcnc_programs"
DEFAULT_SEED = 20240601
DEFAULT_COUNT = 300

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


def generate(index, seed=DEFAULT_SEED):
    rng = random.Random("%d:%d" % (seed, index))
    p = Program(rng)
    p.emit("G21 G17 G90 G94")
    n_blocks = rng.randint(20, 75)
    # per-program emphasis so that some programs lean on one feature
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
    favourite = rng.choice(list(weights))
    weights[favourite] *= 2
    funcs = list(weights)
    w = [weights[f] for f in funcs]
    while len(p.ngc) < n_blocks:
        rng.choices(funcs, w)[0]()
    p.emit("M2")
    return p.ngc, p.nc, p.trace


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, default=DEFAULT_COUNT)
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED)
    ap.add_argument("--out", default=DEFAULT_OUT)
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    for name in os.listdir(args.out):
        if name.endswith((".nc", ".ngc")):
            os.remove(os.path.join(args.out, name))
    for i in range(1, args.count + 1):
        ngc, nc, _ = generate(i, args.seed)
        assert len(ngc) == len(nc)
        for ext, lines in (("ngc", ngc), ("nc", nc)):
            with open(os.path.join(args.out, "%03d.%s" % (i, ext)), "w") as f:
                f.write("\n".join(lines) + "\n")
    print("wrote %d programs (x2 spellings) to %s" % (args.count, args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
