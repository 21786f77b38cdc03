#!/usr/bin/env python3
"""Write an N-block 3-axis surfacing program (benchmark input).

Usage: gen_surfacing.py [N] [OUT.nc]     (N defaults to 1,000,000; OUT to stdout)

The program is a zig-zag raster over a 200 x 150 mm wavy surface: every block
is one G1 segment of 0.5 mm along X with a small Z change (modal G1, X and Z
words only), passes are joined by a 0.5 mm step-over in Y, and each new layer
(0.25 mm deeper) starts with a few G0 moves (retract, reposition, plunge).
Exactly N lines, one block per line: a `G21 G17 G90 G94` header, the moves,
`M2` last. Every number carries a decimal point, so vcnc's fanuc dialect and
LinuxCNC's rs274 read it the same way. Deterministic: no randomness.
"""

import math
import sys

X0, X1 = -100.0, 100.0      # raster extent (mm)
Y0, Y1 = -75.0, 75.0
STEP = 0.5                  # segment length along X and step-over in Y
LAYER_DZ = 0.25             # depth added per layer
SAFE_Z = 10.0
FEED = "F1500.0"


def surface(x, y):
    return 1.5 * math.sin(x / 17.0) * math.cos(y / 23.0) + 0.4 * math.sin((x + y) / 7.0) - 2.0


def blocks():
    nx = int(round((X1 - X0) / STEP))
    ny = int(round((Y1 - Y0) / STEP))
    layer = 0
    while True:
        depth = -LAYER_DZ * layer
        y = Y0
        x = X0
        # a few rapids per layer: retract, go over the start, plunge near it
        yield "G0 Z%.1f" % SAFE_Z
        yield "G0 X%.3f Y%.3f" % (x, y)
        yield "G0 Z%.4f" % (surface(x, y) + depth + 1.0)
        yield "G1 Z%.4f %s" % (surface(x, y) + depth, FEED)
        for j in range(ny + 1):
            y = Y0 + j * STEP
            if j > 0:
                # step-over at the end of the previous pass
                yield "G1 Y%.3f Z%.4f" % (y, surface(x, y) + depth)
            forward = j % 2 == 0
            for i in range(1, nx + 1):
                k = i if forward else nx - i
                x = X0 + k * STEP
                yield "X%.3f Z%.4f" % (x, surface(x, y) + depth)
        layer += 1


def main(argv):
    n = int(argv[1]) if len(argv) > 1 else 1_000_000
    if n < 3:
        sys.exit("N must be at least 3")
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
