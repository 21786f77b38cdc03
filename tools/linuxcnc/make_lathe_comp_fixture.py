#!/usr/bin/env python3
"""Write tests/fixtures/linuxcnc_lathe_comp/orientations.json: the first
three compensated feed end points rs274 gives for orientation.ngc (G42 on
a lathe, tool 2 with a 0.4 mm nose radius) for each tool orientation Q1-Q9,
so that `--dialect linuxcnc-lathe` can be checked against LinuxCNC's own
lathe compensation (crates/vcnc_interp/tests/linuxcnc_dialect.rs).

rs274 reads the tool table in inches, D the nose DIAMETER.

Usage: make_lathe_comp_fixture.py [--rs274 PATH]
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
FOLDER = os.path.join(os.path.dirname(os.path.dirname(HERE)), "tests", "fixtures",
                      "linuxcnc_lathe_comp")
NOSE_RADIUS_MM = 0.4


def feeds(rs274, program, q):
    with tempfile.TemporaryDirectory(prefix="vcnc_rs274_") as tmp:
        tbl = os.path.join(tmp, "tool.tbl")
        with open(tbl, "w") as f:
            f.write("T2 P2 D%.9f Q%d X0 Z0 ;\n" % (2 * NOSE_RADIUS_MM / 25.4, q))
        out = subprocess.run([rs274, "-g", "-t", tbl, program], input="",
                             capture_output=True, text=True,
                             env=dict(os.environ, HOME=tmp), cwd=tmp).stdout
    points = []
    for line in out.splitlines():
        if "STRAIGHT_FEED(" in line:
            x, _, z = (float(v) for v in re.findall(r"-?\d+\.\d+", line)[:3])
            points.append({"x": x, "z": z})
    return points[:3]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rs274", default=shutil.which("rs274"))
    a = ap.parse_args()
    if not a.rs274:
        sys.exit("needs LinuxCNC's rs274: apt-get install linuxcnc-uspace")
    program = os.path.join(FOLDER, "orientation.ngc")
    table = {str(q): feeds(a.rs274, program, q) for q in range(1, 10)}
    with open(os.path.join(FOLDER, "orientations.json"), "w") as f:
        json.dump({"nose_radius_mm": NOSE_RADIUS_MM, "feeds_by_q": table}, f, indent=1)
        f.write("\n")
    print("9 orientations -> %s" % FOLDER)


if __name__ == "__main__":
    main()
