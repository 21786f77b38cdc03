#!/usr/bin/env python3
"""The flattening round trip's LinuxCNC expectations
(tests/fixtures/flatten/, checked by crates/vcnc/tests/behaviour/flatten.rs).

For each program of programs.txt (path, dialect, options), on machine.toml
(G54 and G55 not zero):

  1. vcnc flattens it: `vcnc run --format gcode` (work coordinates, the
     program's units) -> NAME.flat.ngc, the very text rs274 reads;
  2. LinuxCNC's rs274 runs NAME.flat.ngc with a parameter file that holds
     the machine file's G54 and G55 (5221-5223, 5241-5243, in inches as the
     standalone interpreter reads them) and a tool table listing the tools
     it changes to (no offsets: the flattened program has none);
  3. rs274_events.py converts its canonical calls into machine coordinates
     in mm (program + G5x offset) -> NAME.rs274.jsonl.

The test compares the rs274 moves with vcnc's own moves of the original
program, and checks that vcnc still flattens the program to the committed
NAME.flat.ngc (else: run this script again and review the diff).

    tools/linuxcnc/make_flatten_fixtures.py [--vcnc target/debug/vcnc] [--rs274 rs274]
"""

import argparse
import os
import re
import subprocess
import sys
import tomllib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rs274_events as rs  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SET = os.path.join(ROOT, "tests", "fixtures", "flatten")
MM_PER_IN = 25.4


def programs():
    with open(os.path.join(SET, "programs.txt")) as f:
        for line in f:
            words = line.split()
            if words and not words[0].startswith("#"):
                yield words[0], words[1], words[2:]


def name_of(path):
    return os.path.splitext(os.path.basename(path))[0]


def var_text(machine):
    """G54 (5221..) and G55 (5241..) of the machine file, in inches."""
    lines = ["5220 1.000000"]
    for n, key in ((5221, "G54"), (5241, "G55")):
        off = machine.get("work_offsets", {}).get(key, {})
        for k, axis in enumerate("xyz"):
            lines.append("%d %.12f" % (n + k, off.get(axis, 0.0) / MM_PER_IN))
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--vcnc", default=os.path.join(ROOT, "target", "debug", "vcnc"))
    ap.add_argument("--rs274", default="rs274")
    a = ap.parse_args()
    machine_path = os.path.join(SET, "machine.toml")
    with open(machine_path, "rb") as f:
        machine = tomllib.load(f)
    for path, dialect, opts in programs():
        name = name_of(path)
        flat = subprocess.run(
            [a.vcnc, "run", "--format", "gcode", "--dialect", dialect,
             "--machine", machine_path, *opts, path],
            cwd=ROOT, capture_output=True, text=True, check=True).stdout
        with open(os.path.join(SET, name + ".flat.ngc"), "w") as f:
            f.write(flat)
        lines = flat.splitlines()
        tools = sorted({int(t) for t in re.findall(r"^T(\d+) M6", flat, re.M)})
        table = "".join("T%d P%d D0 Z0 ;\n" % (t, t) for t in tools)
        out = rs.run_rs274(a.rs274, lines, table, name, var_text(machine))
        end, cycles, m5 = rs.program_facts(lines)
        if cycles:
            raise SystemExit("%s: a flattened program has no canned cycles" % name)
        inch = "G20" in flat
        events = rs.convert(out, name, end, m5_lines=m5, inch=inch,
                            end_code=rs.end_code(lines, end),
                            start_offsets=True, exact_inch=False)
        motion = [e for e in events if e["type"] in ("rapid", "feed", "arc")]
        rs.write_jsonl(os.path.join(SET, name + ".rs274.jsonl"), motion)
        print("%s: %d moves" % (name, len(motion)))


if __name__ == "__main__":
    main()
