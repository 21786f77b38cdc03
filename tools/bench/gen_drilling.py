#!/usr/bin/env python3
"""Write an N-hole G83 peck-drilling program for `vcnc` benchmarks.

A grid of holes 0.5 mm apart, one position per block under G99 (R 1 mm,
Z -5.3 mm, Q 2 mm: three pecks a hole), so each hole is about ten events.
Usage: gen_drilling.py [N] OUT.nc
"""
import sys


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 2 else 100_000
    out = sys.argv[-1]
    with open(out, "w") as f:
        f.write("G21 G17 G90 G94\nS3000 M03\nG00 X0 Y0 Z10.\n")
        f.write("G99 G83 X0.000 Y0.000 Z-5.3 R1. Q2. F300.\n")
        for k in range(1, n):
            f.write(f"X{(k % 1600) * 0.5:.3f} Y{(k // 1600) * 0.5:.3f}\n")
        f.write("G80\nG00 Z10.\nM30\n")


if __name__ == "__main__":
    main()
