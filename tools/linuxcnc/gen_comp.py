#!/usr/bin/env python3
"""Generate the cutter-radius-compensation programs of
tests/fixtures/linuxcnc_comp, and the tool-centre points a Fanuc type-A
controller and LinuxCNC must both reach.

Both spellings (.nc for vcnc's fanuc dialect, .ngc for rs274) are the same
text: `G41 D<n>` names a tool in both (vcnc's machine file holds its radius,
LinuxCNC's tool table its diameter). Line 1 of both is
`(vcnc-args: --dialect fanuc --machine machine.toml)`.

A program: optional work offset (G10 L2 P2 + G55), then one or two closed
contours, each

    G0 to the start point S at a safe height, G1 down to the cutting depth,
    [G41/G42 D<n> alone in a block, sometimes]
    G41/G42 D<n> G1 to P0 (the start-up block; P0 is the contour's start),
    the contour: lines and arcs (I/J/K centres) back to P0,
    G40 G1 to the end point E (sometimes G40 alone, then G1 to E),
    G0 up to the safe height,

and M2. Contours (all vertices and centres exact at 4 decimals): rectangles,
parallelograms, trapezoids, rhombi and right triangles with Pythagorean
(3-4-5) edges, L, T and plus shapes (concave corners), obrounds, with
optional tangent fillets (their tangent points are exact: every filleted
edge has a 3-4-5 or axis direction) and semicircular bumps or notches on a
side (arcs meeting the side at 90 degrees). Run counter-clockwise or
clockwise, with G41 or G42, so the tool is inside (pocket) or outside
(profile). Mostly G17, some G18 (Z-X plane, Y is the depth). No G19:
LinuxCNC refuses compensation outside the XY and XZ planes.

The points (see tests/fixtures/linuxcnc_comp/README.md for the rules): the
uncompensated moves before G41 and after G40, the start-up point, the end
point of every compensated block whose junction with the next block is an
inside corner (intersection of the offset paths) or tangent (the point
offset by r along the normal), the exit point when the junction with the
cancel block is not an inside corner (or G40 has no motion), and E.
`generate()` returns (ngc, nc, points) with points = [(line, kind,
(x, y, z) in mm, machine)]; make_ext_fixtures.py checks that they occur in
order among the end points of rs274's moves and writes rs274's values.

Usage: gen_comp.py [--count 40] [--seed 20240803] [--out DIR]
"""

import argparse
import math
import os
import random
import sys
from fractions import Fraction as F

DEFAULT_SEED = 20240803
DEFAULT_COUNT = 40
DEFAULT_OUT = "/tmp/vcnc_linuxcnc_comp"
ARGS_LINE = "(vcnc-args: --dialect fanuc --machine machine.toml)"

# n -> (length mm, RADIUS mm); LinuxCNC's table has the diameter (in inches)
TOOLS = {1: (0.0, 5.0), 2: (0.0, 3.0), 3: (0.0, 6.35), 4: (0.0, 2.5)}

PYTH = [(3, 4), (4, 3)]          # 3-4-5 directions (with signs and axes)


def fmt(v):
    """A Fraction (mm) with at most 4 decimals -> a word value with a point."""
    q = v * 10000
    if q.denominator != 1:
        raise ValueError("%s is not exact at 4 decimals" % v)
    u = int(q)
    sign = "-" if u < 0 else ""
    whole, frac = divmod(abs(u), 10000)
    return "%s%d.%s" % (sign, whole, ("%04d" % frac).rstrip("0") or "0")


def exact(v):
    return (v * 10000).denominator == 1


# -- geometry (plane coordinates (u, v): G17 (X, Y), G18 (Z, X)) ------------------

def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1])


def mul(a, k):
    return (a[0] * k, a[1] * k)


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def left(t):
    return (-t[1], t[0])


def unit_exact(d):
    """Exact unit vector of an integer/fraction vector, or None."""
    n2 = d[0] * d[0] + d[1] * d[1]
    n = F(math.isqrt(int(n2 * 10 ** 8)), 10 ** 4)
    if n * n != n2:
        return None
    return (F(d[0]) / n, F(d[1]) / n)


def unit(d):
    n = math.hypot(d[0], d[1])
    return (d[0] / n, d[1] / n)


class Line:
    def __init__(self, a, b):
        self.a, self.b = a, b

    def t0(self):
        return unit((float(self.b[0] - self.a[0]), float(self.b[1] - self.a[1])))

    t1 = t0

    def offset(self, s, r):
        n = mul(left(self.t0()), s * r)
        return ("line", add(fl(self.a), n), self.t0())


class Arc:
    def __init__(self, a, b, c, ccw):
        self.a, self.b, self.c, self.ccw = a, b, c, ccw

    def radius(self):
        return math.hypot(float(self.a[0] - self.c[0]), float(self.a[1] - self.c[1]))

    def tangent(self, p):
        rad = unit((float(p[0] - self.c[0]), float(p[1] - self.c[1])))
        return left(rad) if self.ccw else mul(left(rad), -1)

    def t0(self):
        return self.tangent(self.a)

    def t1(self):
        return self.tangent(self.b)

    def offset(self, s, r):
        # left of a CCW arc is its centre
        rr = self.radius() - s * r * (1 if self.ccw else -1)
        return ("circle", fl(self.c), rr)


def fl(p):
    return (float(p[0]), float(p[1]))


def intersect(o1, o2, near):
    """Intersection of two offset paths nearest to `near`."""
    cands = []
    if o1[0] == "line" and o2[0] == "line":
        p, d = o1[1], o1[2]
        q, e = o2[1], o2[2]
        den = cross(d, e)
        if abs(den) < 1e-12:
            return None
        t = cross(sub(q, p), e) / den
        cands = [add(p, mul(d, t))]
    elif o1[0] == "circle" and o2[0] == "circle":
        c1, r1 = o1[1], o1[2]
        c2, r2 = o2[1], o2[2]
        d = math.hypot(*sub(c2, c1))
        if d < 1e-12:
            return None
        a = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
        h2 = r1 * r1 - a * a
        if h2 < 0:
            return None
        h = math.sqrt(h2)
        ex = mul(sub(c2, c1), 1 / d)
        m = add(c1, mul(ex, a))
        cands = [add(m, mul(left(ex), h)), add(m, mul(left(ex), -h))]
    else:
        ln, ci = (o1, o2) if o1[0] == "line" else (o2, o1)
        p, d = ln[1], ln[2]
        c, rr = ci[1], ci[2]
        f = sub(p, c)
        b = dot(f, d)
        cc = dot(f, f) - rr * rr
        disc = b * b - cc
        if disc < 0:
            return None
        sq = math.sqrt(disc)
        cands = [add(p, mul(d, -b + sq)), add(p, mul(d, -b - sq))]
    return min(cands, key=lambda x: math.hypot(*sub(x, near)))


def junction(t1, t2, s):
    """'inside', 'outside' or 'tangent' for the tool on side s (+1 left)."""
    c = cross(t1, t2)
    if abs(c) < 1e-9:
        if dot(t1, t2) < 0:
            raise ValueError("reversal")
        return "tangent"
    return "inside" if s * c > 0 else "outside"


# -- shapes ----------------------------------------------------------------------

def pyth_dir(rng):
    a, b = rng.choice(PYTH)
    return (a * rng.choice([1, -1]), b * rng.choice([1, -1]))


def polygon(rng):
    """A CCW polygon with integer vertices (mm) and its kind."""
    kind = rng.choice(["rect", "rect", "para", "trap", "rhombus", "tri", "L", "T",
                       "plus"])
    k = rng.randint(4, 9)
    w = rng.randint(30, 90)
    h = rng.randint(25, 70)
    if kind == "rect":
        pts = [(0, 0), (w, 0), (w, h), (0, h)]
    elif kind == "para":
        a, b = rng.choice(PYTH)
        pts = [(0, 0), (w, 0), (w + a * k, b * k), (a * k, b * k)]
    elif kind == "trap":
        a, b = rng.choice(PYTH)
        w = max(w, 2 * a * k + 20)
        pts = [(0, 0), (w, 0), (w - a * k, b * k), (a * k, b * k)]
    elif kind == "rhombus":
        a, b = rng.choice(PYTH)
        pts = [(0, -b * k), (a * k, 0), (0, b * k), (-a * k, 0)]
    elif kind == "tri":
        a, b = rng.choice(PYTH)
        k = rng.randint(8, 14)
        pts = [(0, 0), (a * k, 0), (0, b * k)]
    elif kind == "L":
        cw, ch = rng.randint(15, w - 15), rng.randint(12, h - 12)
        pts = [(0, 0), (w, 0), (w, ch), (cw, ch), (cw, h), (0, h)]
    elif kind == "T":
        w = max(w, 60)
        s = rng.randint(15, w // 2 - 8)
        stem = rng.randint(20, 40)
        pts = [(s, 0), (w - s, 0), (w - s, stem), (w, stem), (w, stem + h // 2 + 10),
               (0, stem + h // 2 + 10), (0, stem), (s, stem)]
    else:   # plus
        a = rng.randint(15, 25)
        b = rng.randint(15, 25)
        pts = [(a, 0), (2 * a, 0), (2 * a, b), (3 * a, b), (3 * a, 2 * b), (2 * a, 2 * b),
               (2 * a, 3 * b), (a, 3 * b), (a, 2 * b), (0, 2 * b), (0, b), (a, b)]
    return kind, [(F(x), F(y)) for x, y in pts]


def fillet(p_prev, v, p_next, f):
    """Tangent points and centre of a fillet of radius f at v, or None."""
    d_in = unit_exact(sub(v, p_prev))
    d_out = unit_exact(sub(p_next, v))
    if d_in is None or d_out is None:
        return None
    c = cross(d_in, d_out)
    t = f * abs(c) / (1 + dot(d_in, d_out))
    a = sub(v, mul(d_in, t))
    b = add(v, mul(d_out, t))
    sign = 1 if c > 0 else -1
    centre = add(a, mul(left(d_in), f * sign))
    if not all(exact(x) for x in a + b + centre):
        return None
    return a, b, centre, c > 0, t


def build(rng, pts):
    """Elements of the CCW contour with optional fillets and one side feature."""
    n = len(pts)
    fil = [None] * n
    for i in range(n):
        if rng.random() < 0.45:
            f = F(rng.choice([5, 6, 8, 10, 12, 15, 20]))
            res = fillet(pts[i - 1], pts[i], pts[(i + 1) % n], f)
            if res:
                fil[i] = res
    # trims must leave every edge a length of 6 mm at least
    for i in range(n):
        j = (i + 1) % n
        length = math.hypot(*fl(sub(pts[j], pts[i])))
        trims = (fil[i][4] if fil[i] else 0) + (fil[j][4] if fil[j] else 0)
        if length - float(trims) < 6:
            fil[i] = fil[j] = None
    elems = []
    for i in range(n):
        j = (i + 1) % n
        a = fil[i][1] if fil[i] else pts[i]
        b = fil[j][0] if fil[j] else pts[j]
        elems.append(Line(a, b))
        if fil[j]:
            fa, fb, c, ccw, _ = fil[j]
            elems.append(Arc(fa, fb, c, ccw))
    # a semicircular bump or notch in the middle of one axis-parallel line
    if rng.random() < 0.35:
        cand = [k for k, e in enumerate(elems) if isinstance(e, Line)
                and (e.a[0] == e.b[0] or e.a[1] == e.b[1])
                and math.hypot(*fl(sub(e.b, e.a))) >= 40]
        if cand:
            k = rng.choice(cand)
            e = elems[k]
            length = math.hypot(*fl(sub(e.b, e.a)))
            d = unit_exact(sub(e.b, e.a))
            mid = mul(add(e.a, e.b), F(1, 2))
            rad = F(rng.randint(6, max(6, min(15, int(length / 2) - 10))))
            p1 = sub(mid, mul(d, rad))
            p2 = add(mid, mul(d, rad))
            bump = rng.random() < 0.5      # outward = to the right of a CCW edge
            elems[k:k + 1] = [Line(e.a, p1), Arc(p1, p2, mid, bump), Line(p2, e.b)]
    return elems


def obround(rng):
    L = F(rng.randint(30, 80))
    R = F(rng.randint(10, 25))
    return [Line((F(0), -R), (L, -R)), Arc((L, -R), (L, R), (L, F(0)), True),
            Line((L, R), (F(0), R)), Arc((F(0), R), (F(0), -R), (F(0), F(0)), True)]


def reverse(elems):
    out = []
    for e in reversed(elems):
        if isinstance(e, Line):
            out.append(Line(e.b, e.a))
        else:
            out.append(Arc(e.b, e.a, e.c, not e.ccw))
    return out


def split_start(elems, rng):
    """Start the contour in the middle of a line (mostly), at a corner, or at
    an arc's start."""
    n = len(elems)
    r = rng.random()
    lines = [i for i, e in enumerate(elems) if isinstance(e, Line)
             and math.hypot(*fl(sub(e.b, e.a))) >= 16]
    if r < 0.7 and lines:
        i = rng.choice(lines)
        e = elems[i]
        mid = mul(add(e.a, e.b), F(1, 2))
        rest = elems[i + 1:] + elems[:i]
        return [Line(mid, e.b)] + rest + [Line(e.a, mid)]
    i = rng.randrange(n)
    return elems[i:] + elems[:i]


# -- the Fanuc type-A points -------------------------------------------------------

def offsets_ok(elems, s, r, pts):
    """Each offset element keeps its direction between its two corner points."""
    for e, (p, q) in zip(elems, pts):
        if isinstance(e, Line):
            if dot(sub(q, p), e.t0()) < 2.0:
                return False
        else:
            rr = e.radius() - s * r * (1 if e.ccw else -1)
            if rr < 1.0:
                return False
            c = fl(e.c)
            a0 = math.atan2(*reversed(sub(fl(e.a), c)))
            a1 = math.atan2(*reversed(sub(fl(e.b), c)))
            b0 = math.atan2(*reversed(sub(p, c)))
            b1 = math.atan2(*reversed(sub(q, c)))
            sweep = (a1 - a0) % (2 * math.pi) if e.ccw else (a0 - a1) % (2 * math.pi)
            osweep = (b1 - b0) % (2 * math.pi) if e.ccw else (b0 - b1) % (2 * math.pi)
            if osweep < 0.05 or osweep > sweep + 1e-6:
                return False
    return True


def corner_point(e1, e2, s, r, kind, p):
    if kind == "inside":
        x = intersect(e1.offset(s, r), e2.offset(s, r), p)
        if x is None:
            raise ValueError("no intersection")
        return x
    return add(fl(p), mul(left(e2.t0()), s * r))


def fanuc_points(S, elems, E, s, r, exit_mode):
    """(kind, element index or 'start'/'exit', point) of the common points,
    and the corner points used to check the offset path."""
    ts = unit(sub(fl(elems[0].a), fl(S)))
    k0 = junction(ts, elems[0].t0(), s)
    P0 = elems[0].a
    if k0 == "inside":
        start_line = Line(S, P0)
        p_start = intersect(start_line.offset(s, r), elems[0].offset(s, r), fl(P0))
        if p_start is None:
            raise ValueError("start-up")
    else:
        p_start = add(fl(P0), mul(left(elems[0].t0()), s * r))
    out = [("start_up", -1, p_start)]
    ends = []
    prev = p_start
    for i in range(len(elems) - 1):
        e1, e2 = elems[i], elems[i + 1]
        kind = junction(e1.t1(), e2.t0(), s)
        if kind == "outside":
            end_here = add(fl(e1.b), mul(left(e1.t1()), s * r))
            start_next = add(fl(e1.b), mul(left(e2.t0()), s * r))
        else:
            end_here = start_next = corner_point(e1, e2, s, r, kind, e1.b)
            out.append(("inside_corner" if kind == "inside" else "tangent", i, end_here))
        ends.append((prev, end_here))
        prev = start_next
    last = elems[-1]
    perp = add(fl(last.b), mul(left(last.t1()), s * r))
    ends.append((prev, perp))
    if exit_mode == "alone":
        out.append(("exit", len(elems) - 1, perp))
    else:
        te = unit(sub(fl(E), fl(last.b)))
        if junction(last.t1(), te, s) != "inside":
            out.append(("exit", len(elems) - 1, perp))
    return out, ends


# -- programs ----------------------------------------------------------------------

class CompProgram:
    def __init__(self, rng):
        self.rng = rng
        self.lines = []
        self.points = []
        self.origin = (F(0), F(0), F(0))
        self.plane = "G17"
        self.feed_set = False

    def emit(self, text):
        self.lines.append(text)
        return len(self.lines)

    def axes(self):
        # plane axes (u, v) and depth axis as indices into XYZ
        return ((0, 1), 2) if self.plane == "G17" else ((2, 0), 1)

    def machine(self, u, v, depth):
        (a, b), c = self.axes()
        p = [None, None, None]
        p[a], p[b], p[c] = u, v, depth
        return tuple(float(p[i] + self.origin[i]) for i in range(3))

    def words(self, pts):
        """{axis index: program value} -> words in X, Y, Z order."""
        return ["XYZ"[i] + fmt(pts[i]) for i in sorted(pts)]

    def contour(self):
        rng = self.rng
        (a, b), c = self.axes()
        tool = rng.choice(sorted(TOOLS))
        r = TOOLS[tool][1]
        for _attempt in range(500):
            if rng.random() < 0.15:
                elems = obround(rng)
            else:
                _kind, pts = polygon(rng)
                elems = build(rng, pts)
            if rng.random() < 0.5:
                elems = reverse(elems)
            ccw = self.orientation(elems) > 0
            inside = rng.random() < 0.5
            # tool on the left of a CCW contour is inside it
            s = (1 if inside else -1) * (1 if ccw else -1)
            elems = split_start(elems, rng)
            # shift the shape somewhere
            shift = (F(rng.randint(-120, 120)), F(rng.randint(-100, 100)))
            elems = [move_elem(e, shift) for e in elems]
            P0 = elems[0].a
            S, E, exit_mode = self.entry_exit(elems, s, r, inside)
            if S is None:
                continue
            try:
                pts, ends = fanuc_points(S, elems, E, s, r, exit_mode)
            except ValueError:
                continue
            if not offsets_ok(elems, s, r, ends):
                continue
            if not self.arcs_ok(elems, s, r):
                continue
            break
        else:
            raise RuntimeError("no contour")
        depth = F(rng.randint(-15, -1))
        safe = F(rng.randint(5, 30))
        feed = rng.choice(["F200.", "F350.", "F500.", "F120.", "F800."])
        g = "G41" if s > 0 else "G42"
        d = {a: S[0], b: S[1]}
        line = self.emit(" ".join(["G0"] + self.words(d)))
        self.points.append((line, "uncompensated", self.machine(S[0], S[1], self.cur_depth)))
        line = self.emit(" ".join(["G0"] + self.words({c: safe})))
        self.cur_depth = safe
        self.points.append((line, "uncompensated", self.machine(S[0], S[1], safe)))
        line = self.emit(" ".join(["G1"] + self.words({c: depth}) + [feed]))
        self.cur_depth = depth
        self.points.append((line, "uncompensated", self.machine(S[0], S[1], depth)))
        alone = rng.random() < 0.25
        if alone:
            self.emit("%s D%d" % (g, tool))
            head = ["G1"]
        else:
            head = [g, "D%d" % tool, "G1"] if rng.random() < 0.6 else ["G1", g, "D%d" % tool]
        start_line = self.emit(" ".join(head + self.words({a: P0[0], b: P0[1]})))
        elem_lines = []
        for e in elems:
            w = self.words({a: e.b[0], b: e.b[1]})
            if isinstance(e, Line):
                elem_lines.append(self.emit(" ".join(["G1"] + w)))
            else:
                ij = {a: "I" if a == 0 else "K", b: "J" if b == 1 else "I"}
                cw = ["%s%s" % (ij[a], fmt(e.c[0] - e.a[0])),
                      "%s%s" % (ij[b], fmt(e.c[1] - e.a[1]))]
                cw.sort()
                elem_lines.append(self.emit(" ".join(["G3" if e.ccw else "G2"] + w + cw)))
        if exit_mode == "alone":
            self.emit("G40")
            end_line = self.emit(" ".join(["G1"] + self.words({a: E[0], b: E[1]})))
        else:
            end_line = self.emit(" ".join(["G40", "G1"] + self.words({a: E[0], b: E[1]})))
        for kind_, idx, p in pts:
            line = start_line if idx == -1 else elem_lines[idx]
            self.points.append((line, kind_, self.machine(p[0], p[1], depth)))
        self.points.append((end_line, "cancel", self.machine(E[0], E[1], depth)))
        line = self.emit(" ".join(["G0"] + self.words({c: safe})))
        self.points.append((line, "uncompensated", self.machine(E[0], E[1], safe)))
        self.cur_depth = safe

    @staticmethod
    def orientation(elems):
        area = 0.0
        for e in elems:
            area += cross(fl(e.a), fl(e.b))
            if isinstance(e, Arc):
                # add the circular segment's signed area
                rr = e.radius()
                c = fl(e.c)
                a0 = math.atan2(*reversed(sub(fl(e.a), c)))
                a1 = math.atan2(*reversed(sub(fl(e.b), c)))
                sw = (a1 - a0) % (2 * math.pi) if e.ccw else -((a0 - a1) % (2 * math.pi))
                area += rr * rr * (sw - math.sin(sw))
        return area

    def arcs_ok(self, elems, s, r):
        for e in elems:
            if isinstance(e, Arc):
                rr = e.radius() - s * r * (1 if e.ccw else -1)
                if rr < r * 0.2 + 1.0:
                    return False
        return True

    def entry_exit(self, elems, s, r, inside):
        """Start point S and end point E (exact), exit mode."""
        rng = self.rng
        P0 = elems[0].a
        t0 = unit_exact(sub(elems[0].b, elems[0].a)) if isinstance(elems[0], Line) else None
        L = F(rng.choice([8, 10, 12, 15, 20]))
        from_tool_side = True
        if t0 is None or rng.random() < 0.25:
            # from a point on the tool side, not perpendicular
            n = elems[0].t0()
            side = left(n)
            cand = add(fl(P0), add(mul(side, s * float(L)), mul(n, -float(L) * rng.choice([0.5, 1.0, -0.5]))))
            S = (F(round(cand[0])), F(round(cand[1])))
        else:
            kind = rng.random()
            nrm = left(t0)
            if kind < 0.4:
                S = add(P0, mul(nrm, s * L))                      # perpendicular
            elif kind < 0.6:
                S = add(add(P0, mul(nrm, s * L)), mul(t0, -L))    # oblique
            elif kind < 0.75:
                S = add(P0, mul(t0, -L))                          # along the side
                from_tool_side = False
            else:
                # from behind, on the other side of the line: an outside
                # start-up (the block turns away from the tool side)
                S = add(add(P0, mul(nrm, -s * L / 2)), mul(t0, -L))
                from_tool_side = False
        if not all(exact(x) for x in S):
            return None, None, None
        if math.hypot(*fl(sub(P0, S))) < 2.5 * r:
            return None, None, None
        if inside and from_tool_side and not self.point_inside(elems, S):
            return None, None, None
        last = elems[-1]
        tl = last.t1()
        nl = left(tl)
        mode = rng.random()
        if mode < 0.2:
            exit_mode = "alone"
            cand = add(fl(last.b), mul(nl, s * float(L)))
        elif mode < 0.5:
            exit_mode = "move"
            cand = add(fl(last.b), mul(nl, s * float(L)))        # inside corner
        elif mode < 0.75:
            exit_mode = "move"
            cand = add(fl(last.b), mul(tl, float(L)))             # straight on
        else:
            exit_mode = "move"
            cand = add(fl(last.b), add(mul(tl, float(L)), mul(nl, -s * float(L) * 0.5)))
        E = (F(round(cand[0] * 2), 2), F(round(cand[1] * 2), 2))
        if math.hypot(*fl(sub(E, last.b))) < 2.5 * r:
            return None, None, None
        if inside and not self.point_inside(elems, E):
            return None, None, None
        return S, E, exit_mode

    @staticmethod
    def point_inside(elems, p):
        # ray casting on the polygon of element end points (arcs as chords,
        # good enough for the points we test, which are away from arcs)
        x, y = fl(p)
        inside = False
        for e in elems:
            (x1, y1), (x2, y2) = fl(e.a), fl(e.b)
            if (y1 > y) != (y2 > y):
                xi = x1 + (y - y1) * (x2 - x1) / (y2 - y1)
                if xi > x:
                    inside = not inside
        return inside


def move_elem(e, d):
    if isinstance(e, Line):
        return Line(add(e.a, d), add(e.b, d))
    return Arc(add(e.a, d), add(e.b, d), add(e.c, d), e.ccw)


def generate(index, seed=DEFAULT_SEED):
    rng = random.Random("comp:%d:%d" % (seed, index))
    p = CompProgram(rng)
    p.emit(ARGS_LINE)
    p.plane = "G18" if index % 5 == 0 else "G17"
    p.emit("G21 %s G90 G94" % p.plane)
    p.cur_depth = F(0)
    if rng.random() < 0.35:
        o = (F(rng.randint(-60, 60)), F(rng.randint(-60, 60)), F(rng.randint(-20, 20)))
        p.emit("G10 L2 P2 X%s Y%s Z%s" % tuple(fmt(v) for v in o))
        p.emit("G55")
        p.origin = o
        # the machine stays at 0: its program position changes
        p.cur_depth = -o[p.axes()[1]]
    for _ in range(rng.choice([1, 1, 2])):
        p.contour()
    p.emit("M2")
    return p.lines, list(p.lines), p.points


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
