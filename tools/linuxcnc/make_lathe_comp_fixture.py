#!/usr/bin/env python3
"""Write tests/fixtures/linuxcnc_lathe_comp/orientations.json: the first
three compensated feed end points rs274 gives for orientation.ngc (G42 on
a lathe, tool 2 with a 0.4 mm nose radius) for each tool orientation Q1-Q9,
so that `--dialect linuxcnc-lathe` can be checked against LinuxCNC's own
lathe compensation (crates/vcnc_interp/tests/behaviour/linuxcnc_dialect.rs).

rs274 reads the tool table in inches, D the nose DIAMETER.

Usage: make_lathe_comp_fixture.py [--rs274 PATH]
"""
import argparse
import json
import os
import re
import shutil
import sys

import rs274_events as rv

HERE = os.path.dirname(os.path.abspath(__file__))
FOLDER = os.path.join(os.path.dirname(os.path.dirname(HERE)), "tests", "fixtures",
                      "linuxcnc_lathe_comp")
NOSE_RADIUS_MM = 0.4


def feeds(rs274, lines, q):
    table = "T2 P2 D%.9f Q%d X0 Z0 ;\n" % (2 * NOSE_RADIUS_MM / 25.4, q)
    out = rv.run_rs274(rs274, lines, table, "orientation Q%d" % q)
    points = []
    for line in out.splitlines():
        if "STRAIGHT_FEED(" in line:
            x, _, z = (float(v) for v in re.findall(r"-?\d+\.\d+", line.split("(", 1)[1])[:3])
            points.append({"x": x, "z": z})
    return points[:3]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rs274", default=shutil.which("rs274"))
    a = ap.parse_args()
    if not a.rs274:
        sys.exit("needs LinuxCNC's rs274: apt-get install linuxcnc-uspace")
    with open(os.path.join(FOLDER, "orientation.ngc")) as f:
        lines = f.read().split("\n")[:-1]
    table = {str(q): feeds(a.rs274, lines, q) for q in range(1, 10)}
    with open(os.path.join(FOLDER, "orientations.json"), "w") as f:
        json.dump({"nose_radius_mm": NOSE_RADIUS_MM, "feeds_by_q": table}, f, indent=1)
        f.write("\n")
    print("9 orientations -> %s" % FOLDER)


if __name__ == "__main__":
    main()
