#!/usr/bin/env python3
"""Write tests/fixtures/linuxcnc_lathe_cycles: the moves LinuxCNC's rs274
makes for hand-written lathe-mode programs (*.ngc there: its G76 threading
cycle, its roughing cycles G71/G72 and their .1/.2, G70 with D and E), for
`--dialect linuxcnc-lathe`.

Each program runs through rs274 -g (lines prefixed with N<line>); its
canonical calls become vcnc's motion events in machine mm with
make_lathe_fixtures.Lathe (X a radius, START_SPEED_FEED_SYNC's value the
thread's lead_mm, moves that do not move dropped) in NAME.expected.jsonl;
the end is the program's M2. rs274 reports the moves of G70-G72 with the
line of their profile subroutine's `endsub`; they get the cycle block's
line (`Cycles`), as vcnc gives them (these programs' subroutines are not
O100, which make_lathe_fixtures.Lathe reads as a Fanuc G70's profile, one
move per block). machine.toml is the built-in turning centre
starting at X0 Z0, as rs274 does. The test is
`linuxcnc_lathe_cycles_match_rs274` in crates/vcnc/tests/behaviour/fixtures.rs.

Usage: make_lathe_cycle_fixtures.py [--rs274 PATH]
"""

import argparse
import os
import re
import shutil
import sys

import rs274_events as rv
from make_lathe_fixtures import REPO, Lathe, machine_toml

FOLDER = os.path.join(REPO, "tests", "fixtures", "linuxcnc_lathe_cycles")
ENDSUB = re.compile(r"O\d+\s+ENDSUB", re.I)


class Cycles(Lathe):
    """Lathe, with the moves reported on a subroutine's `endsub` line
    given the line of the cycle block that ran them: the last line outside
    an `endsub` that rs274 reported anything for."""

    def __init__(self, name, ngc):
        super().__init__(name, ngc)
        self.g70 = {}    # no Fanuc-style G70 rewriting: the cycle's line
        self.endsubs = {i for i, text in enumerate(ngc, 1)
                        if ENDSUB.search(rv.strip_comments(text))}
        self.cycle_line = None

    def call(self, call, args):
        if self.line not in self.endsubs:
            self.cycle_line = self.line
            return super().call(call, args)
        line, self.line = self.line, self.cycle_line
        try:
            return super().call(call, args)
        finally:
            self.line = line


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
        events = Cycles(name, ngc).convert(out)
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
