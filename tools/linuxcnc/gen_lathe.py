#!/usr/bin/env python3
"""Generate the programs of the linuxcnc_lathe fixture set: random turning
programs written twice, line for line, for vcnc's fanuc-lathe dialect
(NNN.nc) and for LinuxCNC 2.9 (NNN.ngc), in what both define alike.

  .nc (fanuc-lathe)               .ngc (LinuxCNC)
  G18 G21 G40 G80 G99             G18 G21 G40 G80 G7 G90 G95   diameters, per rev
  G00 X40. Z2.                    G90 G0 X40. Z2.
  G01 U-4. W-10. F0.2             G91 G1 X-4. Z-10. F0.2       U/W: incremental
  G02 X40. Z-16. I2. K-3.         G90 G2 X40. Z-16. I2. K-3.   I is a radius in both
  G32 X38. Z-30. F1.5             G90 G33 X38. Z-30. K1.5      threads (lead F / K)
  G50 X100. Z0.                   G92 X100. Z0.                coordinate setting
  G50 S1500                       (G50 S1500)                  the clamp ...
  G96 S120                        G96 D1500 S120               ... of the surface speed
  M99 P30                         O100 sub                     the profile, skipped by
  N10 G00 X20. Z2. … N20 …        G0 X20. Z2. …                the flow on both sides,
  (end of profile)                O100 endsub
  N30 G70 P10 Q20                 G70 Q100 X.. Z.. P1 D0       finished by G70
  M30                             M2

Every arc is built from a centre (I/K) or a radius at least 0.55 of its
chord (R), so that both read the same circle; coordinates have four
decimals. Seeded: the output is reproducible. Used by
make_lathe_fixtures.py; run alone it prints one program pair.
"""

import random


def fmt(v):
    """A length with a decimal point and at most four decimals."""
    s = "%.4f" % v
    s = s.rstrip("0")
    return s if not s.endswith(".") else s


class Gen:
    def __init__(self, seed):
        self.r = random.Random(seed)
        self.nc = []
        self.ngc = []
        self.x = 0.0    # radius; the set's machine starts at X0 Z0 like rs274
        self.z = 0.0
        self.profiled = False
        self.rpm = 800

    def line(self, nc, ngc):
        self.nc.append(nc)
        self.ngc.append(ngc)

    def point(self):
        return self.r.uniform(5.0, 40.0), self.r.uniform(-60.0, 5.0)

    def rapid(self, absolute=False):
        x, z = self.point()
        if self.r.random() < 0.3 and not absolute:
            u, w = 2 * round(x - self.x, 4), round(z - self.z, 4)
            self.line("G00 U%s W%s" % (fmt(u), fmt(w)), "G91 G0 X%s Z%s" % (fmt(u), fmt(w)))
            self.x += u / 2
            self.z += w
        else:
            x, z = round(x, 4), round(z, 4)
            self.line("G00 X%s Z%s" % (fmt(2 * x), fmt(z)), "G90 G0 X%s Z%s" % (fmt(2 * x), fmt(z)))
            self.x, self.z = x, z

    def feed(self):
        x, z = self.point()
        f = self.r.choice([0.05, 0.1, 0.15, 0.2, 0.25])
        if self.r.random() < 0.3:
            u, w = 2 * round(x - self.x, 4), round(z - self.z, 4)
            self.line("G01 U%s W%s F%s" % (fmt(u), fmt(w), fmt(f)),
                      "G91 G1 X%s Z%s F%s" % (fmt(u), fmt(w), fmt(f)))
            self.x += u / 2
            self.z += w
        else:
            x, z = round(x, 4), round(z, 4)
            self.line("G01 X%s Z%s F%s" % (fmt(2 * x), fmt(z), fmt(f)),
                      "G90 G1 X%s Z%s F%s" % (fmt(2 * x), fmt(z), fmt(f)))
            self.x, self.z = x, z

    def arc_ik(self):
        import math
        rad = self.r.uniform(2.0, 12.0)
        a0 = self.r.uniform(0, 2 * math.pi)
        # centre so that the tool is on the circle at angle a0 (Z, X frame)
        cz, cx = self.z - rad * math.cos(a0), self.x - rad * math.sin(a0)
        if cx - rad < 1.0:
            return self.feed()
        sweep = self.r.uniform(0.3, 2.5) * self.r.choice([1, -1])
        a1 = a0 + sweep
        ez, ex = cz + rad * math.cos(a1), cx + rad * math.sin(a1)
        ex, ez = round(ex, 4), round(ez, 4)
        i, k = round(cx - self.x, 4), round(cz - self.z, 4)
        g = "G03" if sweep > 0 else "G02"
        f = self.r.choice([0.1, 0.2])
        self.line("%s X%s Z%s I%s K%s F%s" % (g, fmt(2 * ex), fmt(ez), fmt(i), fmt(k), fmt(f)),
                  "G90 %s X%s Z%s I%s K%s F%s" % (g.replace("0", "", 1), fmt(2 * ex), fmt(ez), fmt(i), fmt(k), fmt(f)))
        self.x, self.z = ex, ez

    def arc_r(self):
        import math
        x, z = self.point()
        x, z = round(x, 4), round(z, 4)
        chord = math.hypot(x - self.x, z - self.z)
        if chord < 1.0:
            return self.feed()
        rad = round(chord / 2 * self.r.uniform(1.1, 3.0), 4)
        g = self.r.choice(["G02", "G03"])
        # The arc's far point must stay off the axis (X > 0).
        h = math.sqrt(max(rad * rad - chord * chord / 4, 0))
        if min(x, self.x) - (rad - h) < 1.0:
            return self.feed()
        self.line("%s X%s Z%s R%s F0.1" % (g, fmt(2 * x), fmt(z), fmt(rad)),
                  "G90 %s X%s Z%s R%s F0.1" % (g.replace("0", "", 1), fmt(2 * x), fmt(z), fmt(rad)))
        self.x, self.z = x, z

    def thread(self):
        lead = self.r.choice([1.0, 1.5, 2.0])
        z = round(self.z - self.r.uniform(10.0, 40.0), 4)
        if self.r.random() < 0.3:
            x = round(self.x + self.r.uniform(-1.0, 1.0), 4)
            self.line("G32 X%s Z%s F%s" % (fmt(2 * x), fmt(z), fmt(lead)),
                      "G90 G33 X%s Z%s K%s" % (fmt(2 * x), fmt(z), fmt(lead)))
            self.x = x
        else:
            self.line("G32 Z%s F%s" % (fmt(z), fmt(lead)), "G90 G33 Z%s K%s" % (fmt(z), fmt(lead)))
        self.z = z

    def css(self):
        clamp = self.r.choice([1200, 1500, 2000, 2500])
        s = self.r.choice([80, 120, 150, 200])
        self.line("G50 S%d" % clamp, "(G50 S%d)" % clamp)
        self.line("G96 S%d" % s, "G96 D%d S%d" % (clamp, s))
        for _ in range(self.r.randint(1, 4)):
            self.feed()
        self.line("G97 S%d" % self.rpm, "G97 S%d" % self.rpm)

    def preset(self):
        x, z = round(self.r.uniform(20.0, 60.0), 1), round(self.r.uniform(-10.0, 10.0), 1)
        self.line("G50 X%s Z%s" % (fmt(2 * x), fmt(z)), "G92 X%s Z%s" % (fmt(2 * x), fmt(z)))
        self.x, self.z = x, z

    def profile(self):
        """A monotone OD profile finished by G70 from a start point above it."""
        n = len(self.nc) + 1            # the line of the M99 / O100 sub
        start_x, start_z = 30.0, 3.0
        self.line("G00 X%s Z%s" % (fmt(2 * start_x), fmt(start_z)),
                  "G90 G0 X%s Z%s" % (fmt(2 * start_x), fmt(start_z)))
        self.x, self.z = start_x, start_z
        self.line("M99 P%d" % (n + 100), "O100 sub")
        x, z = round(self.r.uniform(3.0, 10.0), 1), 1.0
        body = [("N%d G00 X%s Z%s" % (n + 10, fmt(2 * x), fmt(z)), "G0 X%s Z%s" % (fmt(2 * x), fmt(z)))]
        body.append(("G01 Z%s" % fmt(0.0), "G1 Z0."))
        z = 0.0
        steps = self.r.randint(2, 5)
        for k in range(steps):
            dz = round(self.r.uniform(2.0, 8.0), 1)
            dx = round(self.r.uniform(0.0, 4.0), 1)
            kind = self.r.random()
            if kind < 0.3 and dx > 0.5:
                # a convex quarter arc: centre (x, z - dx), radius dx
                nz, nx = round(z - dx, 4), round(x + dx, 4)
                body.append(("G03 X%s Z%s I0 K%s" % (fmt(2 * nx), fmt(nz), fmt(-dx)),
                             "G3 X%s Z%s I0 K%s" % (fmt(2 * nx), fmt(nz), fmt(-dx))))
            elif kind < 0.5 and dx > 0.5:
                # a concave quarter arc: centre (x + dx, z), radius dx
                nz, nx = round(z - dx, 4), round(x + dx, 4)
                body.append(("G02 X%s Z%s I%s K0" % (fmt(2 * nx), fmt(nz), fmt(dx)),
                             "G2 X%s Z%s I%s K0" % (fmt(2 * nx), fmt(nz), fmt(dx))))
            else:
                nz, nx = round(z - dz, 4), round(min(x + dx, 28.0), 4)
                body.append(("G01 X%s Z%s" % (fmt(2 * nx), fmt(nz)), "G1 X%s Z%s" % (fmt(2 * nx), fmt(nz))))
            x, z = nx, nz
        last = ("N%d G01 X%s" % (n + 20, fmt(2 * start_x)), "G1 X%s" % fmt(2 * start_x))
        body.append(last)
        for a, b in body:
            self.line(a, b)
        self.line("(end of profile)", "O100 endsub")
        f = self.r.choice([0.1, 0.15])
        self.line("N%d G70 P%d Q%d F%s" % (n + 100, n + 10, n + 20, fmt(f)),
                  "F%s G70 Q100 X%s Z%s P1 D0" % (fmt(f), fmt(2 * start_x), fmt(start_z)))
        # G70 ends at A on a Fanuc, at the profile's end on LinuxCNC: the
        # next move goes to an absolute point, which is the same from either.
        self.rapid(absolute=True)

    def program(self):
        self.line("(vcnc-args: --dialect fanuc-lathe --machine machine.toml)",
                  "(vcnc-args: --dialect fanuc-lathe --machine machine.toml)")
        self.line("G18 G21 G40 G80 G99", "G18 G21 G40 G80 G7 G90 G95")
        self.line("S%d M03" % self.rpm, "S%d M3" % self.rpm)
        self.rapid()
        ops = [self.rapid, self.feed, self.feed, self.arc_ik, self.arc_r, self.thread]
        extras = [self.css, self.preset, self.profile]
        for _ in range(self.r.randint(4, 14)):
            if self.r.random() < 0.2:
                extra = self.r.choice(extras)
                if extra == self.profile:
                    # One profile a program: its sequence numbers are unique.
                    if self.profiled:
                        continue
                    self.profiled = True
                extra()
            else:
                self.r.choice(ops)()
        self.line("M30", "M2")
        return self.nc, self.ngc


def generate(seed):
    """(nc lines, ngc lines) of program `seed`."""
    return Gen(seed).program()


if __name__ == "__main__":
    nc, ngc = generate(1)
    for a, b in zip(nc, ngc):
        print("%-40s | %s" % (a, b))
