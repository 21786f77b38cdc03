#!/usr/bin/env python3
"""Write tests/fixtures/linuxcnc_comp_dynamic: the programs of
tests/fixtures/linuxcnc_comp spelled with LinuxCNC's dynamic cutter
compensation, `G41.1 D<diameter>` / `G42.1 D<diameter>` in place of
`G41 D<tool>` / `G42 D<tool>` (the diameter is the tool's, from
gen_comp.TOOLS), with the same tool-centre points.

For each program rs274 runs both spellings (the tool table of gen_comp for
both) and this script stops unless their canonical motion calls are the
same text: rs274 itself says that G41.1 D<2r> is G41 with a tool of radius
r, so the points the original programs must reach (checked against rs274
by make_ext_fixtures.py --set comp) are the new programs' too. The test
(`crates/vcnc/tests/behaviour/fixtures.rs`,
`linuxcnc_dynamic_compensation_points_are_reached`) runs them under
`--dialect linuxcnc`.

Usage: make_dynamic_comp_fixtures.py [--rs274 PATH]
"""

import argparse
import os
import re
import shutil
import sys

import gen_comp
import rs274_events as rv
from make_ext_fixtures import FIXTURES

SOURCE = os.path.join(FIXTURES, "linuxcnc_comp")
FOLDER = os.path.join(FIXTURES, "linuxcnc_comp_dynamic")
MOTION = ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED")


def dynamic(line):
    """`G41 D3` -> `G41.1 D12.7` (tool 3's diameter in mm)."""
    def repl(m):
        diameter = 2 * gen_comp.TOOLS[int(m.group(2))][1]
        return "G4%s.1 D%s" % (m.group(1), ("%.4f" % diameter).rstrip("0").rstrip("."))
    return re.sub(r"G4([12]) D(\d+)", repl, line)


def motion(out):
    return [l.split(None, 2)[2] for l in out.splitlines()
            if any(c in l for c in MOTION)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rs274", default=shutil.which("rs274"))
    a = ap.parse_args()
    if not a.rs274:
        sys.exit("needs LinuxCNC's rs274: apt-get install linuxcnc-uspace")
    os.makedirs(FOLDER, exist_ok=True)
    table = rv.tool_table_text(gen_comp.TOOLS)
    stems = sorted(f[:-4] for f in os.listdir(SOURCE) if f.endswith(".ngc"))
    for stem in stems:
        with open(os.path.join(SOURCE, stem + ".ngc")) as f:
            ngc = f.read().split("\n")[:-1]
        new = [dynamic(l) for l in ngc]
        if new == ngc:
            sys.exit("%s: no G41/G42 D" % stem)
        new[0] = new[0].replace("--dialect fanuc", "--dialect linuxcnc")
        before = motion(rv.run_rs274(a.rs274, ngc, table, stem))
        after = motion(rv.run_rs274(a.rs274, new, table, stem))
        if before != after:
            sys.exit("%s: rs274 moves differently under G41.1/G42.1" % stem)
        with open(os.path.join(FOLDER, stem + ".ngc"), "w") as f:
            f.write("\n".join(new) + "\n")
        shutil.copy(os.path.join(SOURCE, stem + ".points.jsonl"), FOLDER)
    shutil.copy(os.path.join(SOURCE, "machine.toml"), FOLDER)
    print("%d programs -> %s" % (len(stems), FOLDER))


if __name__ == "__main__":
    main()
