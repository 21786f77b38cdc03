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
with TOOLS. Moves under cutter compensation get their own block's line
(comp_lines: rs274 prints a held move with the next block's number).

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


MOVES = ("rapid", "feed", "arc")


def comp_lines(ngc, events):
    """Give compensated moves their own block's line. Under G41/G42 rs274
    holds a move until it reads the next one, so its canonical call prints
    with the number of the block that released it: a move printed on line L
    belongs to the block with motion before L, but for the last move of the
    G40 block, which is that block's own."""
    motion, comp, region = [], False, {}
    for i, text in enumerate(ngc, 1):
        code = rv.strip_comments(text).upper()
        cancel = re.search(r"G\s*40(?![\d.])", code)
        if re.search(r"G\s*4[12](?![\d])", code):
            comp = True
        if comp:
            region[i] = "cancel" if cancel else "on"
        if cancel:
            comp = False
        if re.search(r"[XYZ@^]", code):
            motion.append(i)

    def before(line):
        return max(m for m in motion if m < line)

    out = []
    for k, e in enumerate(events):
        line = e.get("line")
        kind = region.get(line)
        if e["type"] in MOVES and kind:
            last = not any(f["type"] in MOVES and f.get("line") == line
                           for f in events[k + 1:])
            if not (kind == "cancel" and last):
                e = dict(e, line=before(line))
        out.append(e)
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
        events = comp_lines(ngc, events)
        rv.write_jsonl(os.path.join(FOLDER, name + ".expected.jsonl"), events)
        n += len(events)
    with open(os.path.join(FOLDER, "machine.toml"), "w") as f:
        f.write(machine_toml(TOOLS, header="linuxcnc_dialect fixtures"))
    print("%d events -> %s" % (n, FOLDER))


if __name__ == "__main__":
    main()
