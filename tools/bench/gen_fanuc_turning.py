#!/usr/bin/env python3
"""Write an N-block turning program for `vcnc --dialect fanuc-lathe`
benchmarks: the same passes as gen_turning.py (the seed lathe's benchmark)
spelled for a Fanuc lathe — diameters with decimal points, U/W increments,
R arcs, rapids, feed per revolution at a constant spindle speed — ending
with M30. With --css the speed is G96 (a `spindle` event before every
move that changes the diameter). Usage: gen_fanuc_turning.py [N] [--css] OUT.nc
"""
import sys


def main() -> None:
    args = [a for a in sys.argv[1:] if a != "--css"]
    css = "--css" in sys.argv
    n = int(args[0]) if len(args) > 1 else 1_000_000
    out = args[-1]
    with open(out, "w") as f:
        head = ["G00 G18 G21 G40 G80 G99", "G50 S3000", "G96 S180 M03" if css else "G97 S1000 M03", "G00 X120. Z5."]
        f.write("\n".join(head) + "\n")
        written = len(head)
        p = 0
        while written < n - 1:
            d = 118.0 - (p % 50) * 2.0
            for line in (
                f"G00 X{d:.3f} Z2.",
                "G01 Z-80. F0.2",
                "G02 U4. W-2. R2.",
                "G01 U2.",
                "G00 Z2.",
            ):
                f.write(line + "\n")
                written += 1
                if written >= n - 1:
                    break
            p += 1
        f.write("M30\n")


if __name__ == "__main__":
    main()
