#!/usr/bin/env python3
"""Generate the canned-cycle programs of tests/fixtures/linuxcnc_cycles.

Each program exists in two spellings with identical line structure:

  NNN.ngc  for LinuxCNC's rs274          NNN.nc  for vcnc (fanuc dialect)
  G81 ... L3        (repeats)            G81 ... K3
  G82 ... P1.25     (dwell, seconds)     G82 ... P1250   (integer milliseconds)
  G86 ... P0.       (rs274 needs a P)    G86 ...         (Fanuc G86 has none)
  G83 ...           (never dwells)       G83 ... P0      (after a G82/G89 P in the chain)
  G10 L1 / G4 P are not used.

Line 1 of both is `(vcnc-args: --dialect fanuc --machine machine.toml)`.

A program: optional work offset (G10 L2 + G54..G59), G92 preset and tool
length offset (G43 H, G17 programs only), `S M3`/`S M4`, one to four cycle
chains, `M5`, `M2`. A chain: plane (G17/G18/G19) selected while no cycle is
active, a G0 to the start point (the initial level), a first cycle block
with R, the depth word (Z in G17, Y in G18, X in G19) and Q (G73/G83) or P
(G82/G89; G86 in LinuxCNC), then zero to four more blocks with new hole
positions (modal), sometimes new depth, R, Q, P, a G98 -> G99 switch or
another cycle, and a G80 or a G0 that ends the chain. G90 or G91 per chain
(G91: R from the initial level, the depth from R, positions incremental,
K repeats with a non-zero increment in the plane).

Where LinuxCNC's cycles differ from Fanuc's, the generator keeps out of it
(see tests/fixtures/linuxcnc_cycles/README.md):

  * the initial level is always above R (LinuxCNC first rapids up to R when
    it is below);
  * once a chain drilled a hole under G99 (the tool waits at R), it stays
    under G99, and R only stays or goes down: from below the clearance
    level LinuxCNC moves diagonally to it, Fanuc positions at the level the
    tool is at and then moves along the drilling axis;
  * G89 only under G99: LinuxCNC feeds out all the way to the clearance
    level (the initial level under G98), Fanuc feeds to R and rapids on;
  * K > 1 only under G91, and every hole position differs from where the
    tool is: no zero-length positioning;
  * another cycle without G80 only while the tool is at the initial level
    (whether the initial level is kept or taken again then does not
    matter);
  * G73/G83: either (R - Z) is no multiple of Q by at least 0.01 mm, or
    R, Z and Q are multiples of 0.5 mm under G90 (exact in binary, so
    LinuxCNC's floating-point peck loop ends exactly at Z).

`generate()` returns (ngc, nc, events): events is the generator's own
Fanuc reading of the program (every event but `end`, machine coordinates,
0.0001 mm units turned into mm), which make_ext_fixtures.py compares with
rs274's output.

Usage: gen_cycles.py [--count 80] [--seed 20240802] [--out DIR]
"""

import argparse
import os
import random
import sys

from gen_programs import U, fmt

DEFAULT_SEED = 20240802
DEFAULT_COUNT = 80
DEFAULT_OUT = "/tmp/vcnc_linuxcnc_cycles"
ARGS_LINE = "(vcnc-args: --dialect fanuc --machine machine.toml)"

# LinuxCNC 2.9.0~pre1 interp_internal.hh: G83_RAPID_DELTA 0.010 inch, times
# 25.4 under G21, for G73's retract and G83's re-approach alike.
PECK_RETURN = 2540           # 0.254 mm in 0.0001 mm units

TOOLS = {1: (75.0, 5.0), 2: (-42.5, 3.0), 3: (120.125, 2.0)}

CYCLES = ["G81", "G82", "G73", "G83", "G85", "G86", "G89"]
# plane -> (the two plane axes as indices into XYZ, drilling axis)
PLANE_AXES = {"G17": ((0, 1), 2), "G18": ((2, 0), 1), "G19": ((1, 2), 0)}
AXES = "XYZ"
FEEDS = ["F100.", "F150.", "F200.", "F250.", "F80.", "F320.5", "F400."]
DWELLS_MS = [100, 250, 500, 750, 1000, 1250, 1500, 2000, 3000]


def secs(ms):
    s = "%d.%03d" % divmod(ms, 1000)
    return s.rstrip("0") if not s.endswith(".000") else s[:-2]


class CycleProgram:
    def __init__(self, rng):
        self.rng = rng
        self.ngc = []
        self.nc = []
        self.events = []
        self.pos = [0, 0, 0]            # machine
        self.g5x = {p: [0, 0, 0] for p in range(1, 7)}
        self.active = 1
        self.g92 = [0, 0, 0]
        self.tlo = 0
        self.reported = ([0, 0, 0], 0)
        self.absolute = True
        self.plane = "G17"
        self.feed = None
        self.spindle = ("stop", 0)
        self.rpm = 0

    # -- bookkeeping -------------------------------------------------------
    def offset(self):
        o = self.g5x[self.active]
        return [o[0] + self.g92[0], o[1] + self.g92[1], o[2] + self.g92[2] + self.tlo]

    def prog(self, machine):
        off = self.offset()
        return [machine[i] - off[i] for i in range(3)]

    def mach(self, prog):
        off = self.offset()
        return [prog[i] + off[i] for i in range(3)]

    def emit(self, ngc, nc=None):
        self.ngc.append(ngc)
        self.nc.append(ngc if nc is None else nc)
        line = len(self.ngc)
        o = self.g5x[self.active]
        state = ([o[i] + self.g92[i] for i in range(3)], self.tlo)
        if state != self.reported:
            ev = {"type": "frame", "line": line, "origin": mm3(state[0])}
            if state[1]:
                ev["tool_offset"] = mm3([0, 0, state[1]])
            self.events.append(ev)
            self.reported = state
        return line

    def move(self, line, kind, target):
        if target == self.pos:
            return                       # no zero-length moves
        ev = {"type": kind, "line": line, "to": mm3(target)}
        if kind == "feed":
            ev["feed"] = self.feed
        self.events.append(ev)
        self.pos = list(target)

    def words(self, target, axes):
        """Axis words for machine point `target` (absolute or incremental)."""
        out = []
        p_new = self.prog(target)
        p_old = self.prog(self.pos)
        for i in axes:
            v = p_new[i] if self.absolute else p_new[i] - p_old[i]
            out.append(AXES[i] + fmt(v))
        return out

    def distance(self, absolute):
        if absolute != self.absolute:
            self.absolute = absolute
            return ["G90" if absolute else "G91"]
        return []

    # -- set-up blocks -----------------------------------------------------
    def work_offset(self):
        rng = self.rng
        p = rng.randint(2, 6)
        val = [rng.randint(-80, 80) * U + rng.choice([0, 2500, 5000, 1234]),
               rng.randint(-80, 80) * U, rng.randint(-30, 30) * U]
        self.g5x[p] = val
        self.emit("G10 L2 P%d X%s Y%s Z%s" % (p, fmt(val[0]), fmt(val[1]), fmt(val[2])))
        self.active = p
        self.emit("G%d" % (53 + p))

    def preset_g92(self):
        rng = self.rng
        new = [rng.randint(-40, 40) * U + rng.choice([0, 5000, 3333]),
               rng.randint(-40, 40) * U, rng.randint(-20, 20) * U]
        o = self.g5x[self.active]
        val = [self.pos[i] - o[i] - new[i] for i in range(3)]
        val[2] -= self.tlo
        self.g92 = new
        self.emit("G92 X%s Y%s Z%s" % (fmt(val[0]), fmt(val[1]), fmt(val[2])))

    def tool_length(self):
        h = self.rng.choice(sorted(TOOLS))
        self.tlo = int(round(TOOLS[h][0] * U))
        target = list(self.pos)
        target[2] = self.rng.randint(20, 120) * U
        line = self.emit("G43 H%d G0 Z%s" % (h, fmt(self.prog(target)[2])))
        self.move(line, "rapid", target)

    def spindle_on(self):
        rng = self.rng
        rpm = rng.choice([800, 1000, 1200, 1500, 2400, 3000])
        d = "cw" if rng.random() < 0.75 else "ccw"
        line = self.emit("S%d M%d" % (rpm, 3 if d == "cw" else 4))
        self.rpm = rpm
        self.spindle = d
        self.events.append({"type": "spindle", "line": line, "dir": d, "rpm": float(rpm)})

    def speed_change(self):
        rpm = self.rng.choice([600, 900, 1800, 2000, 3600])
        if rpm == self.rpm:
            return
        line = self.emit("S%d" % rpm)
        self.rpm = rpm
        self.events.append({"type": "spindle", "line": line, "dir": self.spindle,
                            "rpm": float(rpm)})

    # -- cycles --------------------------------------------------------------
    def chain(self, allow_planes):
        rng = self.rng
        plane = rng.choice(allow_planes)
        if plane != self.plane:
            self.plane = plane
            self.emit(plane)
        (a, b), c = PLANE_AXES[plane]
        # start point: somewhere, at the initial level (machine)
        start = list(self.pos)
        start[a] = rng.randint(-150, 150) * U + rng.choice([0, 5000, 2500])
        start[b] = rng.randint(-150, 150) * U
        start[c] = rng.randint(-40, 60) * U + rng.choice([0, 5000])
        words = self.distance(True) + ["G0"] + self.words(start, [0, 1, 2])
        line = self.emit(" ".join(words))
        self.move(line, "rapid", start)
        initial = self.prog(self.pos)[c]          # program coordinate

        absolute = rng.random() < 0.65
        cycle = rng.choice(CYCLES)
        retract = "G99" if cycle == "G89" or rng.random() < 0.5 else "G98"
        st = {"R": None, "Z": None, "Q": None, "P": None, "K": 1}
        n_blocks = rng.randint(1, 5)
        any_g99_hole = False
        for k in range(n_blocks):
            first = k == 0
            words = []
            if first:
                words += self.distance(absolute)
            new_cycle = first
            if not first and self.prog(self.pos)[c] == initial and rng.random() < 0.2:
                cycle = rng.choice([x for x in CYCLES if x != cycle])
                new_cycle = True
            # retract mode: G98 -> G99 any time, never back after a G99 hole
            want = retract
            if cycle == "G89":
                want = "G99"
            elif not any_g99_hole and rng.random() < 0.25:
                want = "G99" if retract == "G98" else "G98"
            if any_g99_hole:
                want = "G99"
            if first or want != retract:
                words.append(want)
            retract = want
            if new_cycle:
                words.append(cycle)
            # R and the depth (program coordinates on the drilling axis)
            r_old, z_old = st["R"], st["Z"]
            set_r = new_cycle or rng.random() < 0.2
            set_z = new_cycle or rng.random() < 0.3
            r = r_old
            if set_r:
                top = initial - 1 * U
                if any_g99_hole and r_old is not None:
                    top = min(top, r_old)          # R only goes down at R
                r = top - rng.randint(0, 15) * U - rng.choice([0, 5000])
            z = z_old
            if set_z or (z is not None and z >= r - 1 * U):
                z = r - rng.randint(2, 40) * U - rng.choice([0, 2500, 1250, 7500])
                set_z = True
            q = st["Q"]
            p_ms = st["P"]
            exact = False
            if cycle in ("G73", "G83"):
                if new_cycle or rng.random() < 0.2:
                    q = rng.choice([15000, 20000, 25000, 30000, 40000, 50000,
                                    12345, 33333, 60000])
                if absolute and rng.random() < 0.3:
                    # exact case: R, Z, Q multiples of 0.5 mm, (R - Z) = n Q
                    q = rng.choice([10000, 20000, 25000, 50000])
                    r = r // 5000 * 5000
                    n = rng.randint(1, 6)
                    z = r - n * q
                    set_r = set_z = exact = True
                if not exact:
                    for _ in range(200):
                        rem = (r - z) % q
                        if 100 <= rem <= q - 100 and (r - z) > 0:
                            break
                        z -= rng.randint(1, 999)
                        set_z = True
                    else:
                        raise RuntimeError("no peck depth")
                if new_cycle or q != st["Q"]:
                    set_q = True
                else:
                    set_q = False
            if cycle in ("G82", "G89") and (new_cycle or rng.random() < 0.2):
                p_ms = rng.choice(DWELLS_MS)
            if not absolute and (set_r or set_z):
                # G91: the depth word is from R, R from the initial level;
                # a new R with the old depth word would move the bottom too
                set_r = set_z = True
            # hole position(s): machine points; the drilling axis is ignored
            reps = 1
            if not absolute and rng.random() < 0.35:
                reps = rng.randint(2, 4)
            axes = [a, b] if rng.random() < 0.5 else [rng.choice([a, b])]
            for _ in range(100):
                step = [0, 0, 0]
                for i in axes:
                    while step[i] == 0:
                        step[i] = rng.randint(-60, 60) * U + rng.choice([0, 5000, 2500])
                holes = []
                cur = list(self.pos)
                for _rep in range(reps):
                    cur = [cur[i] + step[i] for i in range(3)]
                    holes.append(cur)
                if all(abs(h[i]) <= 350 * U for h in holes for i in axes):
                    break
            else:
                raise RuntimeError("no hole inside the travel")
            hole = holes[0]
            # words: positions, depth, R, Q/P, F, K
            pw = []
            p_hole = self.prog(hole)
            for i in sorted(axes):
                v = p_hole[i] if absolute else step[i]
                pw.append(AXES[i] + fmt(v))
            if set_z:
                pw.append(AXES[c] + fmt(z if absolute else z - r))
                pw.sort(key=lambda w: AXES.index(w[0]))
            words += pw
            if set_r:
                words.append("R" + fmt(r if absolute else r - initial))
            ngc_extra, nc_extra = [], []
            if cycle in ("G73", "G83") and set_q:
                words.append("Q" + fmt(q))
            if cycle in ("G82", "G89") and (new_cycle or p_ms != st["P"]):
                ngc_extra.append("P" + secs(p_ms))
                nc_extra.append("P%d" % p_ms)
            if cycle == "G86" and new_cycle:
                ngc_extra.append("P0.")
            if cycle in ("G73", "G83") and new_cycle and st["P"]:
                # Syntec's G73/G83 dwell at the bottom with the modal P
                # (1.2.31, 1.2.36), LinuxCNC's never: clear it for vcnc.
                nc_extra.append("P0")
                p_ms = 0
            tail_ngc, tail_nc = [], []
            if self.feed is None or (first and rng.random() < 0.4):
                f = rng.choice(FEEDS)
                self.feed = float(f[1:])
                tail_ngc.append(f)
                tail_nc.append(f)
            if reps > 1:
                tail_ngc.append("L%d" % reps)
                tail_nc.append("K%d" % reps)
            line = self.emit(" ".join(words + ngc_extra + tail_ngc),
                             " ".join(words + nc_extra + tail_nc))
            st.update(R=r, Z=z, Q=q, P=p_ms)
            # Fanuc execution of the block
            level = initial if retract == "G98" else r
            for h in holes:
                self.drill(line, cycle, h, c, r, z, q, p_ms, level)
            if retract == "G99":
                any_g99_hole = True
        # end of chain
        if rng.random() < 0.8:
            self.emit("G80")
        else:
            # a G0 along the drilling axis ends the chain too (group 01)
            target = list(self.pos)
            target[c] = self.at_level(initial, c)[c] + rng.randint(5, 30) * U
            line = self.emit(" ".join(["G0"] + self.words(target, [c])))
            self.move(line, "rapid", target)

    def at_level(self, v, c):
        """The current point with program coordinate `v` on axis c (machine)."""
        p = self.prog(self.pos)
        p[c] = v
        return self.mach(p)

    def drill(self, line, cycle, hole_xy, c, r, z, q, p_ms, level):
        """One hole, Fanuc: position at the current level, rapid to R, the
        cycle's moves, back to `level` (program coordinates on axis c)."""
        def at(v):
            return self.at_level(v, c)
        hole_at = list(hole_xy)
        hole_at[c] = at(z)[c]
        self.events.append({"type": "hole", "line": line, "cycle": cycle,
                            "at": mm3(hole_at)})
        target = list(hole_xy)
        target[c] = self.pos[c]
        self.move(line, "rapid", target)
        self.move(line, "rapid", at(r))
        if cycle in ("G73", "G83"):
            depth = r - q
            while depth > z:
                self.move(line, "feed", at(depth))
                if cycle == "G83":
                    self.move(line, "rapid", at(r))
                self.move(line, "rapid", at(depth + PECK_RETURN))
                depth -= q
        self.move(line, "feed", at(z))
        if cycle in ("G82", "G89"):
            self.events.append({"type": "dwell", "line": line, "seconds": p_ms / 1000.0})
        if cycle == "G86":
            self.events.append({"type": "spindle", "line": line, "dir": "stop", "rpm": 0.0})
        if cycle in ("G85", "G89"):
            self.move(line, "feed", at(r))
        self.move(line, "rapid", at(level))
        if cycle == "G86":
            self.events.append({"type": "spindle", "line": line, "dir": self.spindle,
                                "rpm": float(self.rpm)})


def mm3(u):
    return {a: u[i] / float(U) for i, a in enumerate("xyz")}


def generate(index, seed=DEFAULT_SEED):
    rng = random.Random("cycles:%d:%d" % (seed, index))
    p = CycleProgram(rng)
    p.emit(ARGS_LINE)
    p.emit("G21 G17 G90 G94")
    if rng.random() < 0.4:
        p.work_offset()
    with_tlo = rng.random() < 0.2
    if with_tlo:
        p.tool_length()
    if rng.random() < 0.25:
        p.preset_g92()
    p.spindle_on()
    planes = ["G17"] if with_tlo else ["G17", "G17", "G18", "G19"]
    for k in range(rng.randint(1, 4)):
        if k and rng.random() < 0.2:
            p.speed_change()
        if k and rng.random() < 0.15 and p.absolute:
            p.preset_g92()
        p.chain(planes)
    line = p.emit("M5")
    p.events.append({"type": "spindle", "line": line, "dir": "stop", "rpm": 0.0})
    p.emit("M2")
    return p.ngc, p.nc, p.events


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, default=DEFAULT_COUNT)
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED)
    ap.add_argument("--out", default=DEFAULT_OUT)
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    for i in range(1, args.count + 1):
        ngc, nc, _ = generate(i, args.seed)
        for ext, lines in (("ngc", ngc), ("nc", nc)):
            with open(os.path.join(args.out, "%03d.%s" % (i, ext)), "w") as f:
                f.write("\n".join(lines) + "\n")
    print("wrote %d programs (x2 spellings) to %s" % (args.count, args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
