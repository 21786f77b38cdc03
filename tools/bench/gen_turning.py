#!/usr/bin/env python3
"""Write an N-block turning program for `vcnc --dialect lathe` benchmarks.

Roughing passes in diameters (G23) with absolute X/Z, incremental U/W,
R arcs and rapids, ending with M30. Usage: gen_turning.py [N] OUT.nc
"""
import sys


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 2 else 1_000_000
    out = sys.argv[-1]
    with open(out, "w") as f:
        f.write("G23\nG90 G94\nG00 X120 Z5\n")
        written = 3
        p = 0
        while written < n - 1:
            d = 118.0 - (p % 50) * 2.0
            for line in (
                f"G00 X{d:.3f} Z2.000",
                "G01 Z-80.000 F200",
                "G02 U4.000 W-2.000 R2.000",
                "G01 U2.000",
                "G00 Z2.000",
            ):
                f.write(line + "\n")
                written += 1
                if written >= n - 1:
                    break
            p += 1
        f.write("M30\n")


if __name__ == "__main__":
    main()
