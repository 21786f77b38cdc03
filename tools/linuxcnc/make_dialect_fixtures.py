#!/usr/bin/env python3
"""Write tests/fixtures/linuxcnc_dialect: the expected events of the
hand-written LinuxCNC programs there (*.ngc), from LinuxCNC's own rs274.

These programs exercise what `--dialect linuxcnc` reads differently from
Fanuc — G43 without H and G41 without D (the tool in the spindle), G10 L1
(the tool table), the cycles' P in seconds, L repeats, G86's dwell, G99 at
power-on, G74/G84 tapping, G59.1-G59.3 and G61.1 — so no Fanuc spelling
(.nc) stands beside them. Each .ngc runs through rs274 -g with the tool
table TOOLS (in inches, D a diameter: rs274_events.tool_table_text) and a
fresh parameter file; its canonical calls become vcnc events
(rs274_events.py) in NAME.expected.jsonl; machine.toml is the default mill
with TOOLS.

Usage: make_dialect_fixtures.py [--rs274 PATH]
"""

import argparse
import os
import re
import shutil
import sys

import rs274_events as rv
from make_ext_fixtures import FIXTURES, machine_toml

# {tool: (length mm, radius mm)}
TOOLS = {1: (0.0, 3.0), 2: (50.0, 2.5), 3: (75.25, 4.0)}
FOLDER = os.path.join(FIXTURES, "linuxcnc_dialect")
CYCLES = ("73", "74", "81", "82", "83", "84", "85", "86", "89")


def cycle_lines(ngc):
    """{line: "G8x"} for the blocks that drill: rs274_events.program_facts'
    rule, with the tapping cycles G74 and G84 too."""
    motion = None
    out = {}
    for i, text in enumerate(ngc, 1):
        code = rv.strip_comments(text)
        for g in re.findall(r"G\s*(\d+(?:\.\d*)?)", code):
            v = float(g)
            g = str(int(v)) if v == int(v) else g
            if g in ("0", "1", "2", "3", "80") + CYCLES:
                motion = g
        if motion in CYCLES and re.search(r"[XYZ]", code) \
                and not re.search(r"G(10|28|30|53|92)(?![\d.])", code):
            out[i] = "G" + motion
    return out


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
        end, _, m5 = rv.program_facts(ngc)
        out = rv.run_rs274(a.rs274, ngc, rv.tool_table_text(TOOLS), name)
        events = rv.convert(out, name, end, cycle_lines(ngc), m5, inch=True,
                            end_code=rv.end_code(ngc, end),
                            home_lines=rv.home_lines(ngc))
        rv.write_jsonl(os.path.join(FOLDER, name + ".expected.jsonl"), events)
        n += len(events)
    with open(os.path.join(FOLDER, "machine.toml"), "w") as f:
        f.write(machine_toml(TOOLS, header="linuxcnc_dialect fixtures"))
    print("%d events -> %s" % (n, FOLDER))


if __name__ == "__main__":
    main()
