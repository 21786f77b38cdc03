#!/usr/bin/env python3
"""Write tests/fixtures/linuxcnc_lathe_cycles: the moves LinuxCNC's rs274
makes for hand-written lathe-mode programs (*.ngc there: its G76 threading
cycle), for `--dialect linuxcnc-lathe`.

Each program runs through rs274 -g (lines prefixed with N<line>); its
canonical calls become vcnc's motion events in machine mm with
make_lathe_fixtures.Lathe (X a radius, START_SPEED_FEED_SYNC's value the
thread's lead_mm, moves that do not move dropped) in NAME.expected.jsonl;
the end is the program's M2. machine.toml is the built-in turning centre
starting at X0 Z0, as rs274 does. The test is
`linuxcnc_lathe_cycles_match_rs274` in crates/vcnc/tests/behaviour/fixtures.rs.

Usage: make_lathe_cycle_fixtures.py [--rs274 PATH]
"""

import argparse
import os
import shutil
import sys

import rs274_events as rv
from make_lathe_fixtures import REPO, Lathe, machine_toml

FOLDER = os.path.join(REPO, "tests", "fixtures", "linuxcnc_lathe_cycles")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rs274", default=shutil.which("rs274"))
    a = ap.parse_args()
    if not a.rs274:
        sys.exit("needs LinuxCNC's rs274: apt-get install linuxcnc-uspace")
    n = 0
    for name in sorted(f[:-4] for f in os.listdir(FOLDER) if f.endswith(".ngc")):
        with open(os.path.join(FOLDER, name + ".ngc")) as f:
            ngc = f.read().split("\n")
        if ngc[-1] != "":
            sys.exit("%s: no final newline" % name)
        ngc = ngc[:-1]
        out = rv.run_rs274(a.rs274, ngc, "", name)
        events = Lathe(name, ngc).convert(out)
        for e in events:
            if e["type"] == "end":
                e["code"] = rv.end_code(ngc, e["line"])
        rv.write_jsonl(os.path.join(FOLDER, name + ".expected.jsonl"), events)
        n += len(events)
    with open(os.path.join(FOLDER, "machine.toml"), "w") as f:
        f.write(machine_toml())
    print("%d events -> %s" % (n, FOLDER))


if __name__ == "__main__":
    main()
