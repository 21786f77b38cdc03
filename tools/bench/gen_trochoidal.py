#!/usr/bin/env python3
"""Write an N-block trochoidal clearing program of short segments (benchmark
and cross-check input).

Usage: gen_trochoidal.py [N] [OUT.nc]     (N defaults to 100,000; OUT to stdout)

The tool runs loops of radius 1.5 mm whose centre advances 0.3 mm per loop
along X, each loop flattened into 0.1 mm chords (about 94 per loop) at F6000
(100 mm/s): every block is a G1 of 0.1 mm with a 3.8-degree corner, so the
time is set by the centripetal limit of the loops and by acceleration, not
by the feed. Rows of 200 mm are joined by a short linking move in Y.
Exactly N lines: a `G21 G17 G90 G94` header, a positioning move and a
plunge, the chords, `M2` last. Deterministic, decimal points everywhere.
"""

import math
import sys

R = 1.5
CHORD = 0.1
ADVANCE = 0.3
ROW = 200.0
FEED = "F6000.0"


def blocks():
    per_loop = max(8, int(round(2 * math.pi * R / CHORD)))
    yield "G0 X0.000 Y0.000 Z5.0"
    yield "G1 Z-1.0 F600.0"
    row = 0
    while True:
        y0 = row * 4.0
        cx = 0.0
        sign = 1.0 if row % 2 == 0 else -1.0
        while cx < ROW:
            for k in range(1, per_loop + 1):
                a = 2 * math.pi * k / per_loop
                x = (cx + ADVANCE * k / per_loop) - R * math.cos(a) + R
                y = y0 + R * math.sin(a)
                x = x if sign > 0 else ROW - x
                yield "G1 X%.4f Y%.4f %s" % (x, y, FEED)
            cx += ADVANCE
        row += 1
        yield "G1 Y%.4f" % (row * 4.0)


def main(argv):
    n = int(argv[1]) if len(argv) > 1 else 100_000
    if n < 4:
        sys.exit("N must be at least 4")
    out = open(argv[2], "w") if len(argv) > 2 else sys.stdout
    lines = ["G21 G17 G90 G94"]
    gen = blocks()
    for _ in range(n - 2):
        lines.append(next(gen))
    lines.append("M2")
    out.write("\n".join(lines))
    out.write("\n")
    if out is not sys.stdout:
        out.close()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
